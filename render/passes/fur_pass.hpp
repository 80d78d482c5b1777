#pragma once
// Shell-and-fin fur from one photograph: Ukaji et al.'s shells (render/luts/fur_shells.hpp,
// docs/design.md#sources) with Lengyel, Praun, Finkelstein & Hoppe's fins ("Real-time fur over
// arbitrary surfaces", I3D 2001) and Kajiya-Kay lighting. Shaders: shaders/fur_common.glsl,
// fur_shell.{vert,frag}, fur_fin.{vert,frag}.
//
// Memory. The photo is uploaded once, as an sRGB texture with mips; the mesh once (one buffer
// used both as vertex buffer and, for the fins, as a storage buffer). Per frame only a uniform
// block (the thresholds I(0 … 64) whatever N is: Ukaji et al. §3.3) and the fin edge list change.
// GPU memory therefore does not depend on the layer count N.
//
// Shells. Two draws of the mesh, instance i = layer N − i: the skin (instance 0) first, with a
// pipeline that never discards (so lavapipe tests depth before shading), its depth then hiding
// what lies behind the body; then the shells, instances 1 … N − 1, in one instanced draw that
// alpha-tests. Each vertex is pushed out to s = 1 − n/N of h_b above the
// skin (eq. 3): along its world normal n, bent towards its lean λ (a comb direction projected
// on the surface, plus per-vertex leans from simulated guides: setLeans) as a fibre would,
// p + h_b·(s·n + s²·λ). A shell keeps the pixels its FurCoverage says and
// discards the rest; kept fragments are opaque and write depth, so the layers composite
// correctly in any order, with no sorting and no blending. Layer N (the skin) keeps every pixel:
// it is the body the fur grows on. Back faces are culled only when the look says the mesh is
// single-sided (FurLook::doubleSided): meshes come with either winding. The fur is lit per vertex
// (its light varies over a shell as slowly as the normals do), so a shell's fragments, N of them
// over every pixel of the body, only read the photo.
//
// Fins. Lengyel et al. draw fins on the edges near the silhouette, where shells seen edge-on
// leave gaps. Here a fin stands on every edge whose two faces turn opposite ways to the eye,
// (n₁·v)(n₂·v) ≤ 0 with v from the edge's midpoint to the eye (object space, face normals from
// the positions), and on boundary edges (one face). They are found on the CPU per frame
// (MeshEdges::findSilhouette: deterministic, a few ms for the 69k-triangle bunny), written as
// vertex-index pairs to a host-visible buffer sized for every edge of the mesh, and drawn as one
// non-indexed draw of 6 vertices per fin that reads the mesh buffer (vertex pulling). A fin goes
// from the skin to the top shell along the vertex normals, textured from the photo by the same
// luminance → height map as the shells (shaders/fur_fin.frag).
//
// Lay. By default the photo is sampled by the mesh's uvs, so the way its hairs lie follows the
// uv layout. With a fur-direction field (FurLook::layDirection, model space) each vertex takes
// its photo coordinates from a frame of its own instead: f, the field projected on the surface
// (any tangent where the field runs along the normal), and b = n × f; the photo's coordinates
// are (p·b, p·f) × repeats per metre × the model's scale, so the photo's top-to-bottom axis (and
// the hairs drawn along it) follow the field over the whole surface, with no uv seams. Where the
// field turns, the photo shears; that is the price of a projection without a parameterization.
//
// Lighting (shaders/fur_common.glsl): Kajiya & Kay 1989 diffuse and specular for fibres along
// the normal tilted by FurLook::layAngle (averaged over four azimuths), normalised so that light
// along the normal gives back the photo's colour; a half-Lambert term of the normal darkens the
// side of the body away from the light; one directional light plus ambient.
//
// Shadows. The pass receives the frame's hair shadows (render/passes/hair_shadow_pass.hpp: the opacity
// maps of the first light) on the shells and fins, and casts its own: shadowStrands() holds one
// two-point strand per vertex, from the skin to the fur's top (leans included), in world space,
// rewritten by update(), for the renderer to register as a shadow caster. The fur then shadows
// itself through the same map (the side of the body away from the light lies behind the fur
// facing it) and shadows the hair and skin around it.
//
// Frames in flight: one. update() writes the uniform block and the fin buffer that the draw
// reads; call it only when no earlier draw is still running (the Renderer waits for each frame).
//
// Units: metres, radians.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/environment/spherical_harmonics.hpp"
#include "render/frame.hpp"
#include "render/luts/fur_shells.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/passes/skinning_pass.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// Which pixels of the photo a shell shows.
enum class FurCoverage : std::uint32_t {
  /// Ukaji et al. as written: layer n shows I(n) ≤ I < I(n−1), each pixel in exactly one shell,
  /// the one where its fur ends. Seen from above: the photo; from the side: floating specks.
  kBands = 0,
  /// Layer n shows I ≥ I(n): every pixel whose fur reaches at least that high, i.e. each pixel
  /// is a column of fur from the skin to its height (Lengyel's shells are cross-sections of a
  /// volume of hair). Same view from above; no gaps between shells from the side.
  kStrands = 1,
};

/// What the pass draws into and how.
struct FurPassSettings {
  vk::Format colorFormat = vk::Format::eR16G16B16A16Sfloat;
  vk::Format depthFormat = vk::Format::eD32Sfloat;  ///< required: the shells composite by depth
  vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  FurCoverage coverage = FurCoverage::kStrands;
  bool fins = true;
};

/// Appearance constants beyond the photo.
struct FurLook {
  float layAngle = 0.6f;           ///< radians between the fur and the normal (Kajiya-Kay tangent)
  float specularExponent = 40.0f;  ///< Kajiya-Kay p
  float specularStrength = 0.08f;  ///< scales the specular term, × light radiance
  glm::vec3 tint{1.0f};            ///< linear RGB multiplying the photo's colour (a grey photo made green)
  /// Where the fur's tips lean, world space, in units of h_b (e.g. (0, −0.5, 0): combed down by
  /// half its height): projected on each vertex's tangent plane and added to its lean (setLeans).
  glm::vec3 comb{0.0f};
  /// The fur-direction field, model space; zero: the photo by the mesh's uvs ("Lay" above).
  glm::vec3 layDirection{0.0f};
  float layRepeatsPerMetre = 30.0f;  ///< with a layDirection: photo repeats per metre
  /// False: the skin and the shells cull the faces turned away from the eye (counter-clockwise
  /// faces are the front ones, as glTF's), for a closed mesh, whose far side they would otherwise
  /// draw in full under the near one; the fins still stand on its silhouette.
  bool doubleSided = true;
  /// Fewer shells where the fur is short on screen (FurParameters::pixelsPerLayer); 0: all.
  float pixelsPerLayer = 1.0f;
};

/// One furred object as seen this frame.
struct FurView {
  glm::mat4 model{1.0f};           ///< object → world, metres
  glm::mat4 viewProjection{1.0f};  ///< world → clip (Vulkan, depth 0..1)
  /// World eye: w = 1 a position (perspective); w = 0 the unit direction towards the viewer
  /// (orthographic).
  glm::vec4 eye{0.0f, 0.0f, 1.0f, 1.0f};
  vk::Extent2D extent{};
  DirectionalLight light;
  glm::vec3 ambient{0.03f};
  /// The environment's irradiance over π (EnvironmentPass::irradianceOverPi); zeros: none. Each
  /// fibre takes it averaged round its side.
  SphericalHarmonics9 environment{};
  FurLook look;
};

/// The edges of a triangle mesh with the normals of their faces, for finding silhouettes.
class MeshEdges {
public:
  struct Edge {
    std::uint32_t a = 0, b = 0;  ///< vertex indices, as in the edge's first face
    glm::vec3 midpoint{0.0f};
    glm::vec3 normalA{0.0f};  ///< unit normal of the first face
    glm::vec3 normalB{0.0f};  ///< of the second; equal to normalA on a boundary edge
    bool boundary = false;    ///< only one face
    std::uint32_t faceA = 0;  ///< triangle (index into the triangle list / 3) of normalA
    std::uint32_t faceB = 0;  ///< of normalB
  };

  /// Edges of `indices` (a triangle list) with two faces, or one (boundary); edges of three or
  /// more faces (non-manifold) and degenerate triangles are left out. Vertices at the same
  /// position are one vertex here, so uv seams are not boundaries. Errors: an index out of
  /// range or a count not a multiple of 3.
  [[nodiscard]] static Result<MeshEdges> build(std::span<const glm::vec3> positions,
                                               std::span<const std::uint32_t> indices);

  /// Moves the edges' midpoints and face normals to `positions` (the same vertices, deformed): a
  /// skinned mesh's pose. A face that has collapsed keeps its previous normal. Errors: a count
  /// that is not the mesh's.
  [[nodiscard]] Result<void> reshape(std::span<const glm::vec3> positions);

  /// Appends to `out` the vertex pairs of the silhouette edges seen from `eye` (object space; w
  /// as FurView::eye): (n_A·v)(n_B·v) ≤ 0, v = eye − w·midpoint, and boundary edges. Clears `out`
  /// first; allocates only when it grows.
  void findSilhouette(const glm::vec4& eye, std::vector<glm::uvec2>& out) const;

  [[nodiscard]] std::span<const Edge> edges() const { return edges_; }

private:
  std::vector<Edge> edges_;
  std::vector<std::uint32_t> triangles_;  ///< the triangle list built from
  std::size_t vertexCount_ = 0;
};

/// The tangent the fur's shadow strands tilt along at a vertex of unit normal `normal`:
/// normalize(n × x), or n × y where n is within 26° of x.
[[nodiscard]] glm::vec3 furShadowTangent(const glm::vec3& normal);

class FurPass {
public:
  /// Uploads `photo` (8-bit sRGB) and builds the pipelines. `shadows` (which must outlive the
  /// pass) are the hair shadows the fur receives; none: unshadowed. Errors: a photo the shell
  /// model refuses (FurShellModel::fromPhoto), no depth format, or a Vulkan failure.
  [[nodiscard]] static Result<std::unique_ptr<FurPass>> create(const Device& device, const FurPassSettings& settings,
                                                               const TextureData& photo,
                                                               const FurShellSettings& shells = {},
                                                               const HairShadowPass* shadows = nullptr);

  FurPass(const FurPass&) = delete;
  FurPass& operator=(const FurPass&) = delete;

  /// Uploads the mesh the fur grows on (object space; normals and uvs required); replaces the
  /// previous one. Errors (nothing changed): missing normals or uvs, bad indices.
  [[nodiscard]] Result<void> setMesh(const MeshData& mesh);

  /// The mesh's current shape, object space, one position and unit normal per vertex (xyz; w is
  /// ignored): the pose of a mesh deformed on the GPU (a skinned mesh), for the work done on the
  /// CPU, the fins' silhouette test and the shadow strands, from the next update() on. The draws
  /// read the vertex buffer whatever wrote it (vertexTarget). Errors: a count that is not the
  /// mesh's, a non-finite value.
  [[nodiscard]] Result<void> setPose(std::span<const glm::vec4> positions, std::span<const glm::vec4> normals);

  /// Where a SkinningPass writes the deformed positions and normals for the shells and fins to
  /// draw (after setMesh; the buffer changes with the next setMesh).
  [[nodiscard]] SkinnedVertexTarget vertexTarget() const;

  /// Per-vertex lean of the fur's tips (world space, in units of h_b, e.g. from simulated guide
  /// strands), one per vertex of the mesh; zero after setMesh. A shell at height s·h_b sits at
  /// p + h_b·(s·n + s²·lean): fibres leave the skin along the normal and bend towards the lean.
  /// Takes effect at the next draw. Errors: a count that is not the mesh's, a non-finite value.
  [[nodiscard]] Result<void> setLeans(std::span<const glm::vec3> leans);

  /// Changes N and h_b (same photo, same I_min and I_max); no GPU memory changes. Errors as
  /// FurShellModel::create.
  [[nodiscard]] Result<void> setShells(std::uint32_t layers, float thickness);

  /// Writes the view, the light and the thresholds, and finds this frame's fins. Errors: an
  /// empty extent or a non-finite matrix.
  [[nodiscard]] Result<void> update(const FurView& view);

  /// Re-reads the hair shadows' maps: their descriptors, and the pipelines when the number of
  /// maps or their mode changed (after HairShadowPass::setGrooms, or a map's first bounds).
  void refreshShadows();

  /// The hair shadows' uniforms of this frame (HairShadowPass::uniforms after its record()), for
  /// the next draw.
  void setShadowUniforms(const HairShadowUniforms& uniforms);

  /// The fur as a shadow caster: one strand of two points per mesh vertex, world space as of the
  /// last update(); a host-visible storage buffer. A strand runs from the skin point to the top
  /// of its fur, p + h_b·(n + lean), tilted across the column it stands for: both ends moved
  /// half a mean edge (× the model's scale) along furShadowTangent(n), the root back, the tip
  /// forward. Straight along n it would show the light overhead a dot, and cast nothing.
  [[nodiscard]] OpacityShadowStrands shadowStrands() const {
    return {.positions = &shadowStrands_, .strandCount = vertexCount_, .verticesPerStrand = 2};
  }
  /// Bounds of shadowStrands() as of the last update().
  [[nodiscard]] const BoundingSphere& shadowBounds() const { return shadowBounds_; }
  /// Mean edge length of the mesh, object space.
  [[nodiscard]] float meanEdgeLength() const { return meanEdgeLength_; }
  /// The width a shadow strand stands for, metres, as of the last update(): one mean edge at
  /// the model's scale (after setMesh alone, at scale 1).
  [[nodiscard]] float shadowColumnWidth() const { return shadowColumnWidth_; }
  /// Texels per side of a shadow map whose texel spans about one mean edge of the mesh (the
  /// square root of its area over the mean edge, rounded up to a multiple of 8; at least 16).
  /// The strands, one per vertex, then fill every texel the fur covers: in a finer map they
  /// would stand apart and shadow the fur in a lattice of lines.
  [[nodiscard]] std::uint32_t shadowResolution() const { return shadowResolution_; }

  /// Records the shells and fins inside a dynamic rendering scope with FurPassSettings' formats
  /// (viewport and scissor set to the view's extent). Nothing before setMesh and update.
  void draw(const vk::raii::CommandBuffer& commands) const;

  [[nodiscard]] const FurShellModel& model() const { return model_; }
  /// Shells the next draw draws, the skin included (set by update): model().layers(), or fewer
  /// where the fur is short on screen (FurLook::pixelsPerLayer).
  [[nodiscard]] std::uint32_t drawnLayers() const { return drawnLayers_; }
  /// Fins drawn by the next draw (set by update).
  [[nodiscard]] std::uint32_t finCount() const { return finCount_; }
  /// The vertex pairs of those fins.
  [[nodiscard]] std::span<const glm::uvec2> fins() const { return fins_; }

private:
  FurPass(const Device& device, const FurPassSettings& settings, const TextureData& photo, FurShellModel model,
          const HairShadowPass* shadows);
  void buildPipelines();
  /// Writes shadowStrands_ and shadowBounds_ for this model matrix and comb.
  void writeShadowStrands(const glm::mat4& model, const glm::vec3& comb);
  /// The fur's height in pixels where it comes nearest the eye: on furBounds_, as of the last
  /// writeShadowStrands.
  [[nodiscard]] float furHeightInPixels(const FurView& view) const;

  const Device* device_;
  std::unique_ptr<HairShadowPass> ownShadows_;  ///< empty maps, when the caller gives none
  const HairShadowPass* shadows_;
  SpecializationConstants shadowConstants_;  ///< of the current pipelines
  FurPassSettings settings_;
  FurShellModel model_;
  vk::Extent2D extent_{};
  Image photo_;
  vk::raii::Sampler sampler_{nullptr};
  vk::raii::DescriptorSetLayout setLayout_{nullptr};
  Pipeline skinPipeline_;   ///< layer N alone, no discard
  Pipeline shellPipeline_;  ///< layers N − 1 … 1, alpha-tested
  Pipeline finPipeline_;
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet set_{nullptr};
  Buffer uniforms_;
  Buffer vertices_;  ///< 8 floats per vertex: position, normal, uv
  Buffer indices_;
  Buffer finEdges_;       ///< uvec2 per edge of the mesh, host-visible
  Buffer leans_;          ///< vec4 per vertex, host-visible (setLeans)
  Buffer shadowStrands_;  ///< two vec4 per vertex, host-visible
  BoundingSphere shadowBounds_{};
  float meanEdgeLength_ = 0.0f;
  float shadowColumnWidth_ = 0.0f;
  std::uint32_t shadowResolution_ = 16;
  std::vector<glm::vec3> meshPositions_;  ///< object space, for the shadow strands
  std::vector<glm::vec3> meshNormals_;
  std::vector<glm::vec3> vertexLeans_;
  std::uint32_t vertexCount_ = 0;
  std::uint32_t indexCount_ = 0;
  MeshEdges edges_;
  std::vector<glm::uvec2> fins_;
  std::uint32_t finCount_ = 0;
  std::uint32_t drawnLayers_ = 0;  ///< the shells' N as of the last update (drawnLayers)
  /// The tight sphere around the shadow strands (shadowBounds_ is the looser one the shadow
  /// map's texel size was chosen for).
  BoundingSphere furBounds_{};
  vk::CullModeFlags cullMode_ = vk::CullModeFlagBits::eNone;  ///< the skin's and shells', as of the last update
  vk::FrontFace frontFace_ = vk::FrontFace::eCounterClockwise;
  bool updated_ = false;
};

}  // namespace mane::render
