#pragma once
// The scene description: what a JSON scene file (scenes/*.json, format in scenes/README.md)
// holds once validated. Plain data; assets are referenced by manifest name, not loaded.

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"
#include "common/strand_layout.hpp"
#include "physics/colliders.hpp"
#include "physics/groom_drape.hpp"
#include "physics/floating_debris.hpp"
#include "physics/interpolation.hpp"
#include "physics/ocean_waves.hpp"
#include "physics/skinning.hpp"
#include "render/frame.hpp"
#include "render/hair_data.hpp"

namespace mane::scenes {

/// Image size of the rendered output, in pixels.
struct OutputSettings {
  int width = 1280;
  int height = 720;
};

/// A turn of the camera round its target, about the up axis through it, eased in and out: the
/// angle at time t is degrees · (1 − cos(π·min(t/seconds, 1)))/2, counter-clockwise seen from
/// above for positive degrees.
struct CameraOrbit {
  float degrees = 0.0f;  ///< the whole turn, in [−3600, 3600]
  float seconds = 1.0f;  ///< how long it takes, > 0
};

/// A perspective camera; positions in metres.
struct Camera {
  glm::vec3 position{0.0f, 0.0f, 3.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float verticalFovDegrees = 40.0f;  ///< full vertical field of view, degrees, in (0, 180)
  float nearPlane = 0.05f;           ///< metres, > 0
  float farPlane = 100.0f;           ///< metres, > nearPlane
  std::optional<CameraOrbit> orbit;  ///< none: the camera stays where it is
};

/// Where `camera` is at `seconds` into the scene: its position turned by its orbit (the position
/// itself without one, or at time 0).
[[nodiscard]] glm::vec3 cameraPositionAt(const Camera& camera, double seconds);

enum class LightKind { directional };

/// A light. Directional: parallel rays travelling along `direction` (from the light toward
/// the scene; normalised on load), radiance `colour * intensity`.
struct Light {
  LightKind kind = LightKind::directional;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};
  glm::vec3 colour{1.0f};  ///< linear RGB, each ≥ 0
  float intensity = 1.0f;  ///< ≥ 0, unitless scale
  /// The angular radius of the light's disc where the background shows it (a sun), 0..20; 0: not seen.
  float discRadiusDegrees = 0.0f;
  float discRadiance = 20.0f;  ///< the disc's radiance as a multiple of `colour`, 0..1000
};

/// Light from every direction, drawn behind the scene and lighting it
/// (render/passes/environment_pass.hpp): a Radiance panorama or, without one, the procedural sky
/// (render/environment/sky_model.hpp), whose sun is the first light.
struct Environment {
  /// Asset name or path of an equirectangular `.hdr` or `.exr` panorama; empty: the sky.
  std::string file;
  float turbidity = 3.0f;     ///< the sky's haze, [1.7, 10]
  float groundAlbedo = 0.3f;  ///< the ground below the sky's horizon, [0, 1]
  /// Turns the panorama about +Y, counter-clockwise seen from above, degrees.
  float rotationDegrees = 0.0f;
  /// Scales the panorama's radiance; the sky's zenith luminance in the lights' units. [0, 1000]
  float intensity = 1.0f;
  /// Texels on a side of each cube face, 8..2048; 0: 256 for a panorama, 64 for the sky.
  int cubeSize = 0;
  /// A panorama's sun cut out of it and made the scene's first light, ahead of `lights`
  /// (render/environment/sun_extraction.hpp), so that it is counted once.
  bool sunLight = false;
};

/// lambert: diffuse; skin: render::SurfaceShading::kSkin; fur: shells and fins grown from the
/// albedo texture, a photo of fur (render::SurfaceShading::kFur), on the meshes drawn with it.
enum class MaterialKind { lambert, skin, fur };

/// Fur that moves: guide strands on the furred mesh, simulated with the scene's fixed step.
struct FurMotion {
  int guides = 1000;            ///< guide strands, 1..100000 (at most one per vertex)
  float shapeStiffness = 0.5f;  ///< how firmly the guides keep their rest shape, [0, 1]
  float damping = 0.05f;        ///< velocity fraction lost per step, [0, 1)
  int iterations = 4;           ///< constraint sweeps per step, 1..100
};

/// A surface material; texture fields hold asset names (empty: none).
struct Material {
  std::string name;
  MaterialKind kind = MaterialKind::lambert;
  std::string albedoTexture;
  std::string normalMap;  ///< tangent-space normal map
  std::string specularMap;
  glm::vec3 baseColour{0.8f};   ///< linear RGB multiplier of the albedo texture, or the albedo
  render::SkinParameters skin;  ///< kind skin only
  render::FurParameters fur;    ///< kind fur only
  /// Kind fur: photo repeats per uv unit, higher for finer, denser fur; the World scales the
  /// mesh's uvs by it. Meshes without uvs get a box projection in metres: repeats per metre.
  float furUvScale = 1.0f;
  /// Kind fur: simulated guide strands that bend the shells (scenes/fur_dynamics.hpp); none: the
  /// fur stands as combed.
  std::optional<FurMotion> furMotion;
  /// Light from the first light shining through the object (render::TranslucencyMethod); off by
  /// default. Extinction (1/metre) is for kinds other than skin, the voxel resolution for kVoxelLut.
  render::TranslucencyParameters translucency;
  /// False culls the faces turned away from the camera (render::MaterialData::doubleSided).
  bool doubleSided = true;
  /// Kind lambert: the share of light a thin sheet passes through (render::MaterialData::transmission).
  float transmission = 0.0f;
};

/// Placement of a mesh: scale, then rotation (X, then Y, then Z, about the fixed axes), then
/// translation.
struct Transform {
  glm::vec3 translation{0.0f};      ///< metres
  glm::vec3 rotationDegrees{0.0f};  ///< Euler angles, degrees
  float scale = 1.0f;               ///< uniform, > 0

  /// The model matrix T · Rz · Ry · Rx · S.
  [[nodiscard]] glm::mat4 matrix() const;
};

/// Prefix of `MeshInstance::source` for built-in geometry, e.g. "procedural:sphere".
inline constexpr std::string_view kProceduralPrefix = "procedural:";

/// The kinds after `kProceduralPrefix` that `loadSceneMesh` builds (scenes/procedural.hpp): a
/// unit sphere, the cube [−1, 1]³ with a hollow of radius 0.5, a torus of radii 1 and 0.4 around +Y,
/// a floor 1 m square in the XZ plane facing +Y.
inline constexpr std::array<std::string_view, 6> kProceduralMeshKinds = {
    "sphere", "cube_with_hollow", "torus", "plane", "hull", "spar"};

/// Bounds of `Subdivision`'s fields (subdiv::LimitSurfaceSettings, subdiv::TessellationSettings).
inline constexpr int kMinSubdivisionLevel = 1;
inline constexpr int kMaxSubdivisionLevel = 10;
inline constexpr float kMaxSubdivisionPixelError = 100.0f;

/// Drawing a mesh with fewer triangles (scenes/mesh_simplify.hpp), for one drawn small on screen.
struct MeshSimplification {
  int triangles = 0;               ///< at most this many, ≥ 1
  float maxRelativeError = 0.01f;  ///< deviation allowed, fraction of the mesh's extent, (0, 1]
};

/// Drawing a mesh as the Catmull-Clark limit surface of its triangles or polygons (the cage),
/// tessellated at load for the scene's camera and output size and again for each new view
/// (World::refineForCamera; scenes/subdivided_mesh.hpp).
struct Subdivision {
  /// Largest projected distance, pixels, between the drawn triangles and the limit surface.
  float maxPixelError = 1.0f;
  /// Feature-adaptive isolation around extraordinary vertices and creases, 1..10: each level
  /// makes the end caps around them half as large and costs refined points at load.
  int isolation = 2;
  /// The most times a ptex face's side is halved, 1..10 (at most 4^maxDepth cells per face).
  int maxDepth = 10;
  /// Close the cage's holes first, one sharp-rimmed polygon per boundary loop
  /// (`capBoundaryLoops`): for open cages that must be solid, e.g. for a voxel translucency table.
  bool capHoles = false;
  /// A coarse quad-dominant cage instead of the mesh's own triangles (coarseCageFromTriangles):
  /// the triangles simplified to this and paired into quads. For a dense scan, whose triangles
  /// as a cage make every patch an end cap and the limit surface too costly to tessellate
  /// each frame.
  std::optional<MeshSimplification> coarseCage;
};

/// A mesh placed in the scene.
struct MeshInstance {
  std::string name;      ///< unique within the scene; grooms attach to it by this name
  std::string source;    ///< asset name (.glb/.gltf/.obj) or "procedural:<kind>"
  std::string material;  ///< name of a `Material` in the scene
  Transform transform;
  /// Draw the limit surface instead of the file's triangles; none: the triangles as they are.
  std::optional<Subdivision> subdivision;
  /// Simplify the triangles at load (not with `subdivision`); none: as they are.
  std::optional<MeshSimplification> simplify;
  /// The mesh it rides on (not itself attached): placed by that mesh's body frame every frame,
  /// `transform` then relative to it (metres; the body's scale does not apply). Empty: none.
  std::string attachedMesh;

  [[nodiscard]] bool isProcedural() const { return source.starts_with(kProceduralPrefix); }
  /// "sphere" for "procedural:sphere"; empty for asset meshes.
  [[nodiscard]] std::string proceduralKind() const;
};

/// Parameters of the Verlet hair solver for one groom; the fixed step is the scene's
/// (`SimulationSettings::stepSeconds`), shared by everything simulated.
struct HairSimulation {
  int iterations = 8;                     ///< constraint relaxation passes per step, ≥ 1
  float damping = 0.02f;                  ///< velocity fraction lost per step, in [0, 1)
  glm::vec3 gravity{0.0f, -9.81f, 0.0f};  ///< m/s²
  float shapeStiffness = 0.0f;            ///< local shape constraint, [0, 1] (physics::SolverSettings)
};

/// Grid resolutions a scene may ask of a collider's signed distance field (nodes along the
/// longest axis): coarser cannot hold a head's shape, finer costs seconds to build at load.
inline constexpr int kMinSdfResolution = 8;
inline constexpr int kMaxSdfResolution = 128;

/// A signed distance field collider, built at load from a mesh of the scene (physics/sdf.hpp).
struct SdfColliderSource {
  std::string mesh;     ///< name of a `MeshInstance`; its triangles, closed and wound outward
  int resolution = 48;  ///< grid nodes along the longest axis, kMinSdfResolution..kMaxSdfResolution
};

/// A sphere carried by a joint of a character (`CharacterInstance`): its centre in the joint's
/// frame, which is the joint's placement with its scale divided out (metres, axes turned with the
/// joint).
struct JointSphere {
  std::string joint;  ///< a node name of the character's file
  physics::SphereCollider sphere;
};

/// A capsule carried by a joint: from `a` to `b` in the joint's frame (as `JointSphere`), or, with
/// `toJoint`, from the joint's origin to that joint's origin (a limb from shoulder to elbow).
struct JointCapsule {
  std::string joint;
  std::string toJoint;  ///< empty: `capsule.a` and `capsule.b` hold the axis
  physics::CapsuleCollider capsule;
};

/// What a groom's or a cloth's particles collide with. Shapes are given in the frame of the body
/// the groom or cloth follows (its `attached_mesh`): metres, origin at the mesh's placed pivot,
/// axes turned with the mesh, its scale not applied — the frame hair roots and cloth pins live
/// in, so the shapes move with the head motion.
struct Colliders {
  std::vector<physics::SphereCollider> spheres;    ///< body frame, metres
  std::vector<physics::CapsuleCollider> capsules;  ///< body frame, metres
  /// The field of a mesh, taken where that mesh stands at time 0 relative to the body (for the
  /// attached mesh itself: its model positions × its scale) and moving with the body from then on.
  std::optional<SdfColliderSource> sdf;
  /// Shapes carried by the joints of the character the body belongs to (its attached mesh names a
  /// character part): they follow their joints, not the body.
  std::vector<JointSphere> jointSpheres;
  std::vector<JointCapsule> jointCapsules;
  float friction = 0.0f;   ///< Coulomb coefficient μ ≥ 0, dimensionless
  float thickness = 0.0f;  ///< particles are kept this far outside every surface, metres ≥ 0

  [[nodiscard]] bool empty() const {
    return spheres.empty() && capsules.empty() && !sdf && jointSpheres.empty() && jointCapsules.empty();
  }
  [[nodiscard]] bool followsJoints() const { return !jointSpheres.empty() || !jointCapsules.empty(); }
};

/// Most guide strands a procedural groom may ask for (memory stays in the hundreds of MB).
inline constexpr int kMaxGuideStrands = 1'000'000;

/// Most dense strands a groom may be drawn with (80 bytes each on the GPU, plus their vertices).
inline constexpr int kMaxDenseStrands = 1'000'000;

/// Most vertices a dense strand may be drawn with (the dense-strand layout's limit).
inline constexpr int kMaxDenseStrandVertices = static_cast<int>(kMaxStrandVertices);

/// How a groom is drawn (render/hair_data.hpp): its Marschner preset, its ribbons and how many
/// dense strands are interpolated from its guides.
struct GroomRendering {
  render::HairLook look = render::HairLook::kBlonde;
  /// Ribbons 0.4 mm wide at the root: 4,095 strands stand for a head of ~100,000 hairs.
  render::HairGroomSettings settings{.width = 4e-4f};
  /// The strands' colour (render::HairStrandLook::colour, each component in [0, 1]), where the
  /// scene gives one; else a groom file's colours, else 1 (the look's own).
  std::optional<glm::vec3> colour;
  /// Which of `settings`' width, tip width scale and opacity the scene gave: those hold for every
  /// strand; the others come from the groom file where it has them (scenes/README.md).
  struct GivenLook {
    bool width = false;
    bool tipWidthScale = false;
    bool opacity = false;
  } given;
  /// Dense strands, 1..kMaxDenseStrands; 0: 4,095, or one per guide where there are more guides.
  int denseStrands = 0;
  /// Vertices along each dense strand, 2..kMaxDenseStrandVertices, resampled from its guide; 0:
  /// the guides' own count.
  int verticesPerStrand = 0;
  /// How dense strands follow the guides (physics/interpolation.hpp): each one guide plus a root
  /// offset, rooted around it, or a blend of three guides, rooted anywhere in their triangle,
  /// which spreads the roots over the whole scalp.
  physics::GuideBlend guideBlend = physics::GuideBlend::kSingle;
  /// How dense strands run between their guides' vertices: a Catmull-Rom spline, which rounds
  /// the guides' turns off, or straight segments, which keep them.
  StrandCurve curve = StrandCurve::kCatmullRom;
  /// How far each dense strand's tip is pulled towards its first guide, in [0, 1].
  float clump = physics::DenseGroomSettings{}.clump;
  /// The clumps' radial profile, an exponent in [0, 8] (physics::DenseGroomSettings::clumpProfile):
  /// 0 shrinks each clump evenly, more gathers its strands towards its guide.
  float clumpProfile = physics::DenseGroomSettings{}.clumpProfile;
  /// Curl: the helix each dense strand winds round its guides (physics::DenseGroomSettings'
  /// curl fields); radius 0: straight.
  float curlRadius = physics::DenseGroomSettings{}.curlRadius;
  float curlPeriod = physics::DenseGroomSettings{}.curlPeriod;
  float curlVariation = physics::DenseGroomSettings{}.curlVariation;
  /// Frizz: the largest random offset of a dense vertex, at the tip, metres; 0: none.
  float frizz = physics::DenseGroomSettings{}.frizz;
};

/// Hair or fur on a mesh.
/// Where a procedural groom grows on its mesh (model space, +y up, +z the front): triangles in
/// the top `topFraction` of the mesh's height whose unit normal n has n.y ≥ minUp and n.z ≤ maxForward.
struct ScalpRegion {
  float topFraction = 0.25f;
  float minUp = 0.2f;
  float maxForward = 1.0f;  ///< 1: no limit; lower keeps the hair off a forward-facing forehead
  /// Roots grow this many times as densely at the front edge (normal z = maxForward) as
  /// elsewhere, falling to the common density across the hairline behind it; in [1, 16].
  float hairlineDensity = 1.0f;

  /// How far behind the front edge the hairline reaches, in the unit normal's z.
  static constexpr float kHairlineWidth = 0.2f;

  /// The relative root density where the unit normal is `normal`: hairlineDensity at the front
  /// edge, falling linearly to 1 kHairlineWidth behind it.
  [[nodiscard]] float densityAt(const glm::vec3& normal) const noexcept {
    const float behind = std::clamp((maxForward - normal.z) / kHairlineWidth, 0.0f, 1.0f);
    return hairlineDensity + (1.0f - hairlineDensity) * behind;
  }
};

/// A procedural groom's parting (physics::GroomSettings' parting fields), body frame, metres.
struct GroomParting {
  float comb = 0.0f;   ///< how hard the roots in front of `backZ` are combed away from the plane; 0: none
  float x = 0.0f;      ///< the parting is the plane x = this
  float backZ = 0.0f;  ///< it runs from the front of the scalp back to z = this
};

struct Groom {
  std::string name;
  /// Asset names of .tfx/.hair files, whose guides are concatenated in this order into one groom,
  /// or exactly {"procedural"}.
  std::vector<std::string> sources;
  std::string attachedMesh;         ///< name of a `MeshInstance`; roots follow it
  int strandCount = 0;              ///< procedural only: guide strands to grow (0: generator default)
  float strandLengthMetres = 0.0f;  ///< procedural only: length (0: generator default)
  ScalpRegion scalp;                ///< procedural only
  glm::vec3 comb{0.0f};             ///< procedural only: physics::GroomSettings::comb, body frame
  GroomParting parting;             ///< procedural only
  /// Procedural only: guides laid over the groom's colliders (the body-frame shapes; not the
  /// joints') at rest, with these settings (physics/groom_drape.hpp); none: grown straight.
  std::optional<physics::DrapeSettings> drape;
  /// Files only: negate the points' z on load. TressFX's Maya exporter can write z inverted (for
  /// left-handed renderers); the TressFX ponytail's strands sit on its head only with this.
  bool invertZ = false;
  /// Files only: refuse a file with a flawed strand (a repeated or non-finite point, fewer than
  /// two points, an absurd length) rather than repair or drop the strand with a note.
  bool strict = false;
  HairSimulation simulation;
  Colliders colliders;  ///< in the attached mesh's body frame
  GroomRendering rendering;

  [[nodiscard]] bool isProcedural() const { return sources.size() == 1 && sources[0] == "procedural"; }
};

/// The cut of a "procedural:cape": a sector of a cone's side (a circle cape's pattern, which lies
/// flat when laid out), its top edge an arc around the neck at y = 0 centred on the back (−z),
/// flaring down to its hem. What the hem's extra width does once the cape hangs is folds.
struct CapeShape {
  float collarRadius = 0.06f;  ///< metres: radius of the arc the top edge is sewn along, > 0
  float hemRadius = 0.25f;     ///< metres: radius of the bottom edge, in [collar, collar + length]
  float length = 0.25f;        ///< metres: from collar to hem along the cloth, > 0
  float wrapDegrees = 240.0f;  ///< how far the collar goes around the neck, (0, 360]
  int columns = 64;            ///< vertices along the collar, 2..512
  int rows = 40;               ///< vertices from collar to hem, 2..512
};

/// The shape of a "procedural:fin": rays fanning from a straight root at y = 0 (along x, centred
/// on the origin) down towards −y, a membrane between them, the rays standing out of it
/// alternately on its +z and −z side, its edge cut back between their tips. The first ray
/// (towards −x) is the longest; the root and the row after it are the fin's base, held by the
/// body as a fin's rays are held at their base.
struct FinShape {
  int rays = 7;                 ///< 3..32
  float length = 0.065f;        ///< metres, [0.001, 1]: the first ray, root to tip
  float root = 0.035f;          ///< metres, [0.001, 1]: the root's length
  float spreadDegrees = 70.0f;  ///< (0, 150]: the angle between the first and the last ray
  float taper = 0.55f;          ///< (0, 1]: the last ray's length over the first's (linear between)
  float scallop = 0.12f;        ///< [0, 0.5]: how far the edge recedes midway between two rays, share of their length
  float pleat = 0.3f;           ///< [0, 0.5]: how far a ray stands out of the membrane, share of the gap beside it
  int rows = 12;                ///< vertices along each ray, 4..128
  /// (0, 1]: the share of the way back to their shape on the body the rays are pulled each step
  /// at their base, half that at their tips (physics::ClothShapeHold).
  float rayStiffness = 0.3f;
};

/// Cloth (a fin, a scarf, a cape): a triangle mesh whose edges become constraints, moving with
/// a mesh (the body). Its `transform` places the cloth relative to the body's pivot in metres,
/// following the body's motion but not its scale; on a character part, relative to the
/// character's placement (its axes, metres) at time 0.
struct Cloth {
  std::string name;
  /// Mesh asset, file path, "procedural:grid" (1 m × 1 m, top edge at y = 0), "procedural:cape"
  /// (`cape`) or "procedural:fin" (`fin`).
  std::string source;
  std::string attachedMesh;  ///< name of a `MeshInstance`; pins follow it
  std::string material;      ///< name of a `Material` (empty: the default material)
  Transform transform;
  /// Pin the vertices at the highest local y (the grid's top edge; a fin's base, `FinShape`).
  bool pinTopEdge = true;
  /// Pin these vertices of the cloth mesh as well (indices into its vertices, checked at load).
  std::vector<std::uint32_t> pinVertices;
  /// Pin every vertex inside these boxes too: cloth-local coordinates (before `transform`), metres.
  std::vector<std::array<glm::vec3, 2>> pinRegions;
  int iterations = 8;                     ///< constraint sweeps per step, ≥ 1
  float damping = 0.02f;                  ///< velocity fraction lost per step, in [0, 1)
  float bendingStiffness = 0.5f;          ///< in [0, 1]
  float selfCollision = 0.0f;             ///< metres each vertex keeps off the cloth's other triangles; 0: off
  glm::vec3 gravity{0.0f, -9.81f, 0.0f};  ///< m/s²
  /// Air blowing on the cloth, world m/s (physics/cloth_wind.hpp); none: still air.
  std::optional<glm::vec3> wind;
  float arealDensity = 0.3f;              ///< kg/m², what the wind pushes against, > 0
  Colliders colliders;                    ///< in the attached mesh's body frame (not the cloth's transform)
  CapeShape cape;                         ///< the cut of a "procedural:cape"
  FinShape fin;                           ///< the shape of a "procedural:fin"
};

/// A clip of a character's file played on the scene's clock.
struct ClipPlay {
  std::string clip;          ///< the glTF animation's name
  float startSeconds = 0.0f;  ///< scene time the clip starts at (its own time 0); increasing along the list
  float speed = 1.0f;         ///< clip seconds per scene second, > 0
  bool loop = true;           ///< start over at its end; else hold its last pose
  /// Blend in from the clip before over this long, seconds ≥ 0 (0: a cut). The clip before keeps
  /// playing under it until the blend is done.
  float crossFadeSeconds = 0.0f;
};

/// A morph weight set in the scene: constant, or piecewise linear through keys (held before the
/// first and after the last). It replaces what the clips say for that target.
struct MorphKey {
  float timeSeconds = 0.0f;
  float weight = 0.0f;
};
struct MorphTrack {
  std::string target;           ///< a morph target name (`extras.targetNames`) of the character's meshes
  std::vector<MorphKey> keys;   ///< strictly increasing times; one key: a constant weight
  [[nodiscard]] float weightAt(float timeSeconds) const;
};

/// A skinned, morphing, animated glTF character (scenes/gltf_character.hpp) placed in the scene.
/// Its meshes are named "<character>/<glTF mesh name>" wherever the scene names a mesh (a groom's
/// or cloth's `attached_mesh`, an `sdf` collider): hair, cloth and colliders then follow the
/// deformed surface and the joints.
struct CharacterInstance {
  std::string name;    ///< unique among characters; no '/'
  std::string source;  ///< .glb/.gltf asset name or file path
  Transform transform;
  /// Scene material of the primitives whose glTF material is not in `materials` (empty: default).
  std::string material;
  /// glTF material name → scene material name.
  std::vector<std::pair<std::string, std::string>> materials;
  physics::SkinningMethod skinning = physics::SkinningMethod::LinearBlend;
  std::vector<ClipPlay> clips;  ///< empty: the rest pose
  std::vector<MorphTrack> morphs;
  /// Draw these meshes (glTF mesh names) as the limit surfaces of their triangles as cages,
  /// skinned each frame and tessellated again for the bend and the view (scenes/skinned_cage.hpp);
  /// none: every mesh as its triangles.
  std::vector<std::string> subdividedMeshes;
  std::optional<Subdivision> subdivision;  ///< set exactly when subdividedMeshes is not empty
};

/// A pair of spectacles worn on a mesh (scenes/glasses.hpp builds them): two lenses ground to a
/// prescription, which refract what lies behind them (render/passes/glasses_pass.hpp), in a frame
/// of rims, a bridge and two temples drawn as a mesh. Sizes in metres.
struct Glasses {
  std::string name;          ///< unique among the scene's glasses
  std::string attachedMesh;  ///< the head, a `MeshInstance` or character part: the glasses follow it
  /// Where the glasses sit in the head's body frame (as a cloth's transform: metres from its placed
  /// pivot, axes turned with it, its scale not applied), scale 1. Their own frame has its origin at
  /// the middle of the bridge on the lenses' front, +x to the wearer's left, +y up, +z forward.
  Transform transform;
  float powerDioptres = 0.0f;  ///< both lenses' thin-lens power, [−20, 20]: < 0 for the short-sighted
  float lensWidth = 0.05f;     ///< each lens's elliptical outline, (0, 0.2]
  float lensHeight = 0.036f;   ///< (0, 0.2]
  float bridge = 0.018f;       ///< between the two lenses, [0, 0.1]
  float templeLength = 0.1f;   ///< from the hinges back to where the temples bend over the ears, [0, 0.3]
  /// Between the temples' ends, behind the head's widest part; 0: the frame's width and 1 cm.
  float templeWidth = 0.0f;
  float ior = 1.5f;      ///< the lenses' index of refraction, (1, 3]
  glm::vec3 tint{1.0f};  ///< what the lenses let through, each channel in [0, 1]: < 1 for sunglasses
  std::string material;  ///< the frame's, a `Material` (empty: the default one)
};

/// A head pose at a time; the motion interpolates these linearly.
struct Keyframe {
  float timeSeconds = 0.0f;
  glm::vec3 rotationDegrees{0.0f};  ///< Euler XYZ like `Transform`
  glm::vec3 translation{0.0f};      ///< metres, added to the mesh's own translation
};

enum class HeadMotionKind {
  none,       ///< the head stays still
  turn,       ///< yaw about +Y: A·sin(2πft)
  nod,        ///< pitch about +X: A·sin(2πft)
  shake,      ///< a vigorous shake: yaw A·sin(2πft) plus pitch (A/4)·sin(4πft)
  keyframes,  ///< piecewise-linear through `keyframes`, held after the last
};

/// Rigid motion of one mesh (the head); hair roots and cloth pins follow it.
struct HeadMotion {
  HeadMotionKind kind = HeadMotionKind::none;
  std::string mesh;                 ///< the `MeshInstance` that moves
  float amplitudeDegrees = 0.0f;    ///< turn / nod / shake
  float frequencyHz = 0.0f;         ///< turn / nod / shake, ≥ 0
  std::vector<Keyframe> keyframes;  ///< keyframes: strictly increasing times
  /// keyframes: after the last, start again from the first (time wraps over first..last); else
  /// the last pose is held.
  bool loop = false;

  /// The motion's pose at `timeSeconds` (rotation degrees XYZ, translation metres), to be
  /// composed as T(mesh) · T(motion) · R(motion) · R(mesh) · S(mesh) — see `animatedMatrix`.
  [[nodiscard]] Keyframe poseAt(float timeSeconds) const;
};

/// World-level simulation settings.
struct SimulationSettings {
  float stepSeconds = 1.0f / 120.0f;  ///< fixed step of the accumulator, s, > 0
  int maxStepsPerFrame = 8;           ///< cap so a slow frame cannot spiral, ≥ 1
  /// Simulated at load with every body held at its pose at time 0, before the first frame, so
  /// hair and cloth start hanging at rest rather than in their modelled shape; s, in [0, 10].
  float settleSeconds = 0.0f;
};

/// The sea (scenes/README.md#ocean): Gerstner waves grown by the wind (physics/ocean_waves.hpp),
/// drawn on a projected grid (render/passes/ocean_pass.hpp).
struct Ocean {
  physics::OceanSettings waves;
  glm::ivec2 grid{150, 150};                    ///< cells across and down the screen, 16 … 1024 each
  float reach = 20000.0f;                       ///< metres the grid reaches from the eye
  glm::vec3 waterColour{0.006f, 0.03f, 0.04f};  ///< light sent up from below, per unit of light
  float fresnelPower = 3.0f;                    ///< 1 … 5
  glm::vec3 skyColour{0.5f, 0.65f, 0.85f};      ///< reflected where there is no environment
  glm::vec3 fogColour{0.6f, 0.7f, 0.8f};        ///< the horizon where there is no environment
  float fogDensity = 2e-4f;                     ///< 1/m, ≥ 0
  glm::vec3 foamColour{0.9f};
  float foamThreshold = 0.35f;  ///< the Jacobian under which crests break
  float foamHalfLife = 3.0f;    ///< seconds, > 0
  float foamGrowth = 6.0f;      ///< per second of breaking, ≥ 0
  float foamExtent = 160.0f;    ///< metres a side of the foam map, round the ship (or the origin)
  int foamResolution = 256;     ///< texels a side, 16 … 4096
  /// Wooden debris afloat round the ship (or the origin); none by default.
  std::optional<physics::FloatingDebrisSettings> debris;
};

/// A rope of the rigging, between two points of the ship's frame (metres, as the translations of
/// the meshes attached to it).
struct RiggingLine {
  glm::vec3 from{0.0f};
  glm::vec3 to{0.0f};
  float width = 0.05f;  ///< metres, > 0
};

/// A cannon on the ship: fired, it blows smoke from its muzzle.
struct Cannon {
  glm::vec3 muzzle{0.0f};                 ///< ship's frame, metres
  glm::vec3 direction{0.0f, 0.0f, 1.0f};  ///< ship's frame, unit
  float firstSeconds = -1.0f;             ///< when it first fires by itself; < 0: only when fired (`mane view`'s B)
  float intervalSeconds = 0.0f;           ///< then again every so often; 0: once
};

/// A mesh that floats on the sea (physics/floating_body.hpp): it heaves, pitches and rolls and
/// keeps its place and heading, those of its transform (turned about +Y only; its model's +X is
/// the bow). Its hull is its mesh filled with upright cells.
struct Ship {
  std::string mesh;            ///< the floating `MeshInstance`; a closed mesh
  float mass = 0.0f;           ///< kg, > 0
  glm::ivec3 cells{24, 8, 8};  ///< hull cells along its length (x), height (y) and beam (z), 1 … 64 each
  float drag = 0.5f;           ///< the water's linear drag, 1/s, ≥ 0
  float sailArea = 0.0f;       ///< m² the wind pushes on, ≥ 0
  glm::vec3 sailCentre{0.0f};  ///< where the wind pushes, model space (the mesh's units)
  bool spray = true;           ///< spray thrown up where the hull cuts the sea
  std::vector<RiggingLine> rigging;
  std::optional<Cannon> cannon;
};

/// Hair shadow map sizes a scene may ask for, texels per side (render::HairShadowSettings).
inline constexpr int kMinHairShadowResolution = 16;
inline constexpr int kMaxHairShadowResolution = 4096;

/// A validated scene.
struct Scene {
  std::filesystem::path file;  ///< the file it came from (empty when built in code)
  std::string name;
  OutputSettings output;
  Camera camera;
  std::vector<Light> lights;
  std::optional<Environment> environment;  ///< none: a flat background and ambient light
  std::vector<Material> materials;
  std::vector<MeshInstance> meshes;
  std::vector<Groom> grooms;
  std::vector<Cloth> cloths;
  std::vector<CharacterInstance> characters;
  std::vector<Glasses> glasses;
  std::optional<Ocean> ocean;
  std::optional<Ship> ship;  ///< only with an ocean
  HeadMotion headMotion;
  SimulationSettings simulation;
  render::HairShadowSettings hairShadows;  ///< opacity shadow maps at 512 × 512 unless the file says otherwise
  /// Glow, auto gain and tone mapping (render::PostSettings); the frame's Δt is the caller's.
  render::PostSettings post;

  [[nodiscard]] const Material* findMaterial(std::string_view name) const;
  [[nodiscard]] const MeshInstance* findMesh(std::string_view name) const;
  [[nodiscard]] const CharacterInstance* findCharacter(std::string_view name) const;
  /// Whether `name` is a mesh of `meshes` or names a character's part ("<character>/<mesh>",
  /// the character being in `characters`; the part itself is checked when the file is read).
  [[nodiscard]] bool namesMesh(std::string_view name) const;
};

/// Separator of a character part's name: "<character>/<glTF mesh name>".
inline constexpr char kCharacterPartSeparator = '/';

/// The mesh's model matrix at `timeSeconds`, including the head motion when it targets it.
[[nodiscard]] glm::mat4 animatedMatrix(const Scene& scene, const MeshInstance& mesh, float timeSeconds);

/// The body frame of a mesh at `timeSeconds`: `animatedMatrix` with the mesh's scale divided out,
/// a rigid map from body-frame metres to the world. Hair roots, cloth pins and colliders live in
/// it; a point `p` of the mesh's model space is at `p × scale` in it.
[[nodiscard]] glm::mat4 bodyMatrix(const Scene& scene, const MeshInstance& mesh, float timeSeconds);

/// Reads and validates a scene file. Errors name the file, the JSON field path (e.g.
/// `lights[1].direction`) and what was expected; unknown fields are errors, so typos are
/// caught. Cross-references (materials, attached meshes) are checked; asset names are not
/// resolved here (a missing asset falls back later, see `loadSceneMesh`).
[[nodiscard]] Result<Scene> loadScene(const std::filesystem::path& file);

/// `loadScene` on text already in memory; `file` is used only in messages.
[[nodiscard]] Result<Scene> parseScene(std::string_view text, const std::filesystem::path& file);

}  // namespace mane::scenes
