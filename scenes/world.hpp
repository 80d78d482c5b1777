#pragma once
// The per-frame world of a scene (DESIGN.md, "The frame"): it owns the loaded meshes,
// textures and hair systems, and per frame runs animate → simulate, then hands the renderer
// plain data. The composition root: the only place physics, subdiv and render meet.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "physics/hair.hpp"
#include "render/frame.hpp"
#include "scenes/assets.hpp"
#include "scenes/image.hpp"
#include "scenes/scene_cloth.hpp"
#include "scenes/render_groom_layout.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_meshes.hpp"

namespace mane::scenes {

class SceneColliders;

struct WorldSettings {
  /// Decode the materials' textures (the renderer needs them; `mane sim` does not).
  bool loadTextures = true;
};

class World {
public:
  /// Loads every mesh, texture and groom of `scene`. Missing assets fall back to procedural
  /// content with a note (see `notes`); unusable files are errors.
  static Result<World> create(Scene scene, const AssetResolver& resolver, const WorldSettings& settings = {});

  const Scene& scene() const { return scene_; }
  /// What differs from what the scene asked for (fallbacks, skipped content), for people.
  const std::vector<std::string>& notes() const { return notes_; }
  /// Seconds of animation played so far.
  double time() const { return time_; }

  /// Animates the head to `time() + frameDt`, moves hair roots with it and simulates.
  /// `threads` ≥ 1 workers; results do not depend on it.
  Result<void> advance(double frameDt, unsigned threads);

  /// Meshes and materials for the renderer; views into this world, valid while it lives.
  render::StaticScene staticScene() const;
  /// Camera, lights and mesh placements at the current time.
  render::FrameInput frameInput() const;

  /// A mesh of staticScene() whose vertices move every frame (cloth), with its current
  /// world-space positions and normals: hand them to Renderer::updateMesh before rendering.
  struct DynamicMesh {
    std::size_t mesh = 0;
    std::span<const glm::vec3> positions;
    std::span<const glm::vec3> normals;
  };
  std::vector<DynamicMesh> dynamicMeshes() const;

  /// A groom of staticScene() (render order) and its simulated guides this frame: hand them to
  /// Renderer::updateHair before rendering.
  struct HairGuides {
    std::size_t groom = 0;
    std::span<const glm::vec3> positions;  ///< world space, metres, guide after guide
  };
  std::vector<HairGuides> hairGuides() const;

  const std::vector<SceneCloth>& cloths() const { return cloths_; }

  /// Hash of every simulated state (grooms, then cloths, in scene order) and of the clock.
  std::uint64_t stateHash() const;
  std::size_t guideStrandCount() const;
  /// The simulated grooms, in scene order (skipped grooms are absent): positions in metres,
  /// world space.
  std::size_t simulatedGroomCount() const { return grooms_.size(); }
  const physics::HairSystem& simulatedGroom(std::size_t index) const { return grooms_.at(index).hair; }
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
    /// The dense strands as the renderer draws them (render::HairGroomData's spans point here);
    /// none when its guides differ in point count.
    std::optional<RenderGroomLayout> dense;
  };

  World() = default;
  Result<void> loadMeshes(const AssetResolver& resolver);
  /// Replaces the triangles of every mesh with a `subdivision` by its limit surface,
  /// tessellated for the scene's camera and output size at time 0 (not again as the camera or
  /// the mesh moves).
  Result<void> subdivideMeshes();
  Result<void> loadMaterials(const AssetResolver& resolver);
  /// The curvature skin materials shade with, for every mesh drawn with one.
  Result<void> computeSkinCurvatures();
  Result<void> loadGrooms(const AssetResolver& resolver, SceneColliders& colliders);
  Result<void> loadCloths(const AssetResolver& resolver, SceneColliders& colliders);
  /// The rigid part of the mesh's placement at `time` (its scale divided out, `bodyMatrix`):
  /// what hair roots, cloth pins and their colliders follow.
  glm::mat4 bodyPlacement(const MeshInstance& mesh, double time) const;
  /// Simulates `frameDt` seconds of hair and cloth with the bodies where they are at time().
  Result<void> simulate(double frameDt, unsigned threads);
  /// `strandCount` dense strands drawn for `guides` (rest shape, equal point counts), or none.
  static std::optional<RenderGroomLayout> denseGroom(std::span<const std::vector<glm::vec3>> guides,
                                                     std::size_t strandCount);

  Scene scene_;
  std::vector<LoadedMesh> meshes_;
  /// Per mesh: 1/r per vertex (mesh units) where a skin material covers it, else empty.
  std::vector<std::vector<float>> meshCurvatures_;
  std::vector<LoadedMaterial> materials_;
  std::vector<SimulatedGroom> grooms_;
  std::vector<SceneCloth> cloths_;
  std::vector<std::size_t> clothBodies_;  ///< per cloth: index into scene_.meshes
  std::vector<std::string> notes_;
  double time_ = 0.0;
};

}  // namespace mane::scenes
