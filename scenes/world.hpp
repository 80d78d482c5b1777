#pragma once
// The per-frame world of a scene (docs/design.md#the-frame): it owns the loaded meshes,
// textures and hair systems, and per frame runs animate → simulate, then hands the renderer
// plain data. The composition root: the only place physics, subdiv and render meet.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "common/error.hpp"
#include "common/strand_layout.hpp"
#include "physics/hair.hpp"
#include "physics/surface_binding.hpp"
#include "render/frame.hpp"
#include "scenes/assets.hpp"
#include "scenes/fur_dynamics.hpp"
#include "scenes/glasses.hpp"
#include "scenes/image.hpp"
#include "scenes/joint_colliders.hpp"
#include "scenes/scene_cloth.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_character.hpp"
#include "scenes/scene_meshes.hpp"
#include "scenes/scene_ocean.hpp"
#include "scenes/skinned_cage.hpp"
#include "scenes/subdivided_mesh.hpp"

namespace mane::scenes {

class SceneColliders;

struct WorldSettings {
  /// Decode the materials' textures and the environment (the renderer needs them; `mane sim`
  /// does not).
  bool loadTextures = true;
  /// Treat every groom as `Groom::strict`: a flawed strand in a groom file is an error, not a note.
  bool strictGrooms = false;
};

class World {
public:
  /// Loads every mesh, texture, character and groom of `scene`. Missing assets fall back to
  /// procedural content with a note (see `notes`); unusable files are errors.
  ///
  /// Characters: each mesh of a character's file becomes meshes of `scene().meshes`, after the
  /// scene's own: "<character>/<glTF mesh>", the whole mesh in its part frame
  /// (SceneCharacter), which grooms, cloths and collider fields name and follow but which is not
  /// drawn, and "<character>/<glTF mesh>#<primitive>", each primitive drawn with the scene
  /// material its glTF material maps to. Both are placed where the part frame is at time 0.
  static Result<World> create(Scene scene, const AssetResolver& resolver, const WorldSettings& settings = {});

  const Scene& scene() const { return scene_; }
  /// What differs from what the scene asked for (fallbacks, skipped content), for people.
  const std::vector<std::string>& notes() const { return notes_; }
  /// Seconds of animation played so far.
  double time() const { return time_; }
  /// The sea and its ship, where the scene has one.
  const SceneOcean* ocean() const { return ocean_ ? &*ocean_ : nullptr; }

  /// Animates the head and the characters to `time() + frameDt`, moves hair roots, cloth pins
  /// and colliders with them and simulates.
  /// `threads` ≥ 1 workers; results do not depend on it.
  Result<void> advance(double frameDt, unsigned threads);
  /// Sets the clock to `time` (seconds, finite, ≥ 0) and poses the characters there, simulating
  /// nothing: for frames whose simulated state comes from elsewhere (a simulation cache,
  /// scenes/sim_cache.hpp), so that placements, poses and skinning match that moment.
  Result<void> showTime(double time);

  /// Meshes, materials and grooms for the renderer; the meshes' and textures' data are views into
  /// this world, valid while it lives.
  render::StaticScene staticScene() const;
  /// Camera, lights and mesh placements at the current time.
  render::FrameInput frameInput() const;

  /// Tessellates every mesh with a `subdivision` again for `camera` on an image of `size`
  /// pixels, with the mesh placed where it is at time() (the head turns): the limit surfaces and
  /// tessellators built at load are kept, only the triangles are redone. Returns the meshes
  /// (indices into staticScene().meshes) whose triangles changed: hand each one's meshData() to
  /// Renderer::replaceMesh before rendering. Costs nothing for a mesh whose view (camera, size,
  /// placement) is the one it was last tessellated for. Hair roots (on the limit surface) and
  /// collider fields (built at load) do not change; meshes drawn with fur keep their load-time
  /// triangles (their uvs are made for the fur once). `threads` ≥ 1 workers; the triangles do not
  /// depend on it. Errors: a size of zero pixels or a camera that gives no projection.
  ///
  /// A character's subdivided meshes are posed at time() and tessellated again here after every
  /// pose that moved them (they bend): they are among the meshes returned whenever the character
  /// moved since the last call.
  Result<std::vector<std::size_t>> refineForCamera(const render::Camera& camera, glm::uvec2 size, unsigned threads = 1);
  /// Mesh `mesh` of staticScene() (a scene mesh, not a cloth) as it is now: after
  /// refineForCamera, the triangles to hand to Renderer::replaceMesh. A view into this world.
  render::MeshData meshData(std::size_t mesh) const;

  /// A mesh of staticScene() whose vertices move every frame on the CPU (cloth), with its current
  /// world-space positions and normals: hand them to Renderer::updateMesh before rendering.
  struct DynamicMesh {
    std::size_t mesh = 0;
    std::span<const glm::vec3> positions;
    std::span<const glm::vec3> normals;
  };
  std::vector<DynamicMesh> dynamicMeshes() const;

  /// A mesh of staticScene() deformed on the GPU (a character's skinned or morphing primitive),
  /// with this frame's joint matrices (into the mesh's model space, the part frame that
  /// frameInput() places it with) and morph weights: hand them to Renderer::updateSkinning.
  struct SkinnedMesh {
    std::size_t mesh = 0;
    std::vector<glm::mat4> jointMatrices;
    std::span<const float> morphWeights;
  };
  std::vector<SkinnedMesh> skinnedMeshes() const;

  /// A groom of staticScene() (render order) and its simulated guides this frame: hand them to
  /// Renderer::updateHair before rendering.
  struct HairGuides {
    std::size_t groom = 0;
    std::span<const glm::vec3> positions;  ///< world space, metres, guide after guide
    std::size_t simulatedGroom = 0;        ///< its index for simulatedGroom()
  };
  std::vector<HairGuides> hairGuides() const;

  /// A fur of staticScene() (StaticScene::furs order) whose guides move, with this frame's
  /// per-vertex leans: hand them to Renderer::updateFurLeans before rendering.
  struct FurLeans {
    std::size_t fur = 0;
    std::span<const glm::vec3> leans;
  };
  std::vector<FurLeans> furLeans() const;

  const std::vector<SceneCloth>& cloths() const { return cloths_; }
  /// For viewers: every character starts the clip after the one it plays (in file order) now,
  /// blended in over `crossFadeSeconds`. Returns "<character>: <clip>" for each, for people.
  std::string playNextClips(float crossFadeSeconds);
  /// For viewers: every character blends the expression it shows out and its next morph target
  /// in (in file order; after the last, none) over `seconds`. Returns what now shows, for people.
  std::string nextExpression(float seconds);
  /// For viewers: fires the ship's cannon at the next step. False where the scene has none.
  bool fireCannon();
  /// For viewers: the sea's wind blows at `speed` m/s from now on; the waves change at once (hand
  /// the renderer the new staticScene()), and the sails' wind grows in proportion. Errors: no
  /// sea, or a speed the waves refuse.
  Result<void> setWindSpeed(float speed);

  /// The scene's characters, posed at time().
  const std::vector<SceneCharacter>& characters() const { return characters_; }
  /// The root of every guide of simulated groom `index` on its body's deformed surface now,
  /// for grooms on a character part (empty for others): where the roots must be.
  Result<std::vector<glm::vec3>> boundRoots(std::size_t index);
  /// Likewise the pins of cloth `index` (cloth().pinnedVertices() order).
  Result<std::vector<glm::vec3>> boundPins(std::size_t index);

  /// Hash of every simulated state (grooms, then cloths, then moving furs, in scene order) and of
  /// the clock.
  std::uint64_t stateHash() const;
  std::size_t guideStrandCount() const;
  /// The simulated grooms, in scene order (skipped grooms are absent): positions in metres,
  /// world space.
  std::size_t simulatedGroomCount() const { return grooms_.size(); }
  const physics::HairSystem& simulatedGroom(std::size_t index) const { return grooms_.at(index).hair; }
  /// The scene's name of simulated groom `index`.
  const std::string& simulatedGroomName(std::size_t index) const {
    return scene_.grooms[grooms_.at(index).sceneGroom].name;
  }
  /// The same groom, for hosts that script it between advances (set particle states or root
  /// targets). advance() still sets its head transform each frame and, for a groom on a
  /// character part, its root targets and colliders, over what was set here.
  physics::HairSystem& simulatedGroomMutable(std::size_t index) { return grooms_.at(index).hair; }
  std::size_t particleCount() const;

private:
  struct LoadedMaterial {
    std::optional<Image> albedo;
    std::optional<Image> normalMap;
    std::optional<Image> specularMap;  ///< skin only
  };
  struct SimulatedGroom {
    std::size_t mesh = 0;  ///< index into scene_.meshes the roots follow
    physics::HairSystem hair;
    std::size_t sceneGroom = 0;  ///< index into scene_.grooms (skipped grooms leave gaps)
    /// The dense strands the renderer draws; none when its guides differ in point count.
    std::optional<DenseStrandLayout> dense;
    /// Their looks where the groom's files or scene give them (scenes/groom_looks.hpp); empty:
    /// every strand as the groom's settings say.
    std::vector<render::HairStrandLook> denseLooks;
    /// On a character part: the roots on its surface, and the colliders its joints carry.
    std::optional<physics::SurfaceBinding> roots;
    std::optional<JointColliders> jointColliders;
  };
  /// What a mesh of scene_.meshes made for a character stands for.
  struct CharacterPart {
    std::size_t character = 0;  ///< index into characters_
    std::size_t part = 0;       ///< index into its meshes
    /// -1: the whole part, followed by the physics and not drawn; else the primitive it draws.
    int primitive = -1;
  };
  /// What follows a character part in a cloth: its pins on the surface, its joint-borne colliders.
  struct ClothOnCharacter {
    std::optional<physics::SurfaceBinding> pins;
    std::optional<JointColliders> jointColliders;
  };

  World() = default;
  Result<void> loadMeshes(const AssetResolver& resolver);
  /// Builds the limit surface and tessellator of every mesh with a `subdivision` (kept in
  /// subdivided_) and replaces its triangles by the limit surface tessellated for the scene's
  /// camera and output size at time 0 (refineForCamera does it again for other views).
  Result<void> subdivideMeshes();
  /// The uvs of meshes drawn with a fur material scaled by its uv_scale; box-projected where the
  /// mesh has none (the shells sample their photo by uv).
  void prepareFurMeshes();
  /// The fur pairs (mesh, material) the renderer draws: fur materials whose photo loaded.
  std::vector<render::FurSurfaceData> furSurfaces() const;
  /// Guide strands for the furs whose material asks for dynamics.
  Result<void> loadFurDynamics();
  Result<void> loadMaterials(const AssetResolver& resolver);
  /// The curvature skin materials shade with, for every mesh drawn with one.
  Result<void> computeSkinCurvatures();
  /// Loads every character and appends its parts to scene_.meshes and meshes_.
  Result<void> loadCharacters(const AssetResolver& resolver);
  /// Appends part `p` of character `c`: its drawn primitives, then the whole part.
  Result<void> addCharacterPart(std::size_t c, std::size_t p);
  /// Checks that the grooms, cloths and fields that name character parts name existing ones.
  Result<void> checkPartReferences() const;
  /// Poses the characters at time().
  void poseCharacters();
  /// Binds `points` (world space, at the current pose) to the deformed surface of mesh `mesh`,
  /// a character part; the error starts with `owner`.
  Result<physics::SurfaceBinding> bindToPart(std::size_t mesh, std::span<const glm::vec3> points,
                                             const std::string& owner);
  /// The points bound to mesh `mesh` (a character part) at the current pose: positions, normals.
  Result<void> followPart(std::size_t mesh, const physics::SurfaceBinding& binding, std::vector<glm::vec3>& positions,
                          std::vector<glm::vec3>& normals, unsigned threads = 1);
  Result<void> loadGrooms(const AssetResolver& resolver, SceneColliders& colliders);
  Result<void> loadCloths(const AssetResolver& resolver, SceneColliders& colliders);
  /// Builds the scene's glasses (scenes/glasses.hpp); their frames are drawn after the cloths.
  Result<void> loadGlasses();
  /// The rigid part of mesh `mesh`'s placement at `time` (its scale divided out, `bodyMatrix`):
  /// what hair roots, cloth pins and their colliders follow. For a character part, its part
  /// frame at the current pose (poseCharacters keeps that at time()).
  glm::mat4 bodyPlacement(std::size_t mesh, double time) const;
  /// Where scene mesh `mesh` (not a character's part) is drawn now: floating, riding on another
  /// mesh, or as the scene animates it.
  glm::mat4 meshModel(std::size_t mesh) const;
  /// Simulates `frameDt` seconds of hair and cloth with the bodies where they are at time().
  Result<void> simulate(double frameDt, unsigned threads);
  /// Hands the air's push on the cloths hung on the ship to its floating body.
  Result<void> handSailsToShip();
  /// `strandCount` dense strands drawn for `guides` (rest shape, equal point counts) as
  /// `rendering` lays them out (vertices per strand, curve, guide blend, clump), or none.
  static std::optional<DenseStrandLayout> denseGroom(std::span<const std::vector<glm::vec3>> guides,
                                                     std::size_t strandCount, const GroomRendering& rendering);

  Scene scene_;
  std::vector<LoadedMesh> meshes_;
  /// Per mesh: its limit surface and tessellator where it has a `subdivision`, else null.
  std::vector<std::unique_ptr<SubdividedSurface>> subdivided_;
  /// Per mesh: 1/r per vertex (mesh units) where a skin material covers it, else empty.
  std::vector<std::vector<float>> meshCurvatures_;
  std::vector<LoadedMaterial> materials_;
  std::vector<SimulatedGroom> grooms_;
  std::vector<SceneCloth> cloths_;
  struct MovingFur {
    std::size_t fur = 0;   ///< index into furSurfaces(); its size when the fur is not drawn
    std::size_t mesh = 0;  ///< index into scene_.meshes
    FurDynamics dynamics;
  };
  std::vector<MovingFur> movingFurs_;
  std::vector<std::size_t> clothBodies_;  ///< per cloth: index into scene_.meshes
  struct WornGlasses {
    std::size_t body = 0;       ///< index into scene_.meshes: the head they follow
    glm::mat4 placement{1.0f};  ///< the glasses' frame in the body frame
    GlassesModel model;
  };
  std::vector<WornGlasses> glasses_;
  std::optional<SceneOcean> ocean_;               ///< where the scene has a sea
  double lastFrameDt_ = 0.0;                      ///< the last advance's, for the sea's foam
  std::vector<ClothOnCharacter> clothFollowers_;  ///< per cloth
  std::vector<SceneCharacter> characters_;
  /// Per character: the morph target nextExpression() last blended in (its count: none).
  std::vector<std::size_t> expressions_;
  /// Per mesh of scene_.meshes: the character part it stands for, if any.
  std::vector<std::optional<CharacterPart>> characterParts_;
  /// Per mesh: what the renderer deforms it with, for a drawn primitive of a deforming part.
  std::vector<std::optional<render::GpuSkinnedMesh>> gpuSkins_;
  /// Per mesh: its skinned cage, for a drawn primitive of a part the character subdivides
  /// (posed and tessellated again by refineForCamera), else null.
  std::vector<std::unique_ptr<SkinnedCage>> skinnedCages_;
  std::vector<std::string> notes_;
  std::optional<render::EnvironmentData> environment_;  ///< the scene's, loaded with the textures
  std::optional<render::DirectionalLight> environmentSun_;  ///< cut from its panorama: the first light
  double time_ = 0.0;
};

}  // namespace mane::scenes
