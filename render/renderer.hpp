#pragma once
// Runs the passes of a frame into an offscreen RenderTarget, in the order of
// docs/design.md#the-frame: the skinned meshes' deformation (compute, written into the vertex
// buffers every later pass draws: render/passes/skinning_pass.hpp), the grooms' strand
// interpolation (compute), the hair shadows from the first light, the texture-space diffusion of
// skin that asks for it, light 0's depth map of the translucent surfaces, the deferred skin's
// G-buffer, the hair's hiding and per-vertex shading (compute), then surfaces, fur (shells and
// fins) and hair into HDR colour, the post chain where FrameInput::post asks for it (glow, auto
// gain, god rays) and the output pass (tone map) to 8-bit sRGB. Reads the result back for PNG
// files, or leaves it for a window to blit into its swapchain.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/fur_surfaces.hpp"
#include "render/hair_order.hpp"
#include "render/gpu_timer.hpp"
#include "render/luts/marschner_lut.hpp"
#include "render/passes/hair_density_pass.hpp"
#include "render/passes/hair_lighting_pass.hpp"
#include "render/passes/hair_occlusion_pass.hpp"
#include "render/passes/hair_pass.hpp"
#include "render/passes/deferred_skin_pass.hpp"
#include "render/passes/environment_pass.hpp"
#include "render/passes/effects_pass.hpp"
#include "render/passes/ocean_pass.hpp"
#include "render/passes/glasses_pass.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/passes/light_disc_pass.hpp"
#include "render/passes/skin_diffusion_pass.hpp"
#include "render/passes/skinning_pass.hpp"
#include "render/passes/output_pass.hpp"
#include "render/passes/post_pass.hpp"
#include "render/passes/strand_interpolation_pass.hpp"
#include "render/passes/surface_pass.hpp"
#include "render/passes/surface_scene.hpp"
#include "render/passes/translucency_pass.hpp"
#include "render/render_target.hpp"

namespace mane::render {

struct RendererSettings {
  vk::Extent2D extent{1280, 720};
  /// 1 or 4 (lavapipe offers no other counts).
  std::uint32_t msaaSamples = 1;
  /// Whether hair segments that lie wholly behind the opaque scene (behind the skin alone where
  /// it is deferred) are left out of the hair's shading and drawing (HairPass, "Hidden strands").
  /// They would be depth-tested away anyway: the image is the same either way.
  bool hideOccludedHair = true;
  /// Whether single-sample frames light pre-integrated skin once per pixel after drawing it into
  /// a G-buffer (render/passes/deferred_skin_pass.hpp) rather than in the fragment
  /// shader: the same image, for 59 MB of G-buffer at 1280×720.
  bool deferSkin = true;
};

class Renderer {
public:
  static Result<std::unique_ptr<Renderer>> create(const Device& device, const RendererSettings& settings);

  /// Uploads meshes and textures that stay for many frames.
  Result<void> setScene(const StaticScene& scene);

  /// New positions (and normals, or none to keep them) for dynamic mesh `mesh` of the scene,
  /// one per vertex; takes effect from the next render.
  Result<void> updateMesh(std::size_t mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);

  /// Replaces static mesh `mesh` of the scene by `data`, whose vertex and index counts may
  /// differ: a subdivision surface tessellated again as the camera moves
  /// (scenes::World::refineForCamera); takes effect from the next render. What was derived from
  /// the old triangles is dropped or redone: the surface scene's bounds, the translucency
  /// pass's voxel thickness tables (built again the next frame that draws them: seconds for a
  /// fine table) and the texture-space skin's copy of the mesh. Errors: no such mesh, a dynamic
  /// mesh or `data` (use updateMesh), data that breaks MeshData's contract, or an upload that
  /// fails.
  Result<void> replaceMesh(std::size_t mesh, const MeshData& data);

  /// This frame's guide positions of groom `groom` of the scene (world space, metres: guide
  /// after guide, root first, as the groom's layout counts them); takes effect from the next
  /// render. Errors: no such groom, a count that does not match, a NaN or a collapsed guide frame.
  /// The groom's shadow map (StaticScene::hairShadows) bounds the guides, widened by how far
  /// the dense strands stray from them.
  Result<void> updateHair(std::size_t groom, std::span<const glm::vec3> guidePositions);

  /// This frame's joint matrices (one per joint of MeshData::skinning, affine, from the joint's
  /// bind space to the mesh's model space, metres) and morph weights (one per morph target) of
  /// skinned mesh `mesh` of the scene; takes effect from the next render, which deforms the mesh
  /// on the GPU before any pass draws it. Until the first call the mesh is in its bind pose.
  /// Errors, changing nothing: no such mesh or not a skinned one, wrong counts, a NaN or infinite
  /// value, or for dual-quaternion skinning a joint matrix that mirrors or flattens space.
  Result<void> updateSkinning(std::size_t mesh, std::span<const glm::mat4> jointMatrices,
                              std::span<const float> morphWeights);

  /// Per-vertex leans of the fur of StaticScene::furs[fur] (world space, units of its thickness:
  /// FurPass::setLeans), e.g. from simulated guides; takes effect from the next render.
  Result<void> updateFurLeans(std::size_t fur, std::span<const glm::vec3> leans);

  /// Records every pass of `frame`; leaves target().output() and target().hdr() in TRANSFER_SRC
  /// layout.
  void record(const vk::raii::CommandBuffer& commands, const FrameInput& frame);

  /// Renders `frame`, waits for it, and returns the GPU time of each pass.
  Result<std::vector<PassTiming>> render(const FrameInput& frame);

  /// The last rendered frame as sRGB-encoded RGBA8, rows top to bottom.
  Result<std::vector<std::uint8_t>> readOutput() const;
  /// The last rendered frame's linear HDR colour before exposure, glow and tone mapping, as
  /// fp16 RGBA bit patterns, rows top to bottom.
  Result<std::vector<std::uint16_t>> readHdrOutput() const;

  /// GPU times of the last frame whose commands completed.
  std::vector<PassTiming> lastTimings() const { return timer_.results(); }

  const RenderTarget& target() const { return target_; }

  /// Per groom (StaticScene::grooms order), what the last rendered frame chose to draw it with
  /// and how many of its vertices it hid (HairPass::lastChoice); a groom not drawn yet has the
  /// defaults. After render() has returned.
  std::vector<HairPrimitiveChoice> hairChoices() const;
  /// Whether render() lights `frame`'s skin deferred (RendererSettings::deferSkin; after setScene).
  bool defersSkin(const FrameInput& frame) const { return deferredSkin_.defersSkin(frame); }
  /// The HDR post chain: its glow, its auto gain state (render/passes/post_pass.hpp).
  const PostPass& post() const { return post_; }
  const Device& device() const { return *device_; }

private:
  Renderer(const Device& device, const RendererSettings& settings, std::unique_ptr<HairShadowPass> shadows);

  /// The diffusion passes of the scene's texture-space skin materials.
  Result<void> setTextureSpaceSkins(const StaticScene& scene);
  /// The skinning passes of the scene's skinned meshes, after the surfaces, furs and diffusion
  /// meshes they write into exist.
  Result<void> setSkinnedMeshes(const StaticScene& scene);
  /// Deforms the skinned meshes that grow fur and whose joints changed, in a submission of their
  /// own, and hands the furs their pose: the fins and the fur's shadows are found on the CPU.
  Result<void> poseSkinnedFurs();

  // Pieces of record()'s frame graph.
  /// The skinning dispatches of the meshes whose joints changed since they were last deformed.
  void addSkinning();
  struct TextureSpaceSkin;
  /// The post chain's compute passes that `frame.post` asks for; none by default.
  void addPost(const FrameInput& frame);
  /// The hair's hiding, choice and shading (HairOcclusionPass, HairPass, HairLightingPass).
  void addHairLighting();
  /// The hair's density and the environment's visibility through it, round this frame's grooms.
  void addHairDensity();
  /// A pass that records nothing, so that its timer is there as in every frame of its kind.
  void addEmptyPass(PassName name);
  /// What the surfaces, furs and deferred skin of the scene pass read from earlier passes.
  void declareSurfaceReads(FrameGraph::Builder& pass, const FrameInput& frame) const;
  void declareHairDraws(FrameGraph::Builder& pass) const;
  void drawHair(const vk::raii::CommandBuffer& commands) const;
  /// The first instance of `frame` drawn with `skin`'s material, whose mesh it diffuses over.
  const MeshInstance* diffusionInstance(const TextureSpaceSkin& skin, const FrameInput& frame) const;

  /// Points every pass that receives hair shadows at the current maps.
  void refreshShadowDescriptors();
  /// The ambient radiance of what does not look up the environment's irradiance by a normal
  /// (texture-space skin): the frame's own plus the environment's average radiance.
  glm::vec3 ambientRadiance(const FrameInput& frame) const;

  const Device* device_;
  RenderTarget target_;
  HairOcclusionPass occlusion_;
  bool hideOccludedHair_;
  std::unique_ptr<HairShadowPass> shadows_;
  // The opaque surfaces: the scene's meshes and materials, translucency, forward and deferred.
  TranslucencyPass translucency_;
  SurfaceShadowPass surfaceShadows_;
  SurfaceScene scene_;
  SurfacePass surfaces_;
  DeferredSkinPass deferredSkin_;
  LightDiscPass discs_;
  std::unique_ptr<EnvironmentPass> environment_;  // where the scene has one
  std::unique_ptr<HairDensityPass> hairDensity_;  // where hair meets an environment
  std::unique_ptr<OceanPass> ocean_;              // where the scene has a sea
  std::unique_ptr<EffectsPass> effects_;          // from the first frame with effects
  std::unique_ptr<GlassesPass> glasses_;          // from the first frame with lenses
  // A groom: its strands interpolated on the GPU, shaded per vertex, then drawn as ribbons.
  struct HairGroom {
    std::unique_ptr<StrandInterpolationPass> strands;
    std::unique_ptr<HairLightingPass> lighting;
    std::unique_ptr<HairPass> ribbons;
    std::unique_ptr<StrandDrawOrder> order;
    Buffer looks;                         // the strands' own looks, where the groom has them
    std::vector<glm::vec3> guideMiddles;  // of the last updateHair: the sort keys
    glm::vec3 centre{0.0f};               // of the guides' bounding sphere: where the level of detail is measured
    HairBounds bounds;                    // the guides' box widened to hold every dense vertex
    HairGroomSettings settings;
    float strayFromGuides = 0.0f;  // metres: bound on a dense vertex's distance from its guides
    bool hasGuides = false;        // updateHair called at least once
  };
  // Texture-space skin: one diffusion pass per such material, fed by the first instance drawn
  // with it, over the diffusion copy of that instance's mesh.
  struct TextureSpaceSkin {
    std::size_t material = 0;
    std::unique_ptr<SkinDiffusionPass> pass;
  };
  std::vector<TextureSpaceSkin> textureSpaceSkins_;
  // A skinned mesh (MeshData::skinning): deformed on the GPU into the vertex buffers of the
  // surface scene, of the furs growing on it and of its texture-space skin copy.
  struct SkinnedMesh {
    std::unique_ptr<SkinningPass> pass;
    std::vector<std::size_t> furs;  // StaticScene::furs on the mesh: posed from the pass's outputs
    bool stale = true;              // joints or weights changed since the last dispatch
  };
  std::vector<SkinnedMesh> skinned_;  // per scene mesh; no pass for the others
  std::vector<std::optional<SkinDiffusionMesh>> diffusionMeshes_;  // per scene mesh: static, with uvs and normals
  std::vector<std::unique_ptr<MarschnerLut>> luts_;                // per HairLook, baked when a groom needs it
  std::vector<HairGroom> hair_;
  FurSurfaces furs_;
  std::vector<bool> furShadowsBound_;  // per fur: its shadow map has had bounds
  PostPass post_;
  OutputPass output_;
  GpuTimer timer_;
  // record()'s graph and what it decided for the frame, kept to reuse their memory.
  FrameGraph graph_;
  struct FramePlan {
    std::vector<bool> shaded, drawn;  ///< per groom
    bool skinDeferred = false;
    bool hairBeforeMainPass = false;
    RenderTarget::ScenePart scene = RenderTarget::ScenePart::kWhole;
    glm::vec4 background{0.0f};
    std::optional<glm::vec2> rayLight;  ///< the god rays' light, frame uv
  };
  FramePlan plan_;
};

}  // namespace mane::render
