#pragma once
// Dense (rendered) strands interpolated from simulated guide strands.
//
// Two schemes, chosen per groom:
// - Single guide (Nalu, NVIDIA 2005: 762 simulated control hairs drive 4,095 rendered ones;
//   AMD TressFX `UpdateFollowHairVertices`): every dense strand copies one guide and adds a
//   per-strand root offset. TressFX grows the offset towards the tip (tip separation); here the
//   offset shrinks towards the tip instead when the strand is clumped.
// - Multi guide (Unreal Engine groom, `HairStrandsInterpolation`: up to 3 guides with
//   barycentric weights from a triangle of guide roots on the scalp): every dense strand is the
//   weighted sum of three guides whose roots surround its root.
// Both add per-strand random variation (length scale, tip jitter) and clumping (the tip pulled
// towards the strand's primary guide).
//
// The layout (which guides, weights, offsets; `DenseStrandLayout` in common/strand_layout.hpp,
// which the renderer uploads as it is) is built once from the guides' rest shape and a seed,
// deterministically (splitmix64, exact IEEE operations only). Interpolation then runs every
// frame on the current guide positions. It is the CPU reference of the GPU interpolation pass:
// the exact formula is below, and a shader must reproduce it within 1e-5 relative.
//
// ## The formula (evaluated in float, left to right, no fused multiply-add)
//
// Inputs: guide positions `G[g][v]` (guide g, vertex v, `Ng` vertices per guide, metres, any
// frame — the result is in the same frame), and for dense strand s its `DenseStrand` entry:
// K guides `g[k]` with weights `w[k]`, `vertexScale`, `clump` c, `rootOffset` o, `tipJitter` j.
// `Nd` = vertices per dense strand. `dot(a, b)` = a.x*b.x + a.y*b.y + a.z*b.z;
// `cross(a, b)` = (a.y*b.z − a.z*b.y, a.z*b.x − a.x*b.z, a.x*b.y − a.y*b.x);
// `normalize(a)` = a / sqrt(dot(a, a)) (one division per component).
//
// 1. Per strand: the frame of the primary guide p = g[0] (its partners a, b from
//    `guideFrames[p]`), built from guide roots only. Roots are rigidly attached to the head, so
//    the frame turns with the head and the offsets follow head rotation:
//        e1 = normalize(G[a][0] − G[p][0])
//        n  = normalize(cross(e1, G[b][0] − G[p][0]))     (points to the hair side of the scalp)
//        e2 = cross(n, e1)
//    A guide whose partners equal itself (no usable neighbours) uses the fixed axes
//    e1 = (1,0,0), e2 = (0,1,0), n = (0,0,1): its offsets do not turn with the head.
//    The root offset and tip jitter in that frame:
//        O = (o.x * e1 + o.y * e2) + o.z * n;   J = (j.x * e1 + j.y * e2) + j.z * n
// 2. For each dense vertex i in [0, Nd):
//        u  = float(i) * vertexScale                 guide-vertex coordinate, u ≤ Ng − 1
//        v  = min(uint(u), Ng − 2);  f = u − float(v)
//    L_k, the point at u along guide g[k] (k < K), by the layout's curve:
//      linear:      L_k = (1 − f) * G[g[k]][v] + f * G[g[k]][v + 1]
//      Catmull-Rom: the uniform spline through the guide's vertices (it passes through each
//                   of them and reproduces evenly spaced points on a line), with
//                   f2 = f * f,  f3 = f2 * f and the weights
//                     a = 0.5 * ((2 * f2 − f3) − f)       b = 0.5 * ((3 * f3 − 5 * f2) + 2)
//                     c = 0.5 * ((4 * f2 − 3 * f3) + f)   d = 0.5 * (f3 − f2)
//                   L_k = ((a * P0 + b * P1) + c * P2) + d * P3,  P0..P3 = G[g[k]][v − 1 .. v + 2],
//                   the guide extended past its ends by the parabola through its last three
//                   vertices, so that the end segments bend as their neighbours do:
//                     G[−1] := 3 * (G[0] − G[1]) + G[2],  G[Ng] := 3 * (G[Ng−1] − G[Ng−2]) + G[Ng−3],
//                   or, on a guide of 2 vertices, the straight line: G[−1] := G[0] + (G[0] − G[1]),
//                   G[2] := G[1] + (G[1] − G[0]).
//                   At f = 0 and f = 1 the weights are exactly (0, 1, 0, 0) and (0, 0, 1, 0).
//        B  = w[0] * L_0;  B = B + w[1] * L_1;  B = B + w[2] * L_2  (only terms with k < K)
//        t  = float(i) / float(Nd − 1)               0 at the root, 1 at the tip
//        h  = c * t;  q = 1 − h
//        C  = B + h * (L_0 − B)                       clumping towards the primary guide
//        P[s][i] = C + q * (O + t * J)
//    With K = 1 and w[0] = 1, B = L_0 exactly, so a single-guide strand is its guide plus the
//    offset O + t·J scaled by (1 − c·t); with c = 1 the tip lies exactly on the guide at u.
//    A strand with curl radius r > 0 or frizz f > 0 (`curlRadius`, `curlTurns` T, `curlPhase` φ,
//    `frizz`) then adds, with G_p = G[g[0]]:
//        T_k = G_p[min(k + 1, Ng − 1)] − G_p[max(k, 1) − 1]     the guide's way at its vertex k
//        D  = (1 − f) * T_v + f * T_{v+1};  d = dot(D, D) > 0 ? normalize(D) : n
//                                            (turning smoothly past the guide's vertices)
//      the side a carried down the strand from vertex to vertex along the primary guide's curve by
//      double reflection (Wang, Jüttler, Zheng & Liu 2008: a rotation-minimising frame, which
//      neither spins where the guide turns towards n nor depends on the guide's vertices):
//        i = 0:  A = cross(d, n);  a = dot(A, A) > 0 ? normalize(A) : e1
//        i > 0:  with x = L_0 here and x', d', a' those of vertex i − 1:
//          v1 = x − x';  c1 = dot(v1, v1)
//          aL = c1 > 0 ? a' − ((2 * dot(v1, a')) / c1) * v1 : a'
//          dL = c1 > 0 ? d' − ((2 * dot(v1, d')) / c1) * v1 : d'
//          v2 = d − dL;  c2 = dot(v2, v2)
//          R  = c2 > 0 ? aL − ((2 * dot(v2, aL)) / c2) * v2 : aL
//          A  = R − dot(R, d) * d;  a = dot(A, A) > 0 ? normalize(A) : a'
//        b  = cross(d, a)
//        (co, si) = cosSinTurns(φ + T * t)
//        R  = r * min(4 * t, 1)                      the helix widens over the first quarter
//        W  = (co * R) * a + (si * R) * b
//        x_k = float(hash(3 * (s * Nd + i) + k) >> 8) * 2^−23 − 1, k = 0, 1, 2   (uint32, wrapping)
//        F  = (f * t) * ((x_0 * e1 + x_1 * e2) + x_2 * n)
//        P[s][i] = P[s][i] + (W + F)
//    where hash(x) is Wellons' lowbias32 (x ^= x >> 16; x *= 0x7feb352d; x ^= x >> 15;
//    x *= 0x846ca68b; x ^= x >> 16) and cosSinTurns(w) the cosine and sine of 2π·w by exact
//    operations only: w = w − floor(w); y = 4 * w; k = floor(y + 0.5); x = (y − k) * 1.57079637;
//    x2 = x * x;
//        S = x * (1 + x2 * (−0.166666672 + x2 * (0.00833333377 + x2 * (−0.000198412701 + x2 * 2.75573188e−06))))
//        C = 1 + x2 * (−0.5 + x2 * (0.0416666679 + x2 * (−0.00138888892 + x2 * 2.48015876e−05)))
//    (Taylor to x⁹ and x⁸ on [−π/4, π/4], within 4e-7 of the sine and cosine), turned by the
//    quadrant k mod 4: (C, S), (−S, C), (−C, −S), (S, −C).
// 3. Tangents (optional), unit vectors root → tip, from the dense positions P:
//        T[i] = normalize(P[i + 1] − P[i − 1]), with P[−1] := P[0] and P[Nd] := P[Nd − 1];
//    T[i] = (0, 0, 0) where those two points coincide.
//
// Output is flat, strand-major: vertex i of dense strand s is element s·Nd + i.
// Units: metres; angles none; all positions in the frame of the guide positions given.

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "common/strand_layout.hpp"
#include "physics/task_runner.hpp"

namespace mane::physics {

/// How dense strands follow their guides.
enum class GuideBlend : std::uint32_t {
  kSingle = 0,       ///< one guide plus a root offset (Nalu / TressFX follow hairs)
  kBarycentric = 1,  ///< three guides whose roots form a triangle around the root (Unreal groom)
};

/// Parameters of a dense groom layout. Lengths in metres.
struct DenseGroomSettings {
  std::uint64_t seed = 1;          ///< PRNG seed; equal seeds give bit-identical layouts
  std::size_t strandCount = 4095;  ///< dense strands to generate (≥ 1); Nalu: 4,095
  /// Vertices per dense strand (≥ 2), or 0 for the guides' vertex count.
  std::size_t verticesPerStrand = 0;
  /// How dense vertices follow each guide between its vertices. A guide of a few particles
  /// turns by tens of degrees at some of them; the spline spreads each turn over the dense
  /// vertices around it, so more dense than guide vertices give a smooth strand.
  StrandCurve curve = StrandCurve::kCatmullRom;
  GuideBlend blend = GuideBlend::kSingle;
  /// Single guide: root offsets lie in a disc in the guide root's tangent plane (e1, e2) whose
  /// radius is this fraction of the distance from the guide root to its nearest other guide
  /// root; in [0, 4]. Barycentric strands get no root offset (their root is already spread).
  float rootSpread = 0.5f;
  /// Each strand is shortened by a random factor in [1 − lengthVariation, 1]; in [0, 1).
  float lengthVariation = 0.1f;
  float clump = 0.3f;           ///< mean clump factor c in [0, 1]: 1 puts the tip on the guide
  float clumpVariation = 0.1f;  ///< c varies uniformly by ± this, clamped to [0, 1]; ≥ 0
  /// The clump's radial profile, an exponent p in [0, 8]: a clump's strands lie round its guide
  /// at the tip with a density ∝ (1 − ρ²)^p over the radius ρ it reaches, gathered towards the
  /// guide; 0 keeps the root's even spread, only shrunk. A strand's clump factor carries it (see
  /// `clumpProfileScale`), so the interpolation's formula is the same either way.
  float clumpProfile = 0.0f;
  /// Largest tip jitter, metres (≥ 0): a per-strand random vector in the ball of this radius,
  /// added in proportion to t (0 at the root, full at the tip) before clumping.
  float tipJitter = 0.002f;
  /// Curl: each strand winds round its guides in a helix of this radius, metres in [0, 0.05]
  /// (0: straight), one turn per `curlPeriod` metres of its length.
  float curlRadius = 0.0f;
  float curlPeriod = 0.02f;    ///< metres of strand per turn, in [0.001, 10]
  float curlVariation = 0.3f;  ///< each strand's radius varies uniformly by ± this share, [0, 1]
  /// Frizz: each dense vertex strays by a random vector in the cube of this half-side, metres in
  /// [0, 0.01], in proportion to t (none at the root).
  float frizz = 0.0f;
  /// Barycentric: the triangle's two other corners are picked among this many nearest guide
  /// roots of the strand's home guide; in [2, 8].
  std::size_t neighbourCandidates = 4;
  /// Barycentric: only candidates whose rest guide leaves its root (its first segment) within
  /// the angle of this cosine of the home guide's are blended (by default less than 90° apart),
  /// so that no strand is the average of guides combed apart (either side of a parting, or a
  /// crown's whorl); in [−1, 1], −1 blends any.
  float minBlendCosine = 0.0f;
};

/// How much of its root offset a strand keeps at a clumped tip, relative to an evenly spread
/// clump, under the radial profile of exponent `profile` (DenseGroomSettings::clumpProfile):
/// ρ'/ρ, where ρ in [0, 1] is the strand's root radius as a share of its clump's and ρ' the
/// radius at which the profile puts the same share of the strands. The roots are spread evenly
/// over the clump's area (ρ² is uniform: a disc round the guide, or 1 − w₀ in a guide triangle),
/// so with ρ'² = 1 − (1 − ρ²)^(1/(p+1)), the inverse of the profile's share within ρ',
/// 1 − (1 − ρ'²)^(p+1), the tips' density is ∝ (1 − ρ'²)^p. A strand then takes the clump factor
/// 1 − (1 − c)·ρ'/ρ. Exact operations only (physics/detail/portable_math.hpp).
[[nodiscard]] float clumpProfileScale(float rootRadius, float profile);

/// Builds a dense groom layout from guide strands at rest (points root first, metres, in any
/// frame: the layout is invariant under rigid motions of the guides). All guides must have the
/// same number of points (`resampleGroom` in strand_resample.hpp makes them so); guide roots
/// should lie on the scalp.
///
/// Every dense strand s has a home guide ⌊s·guideCount / strandCount⌋: each guide is home to the
/// same number of strands (±1), consecutive ones. Single guide: the strand follows its home
/// guide. Barycentric: the home guide is the triangle's first corner, the two other
/// corners are picked at random among its nearest guide roots, and the weights are a uniform
/// random point of that triangle; strands whose home has no non-degenerate triangle fall back to
/// the single guide. Fails, naming the guide or setting, on an empty groom, guides with fewer
/// than 2 or unequal point counts, non-finite points, or settings out of range.
[[nodiscard]] Result<DenseStrandLayout> buildDenseStrandLayout(std::span<const std::vector<glm::vec3>> restGuides,
                                                              const DenseGroomSettings& settings);

/// Everything a `DenseStrandInterpolator` is made from. Plain data.
struct InterpolationSettings {
  /// The guide strands at rest, points root first (metres, any frame), all with the same number
  /// of points (≥ 2): `resampleGroom` in strand_resample.hpp makes them so.
  std::vector<std::vector<glm::vec3>> restGuides;
  /// How the dense strands are laid out around the guides.
  DenseGroomSettings groom;
  /// What runs `interpolate`'s parallel loop (task_runner.hpp); by default the built-in pool with
  /// one worker per hardware thread. The output does not depend on it.
  TaskRunner tasks = defaultTaskRunner();
};

/// Dense strands that follow a set of guides: a layout built once (`buildDenseStrandLayout`)
/// and the task runner that fills the dense strands every frame.
class DenseStrandInterpolator {
public:
  /// Builds the layout from `settings.restGuides` and `settings.groom`. Fails with a message that
  /// starts with the settings field at fault (restGuides, groom, tasks) and names the guide or
  /// setting.
  [[nodiscard]] static Result<DenseStrandInterpolator> create(const InterpolationSettings& settings);

  /// Fills `positions` (and `tangents` when not empty) for the current guide positions:
  /// `interpolateDenseStrands` with this layout, its loop run by `taskRunner()` over fixed
  /// ranges of dense strands. Fails as that function does, or when the task runner fails (the
  /// output is then completed on the calling thread, so it is still right).
  [[nodiscard]] Result<void> interpolate(std::span<const glm::vec3> guidePositions, std::span<glm::vec3> positions,
                                         std::span<glm::vec3> tangents = {}) const;

  /// The layout (what the renderer uploads).
  [[nodiscard]] const DenseStrandLayout& layout() const noexcept { return layout_; }
  /// Replaces the task runner; fails, changing nothing, when `validateTaskRunner` rejects it.
  [[nodiscard]] Result<void> setTaskRunner(TaskRunner tasks);
  /// The task runner `interpolate` uses.
  [[nodiscard]] const TaskRunner& taskRunner() const noexcept { return tasks_; }

private:
  DenseStrandInterpolator(DenseStrandLayout layout, TaskRunner tasks)
      : layout_(std::move(layout)), tasks_(std::move(tasks)) {}
  DenseStrandLayout layout_;
  TaskRunner tasks_;
};

/// Fills `positions` (metres, strand-major: layout.vertexTotal() elements) with the dense
/// strands for the current guide positions, by the formula at the top of this header, and,
/// when `tangents` is not empty (then also vertexTotal() elements), the unit tangents.
///
/// `guidePositions` holds guideCount × guideVertexCount points, guide after guide, root first
/// (for a `HairSystem` whose strands all have that many particles this is exactly
/// `particles().positions`). The tasks of `tasks` fill fixed contiguous ranges of dense strands
/// (task t the t-th of `concurrency` ranges); each strand is computed alone, so the output is
/// bit-identical whatever runs the tasks.
///
/// Fails, writing nothing, when the layout is invalid or empty (`validateStrandLayout`), the
/// guide or output sizes do not match it, a guide position is NaN or infinite (naming guide and
/// vertex), or a guide's frame partners have collapsed onto its root (`validateGuidePositions`);
/// fails after writing everything when the task runner fails (see task_runner.hpp).
[[nodiscard]] Result<void> interpolateDenseStrands(std::span<const glm::vec3> guidePositions,
                                                   const DenseStrandLayout& layout, std::span<glm::vec3> positions,
                                                   std::span<glm::vec3> tangents, const TaskRunner& tasks);

/// Shorthand for a caller that counts workers: the above on `builtInTaskRunner(threads)` (0
/// counts as 1).
[[nodiscard]] Result<void> interpolateDenseStrands(std::span<const glm::vec3> guidePositions,
                                                   const DenseStrandLayout& layout, std::span<glm::vec3> positions,
                                                   std::span<glm::vec3> tangents = {}, unsigned threads = 1);

}  // namespace mane::physics
