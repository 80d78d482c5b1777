#pragma once
// What the renderer is given: plain data only (spans, matrices, texels). Scenes, physics and
// subdiv convert their own types into these; render includes none of them
// (docs/design.md#dependency-rules).

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/environment/environment_map.hpp"
#include "render/hair_data.hpp"
#include "render/lens.hpp"
#include "render/pass_name.hpp"
#include "render/skinned_mesh_data.hpp"

namespace mane::render {

/// Tightly packed 8-bit RGBA texels, rows top to bottom.
struct TextureData {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::span<const std::uint8_t> rgba;
};

/// A triangle list. `normals` and `uvs` are empty or hold one entry per position.
struct MeshData {
  std::span<const glm::vec3> positions;
  std::span<const glm::vec3> normals;
  std::span<const glm::vec2> uvs;
  std::span<const std::uint32_t> indices;
  /// Positions and normals change every frame (cloth): kept in host-visible memory and
  /// replaced with Renderer::updateMesh; topology and uvs stay.
  bool dynamic = false;
  /// Empty or one per position: the surface's curvature 1/r (1 per mesh unit, ≥ 0; the instance's scale converts it),
  /// which skin materials look their pre-integrated scattering up by (scenes/mesh_curvature.hpp).
  std::span<const float> curvatures;
  /// Set: the mesh is skinned and morphed on the GPU every frame (render/passes/skinning_pass.hpp)
  /// from Renderer::updateSkinning's joints and weights; `positions` and `normals` (required) are
  /// its bind pose, one per skinning->positions, and every pass draws the deformed vertices, with
  /// the instance's model matrix applied after the joints. Read during setScene only. Not with
  /// `dynamic`. Like dynamic meshes, left out of the translucency depth map (bounds unknown).
  const GpuSkinnedMesh* skinning = nullptr;
};

/// How a surface scatters light.
enum class SurfaceShading : std::uint32_t {
  kLambert = 0,  ///< diffuse only
  kSkin = 1,     ///< pre-integrated subsurface scattering + Kelemen/Szirmay-Kalos specular
  /// Shell-and-fin fur grown from the albedo photo (render/passes/fur_pass.hpp) on the meshes
  /// StaticScene::furs names; drawn as Lambert with the photo where FrameInput::furShells is off.
  kFur = 2,
};

/// Which integration range the pre-integrated skin table uses (render/luts/preintegrated_skin.hpp).
enum class SkinIntegrationRange : std::uint32_t {
  kPenner = 0,     ///< x ∈ [−π/2, π/2] (Penner & Borshukov 2011)
  kCurvature = 1,  ///< x ∈ ±π(r + 1)/(2r), the skin thesis's curvature-dependent range
};

/// How a skin material's light spreads under the surface.
enum class SkinDiffusion : std::uint32_t {
  kPreintegrated = 0,  ///< the pre-integrated table, looked up per pixel by curvature
  kTextureSpace = 1,   ///< irradiance blurred in UV space (render/passes/skin_diffusion_pass.hpp)
};

/// Parameters of a skin material (render/passes/skin_shading.hpp).
struct SkinParameters {
  SkinDiffusion diffusion = SkinDiffusion::kPreintegrated;
  /// kTextureSpace: texels per side of the irradiance maps (1024; 2048 costs 4× the blurs).
  std::uint32_t irradianceSize = 1024;
  SkinIntegrationRange range = SkinIntegrationRange::kCurvature;
  float roughness = 0.3f;  ///< Beckmann m (GPU Gems 3 ch. 14 uses 0.3)
  /// ρs, scaled by the specular map's red channel. GPU Gems 3 ch. 14 uses 0.18 with a Beckmann
  /// term that leaves out 1/π; ours is normalised (render/luts/skin_specular.hpp), so 0.18·π.
  float specularIntensity = 0.5655f;
};

/// How light entering a surface on the side facing the first light shines out of the far side.
/// Both measure the thickness d between the light's entry point and the shaded point; skin then
/// transmits its diffusion profile's T(d) (SkinProfile::transmittance), any other material
/// exp(−σ·d) per RGB.
enum class TranslucencyMethod : std::uint32_t {
  kNone = 0,
  /// d from the first light's depth map (Jimenez et al. 2010, after Dachsbacher & Stamminger's
  /// translucent shadow maps): the distance from the first surface the light meets. Cheap, but
  /// hollows and gaps between entry and exit count as material.
  kDepthMap = 1,
  /// d from the mesh's voxelized thickness table (render/luts/voxel_thickness.hpp, after the
  /// voxelized-translucency paper): the entry point from the same depth map, hollows subtracted.
  kVoxelLut = 2,
};

/// Dynamic meshes (cloth) are left out of the depth map (their bounds change every frame): give
/// them a material without translucency.
struct TranslucencyParameters {
  TranslucencyMethod method = TranslucencyMethod::kNone;
  /// σ per RGB channel, 1/metre, for materials other than skin.
  glm::vec3 extinction{100.0f};
  /// kVoxelLut: N, cells per axis of the voxel grid over the mesh's bounding box
  /// (VoxelThicknessSettings::resolution).
  int voxelResolution = 32;
};

/// Parameters of a fur material (render/passes/fur_pass.hpp, render/luts/fur_shells.hpp). The
/// albedo texture is the photo the shells are made from; it must be present.
struct FurParameters {
  std::uint32_t layers = 15;  ///< N shells, 1 … 64 (Ukaji et al. use 15 on meshes)
  /// Fewer shells where the fur is short on screen: about one per this many pixels of the fur's
  /// height where it is nearest the eye, at most `layers`; 0 always draws `layers`.
  float pixelsPerLayer = 1.0f;
  float thickness = 0.004f;   ///< h_b, metres: the fur's height above the skin
  bool fins = true;           ///< Lengyel's fins on silhouette edges
  float layAngle = 0.6f;      ///< radians between a fibre and the fur direction (Kajiya-Kay)
  float specularExponent = 40.0f;
  float specularStrength = 0.08f;
  /// Where the tips lean, world space, in units of `thickness`, projected on the surface per
  /// vertex: (0, −0.5, 0) combs the fur down by half its height; zero stands it up.
  glm::vec3 comb{0.0f};
  /// The fur-direction field, in the mesh's model space: non-zero lays the photo along it instead
  /// of by the mesh's uvs. At each vertex the field is projected on the surface, and the photo's
  /// top-to-bottom axis follows it (render/passes/fur_pass.hpp, "Lay"); zero keeps the uvs.
  glm::vec3 layDirection{0.0f};
  /// With a layDirection: photo repeats per metre along the surface.
  float layRepeatsPerMetre = 30.0f;
};

/// A surface: albedo (sRGB texture times base colour) with an optional tangent-space normal map
/// (OpenGL convention, +Y up in the map); skin adds a specular map (its red channel scales ρs).
struct MaterialData {
  glm::vec3 baseColor{1.0f};
  std::optional<TextureData> albedo;
  std::optional<TextureData> normalMap;
  SurfaceShading shading = SurfaceShading::kLambert;
  SkinParameters skin;
  std::optional<TextureData> specularMap;
  TranslucencyParameters translucency;
  FurParameters fur;  ///< kFur only
  /// Lambert only: the share of a light's diffuse light that a thin sheet (a sail, a paper
  /// screen) passes to its other side, in [0, 1]. A face lit from behind shows
  /// t·albedo·radiance·|cos θ|, one lit from the front (1 − t)·albedo·radiance·cos θ: both vanish
  /// edge-on, so no seam shows where the light crosses the sheet.
  float transmission = 0.0f;
  /// Both faces drawn (and lit from the side they face). False culls the faces turned away from
  /// the camera, as glTF's doubleSided: false: for closed meshes, whose back faces are hidden,
  /// it saves shading them where they are drawn before the front faces in front of them.
  bool doubleSided = true;
};

/// Fur growing on a mesh: the instances that draw `mesh` with `material` (a kFur material) are
/// drawn by the fur pass. The mesh needs normals and uvs.
struct FurSurfaceData {
  std::size_t mesh = 0;
  std::size_t material = 0;
};

/// Everything that stays the same from frame to frame; uploaded once.
/// Light from every direction (render/passes/environment_pass.hpp): drawn behind the scene, it
/// lights the surfaces through its irradiance.
struct EnvironmentData {
  CubeMap radiance;  ///< linear RGB, in the units of the lights' radiance
};

/// The sea (render/passes/ocean_pass.hpp): a sum of Gerstner waves, as physics/ocean_waves.hpp
/// grows them, drawn on a grid projected from the screen, with a foam map over part of it.
struct OceanData {
  /// Per wave: its direction (x, z, unit), wavenumber (1/m) and amplitude (m); 1 … 64 waves.
  std::vector<glm::vec4> waves;
  float choppiness = 0.0f;    ///< λ: metres the water moves towards a crest per metre of height
  glm::uvec2 grid{150, 150};  ///< cells across and down the screen, 1 … 1024 each
  float reach = 20000.0f;     ///< metres from the eye where the grid ends (keep the camera's far plane beyond)
  glm::vec3 waterColor{0.006f, 0.03f, 0.04f};  ///< what the water sends up from below per unit of light
  float fresnelPower = 3.0f;                   ///< p of F₀ + (1 − F₀)(1 − n·v)^p, 1 … 5
  glm::vec3 skyColor{0.5f, 0.65f, 0.85f};      ///< the sky it reflects where the scene has no environment
  glm::vec3 fogColor{0.6f, 0.7f, 0.8f};        ///< the horizon where the scene has no environment
  float fogDensity = 2e-4f;                    ///< 1/m
  glm::vec3 foamColor{0.9f};                   ///< albedo
  float foamThreshold = 0.35f;                 ///< J (the waves' Jacobian) under which a crest breaks
  float foamHalfLife = 3.0f;                   ///< seconds, > 0
  float foamGrowth = 6.0f;                     ///< foam a breaking crest adds per second (1 covers)
  glm::vec2 foamCenter{0.0f};                  ///< (x, z) of the foam map's centre, metres at rest
  float foamExtent = 160.0f;                   ///< metres a side of the foam map
  std::uint32_t foamResolution = 256;          ///< texels a side, 1 … 4096
};

/// A body above the sea that hides the sky in the water's reflection (a ship's hull), as the
/// ellipsoid `worldFromUnitSphere` makes of the unit sphere.
struct OceanReflector {
  glm::mat4 worldFromUnitSphere{1.0f};  ///< invertible
  glm::vec3 albedo{0.2f};               ///< lit by the frame's ambient and environment where reflected
};

/// The sea this frame.
struct OceanFrame {
  /// Each wave's phase φ − ω t reduced to [0, 2π), one per OceanData wave
  /// (physics::OceanWaves::phasesAt).
  std::vector<float> phases;
  float seconds = 1.0f / 30.0f;  ///< since the foam map last grew and faded, ≥ 0
  /// Foam laid this frame besides the breaking crests' (a ship's wake): per source, (x, z) at
  /// rest (metres), a radius r (metres, > 0) and the foam it adds per second at its centre (≥ 0),
  /// falling off as exp(−d²/r²); at most kMaxFoamSources.
  std::vector<glm::vec4> foamSources;
  std::optional<OceanReflector> reflector;
};

/// What OceanFrame::foamSources holds at most (shaders/ocean_uniforms.glsl).
inline constexpr std::size_t kMaxFoamSources = 64;

/// A round particle (spray, smoke), drawn as a soft disc facing the eye
/// (render/passes/effects_pass.hpp).
struct EffectSprite {
  glm::vec3 centre{0.0f};  ///< metres
  float radius = 0.1f;     ///< metres, > 0
  glm::vec3 colour{1.0f};  ///< albedo, lit by the frame's lights and environment
  float opacity = 1.0f;    ///< [0, 1] at its centre
  float underside = 0.0f;  ///< [0, 1]: how much darker its lower edge is than its upper (smoke)
};

/// A line (rigging) whose width follows the distance; thinner than a pixel, it is drawn a pixel
/// wide and that much fainter.
struct EffectLine {
  glm::vec3 from{0.0f};
  glm::vec3 to{0.0f};
  float width = 0.02f;  ///< metres, > 0
  glm::vec3 colour{0.1f};
  float opacity = 1.0f;
};

/// A flat, two-sided triangle (debris).
struct EffectTriangle {
  std::array<glm::vec3, 3> corners{};
  glm::vec3 colour{0.5f};
};

/// What the effects pass draws this frame, over the opaque scene.
struct EffectsFrame {
  std::vector<EffectSprite> sprites;
  std::vector<EffectLine> lines;
  std::vector<EffectTriangle> triangles;

  [[nodiscard]] bool empty() const { return sprites.empty() && lines.empty() && triangles.empty(); }
};

struct StaticScene {
  std::optional<EnvironmentData> environment;  ///< none: the flat background and ambient of FrameInput
  std::optional<OceanData> ocean;
  std::vector<MeshData> meshes;
  std::vector<MaterialData> materials;
  std::vector<HairGroomData> grooms;  ///< drawn after the surfaces; guides via Renderer::updateHair
  HairShadowSettings hairShadows;
  std::vector<FurSurfaceData> furs;
};

struct MeshInstance {
  std::size_t mesh = 0;
  std::size_t material = 0;
  glm::mat4 model{1.0f};  ///< object → world, metres
};

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 1.0f};  ///< metres, world space
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float verticalFovRadians = 0.7f;
  float nearPlane = 0.01f;  ///< metres
  float farPlane = 100.0f;  ///< metres

  glm::mat4 view() const;
  /// Right-handed, depth 0..1, Y flipped for Vulkan's downward framebuffer Y.
  glm::mat4 projection(float aspect) const;
};

struct DirectionalLight {
  glm::vec3 direction{0.0f, 0.0f, 1.0f};  ///< unit vector from the surface towards the light
  glm::vec3 color{1.0f};                  ///< linear RGB
  float intensity = 1.0f;                 ///< irradiance scale at normal incidence
  /// Radians: the angular radius of the light's disc, seen where the background shows it
  /// (render/passes/light_disc_pass.hpp); 0: not seen.
  float discRadius = 0.0f;
  /// The disc's radiance as a multiple of `color`, ≥ 0.
  float discRadiance = 20.0f;
};

/// How the post chain maps HDR colour to display values (render/passes/post_pass.hpp).
enum class ToneMapping : std::uint32_t {
  kLinear = 0,    ///< colour × gain, clamped to [0, 1]: the simple scale
  kReinhard = 1,  ///< Reinhard et al. 2002, eq. 3: L_d = L/(1 + L) on the scaled luminance, colour × L_d/L
};

/// HDR post-processing of a frame, after NVIDIA's "Timbury" demo (docs/design.md#sources): a soft
/// glow, automatic gain control and tone mapping. The defaults keep the plain path: colour ×
/// FrameInput::exposure, clamped, no glow, no extra passes.
struct PostSettings {
  ToneMapping toneMapping = ToneMapping::kLinear;
  /// Automatic gain control: gain = exposure · key / L̄ with L̄ the log-average luminance of a tiny
  /// copy of the frame, adapted over time; off: gain = exposure.
  bool autoGain = false;
  /// a, the display value the log-average luminance maps to (Reinhard et al. 2002, §3.1: 0.18 for
  /// a normal key, 0.09 low, 0.36 or 0.72 high). > 0.
  float key = 0.18f;
  /// Share of the blurred image in the displayed colour, 0..1 (Timbury mixes about half and half);
  /// 0 skips the glow passes.
  float glowStrength = 0.0f;
  /// τ, seconds: the adaptation's time constant; each frame L̄ moves 1 − exp(−Δt/τ) of the way (in
  /// log luminance) towards this frame's value. 0 follows the frame at once. ≥ 0.
  float adaptationSeconds = 0.5f;
  /// Δt, seconds since the previous frame. ≥ 0.
  float frameSeconds = 1.0f / 30.0f;
  /// Snap L̄ to this frame's value (a cut); the first frame with auto gain always snaps.
  bool resetAdaptation = false;
  /// God rays: strength of the light shafts added to the HDR colour, ≥ 0; 0 skips
  /// their passes. They stream from the screen position of FrameInput::lights[godRayLight] (a
  /// directional light, at infinity); none when there is no light or it is behind the camera or
  /// off-screen.
  float godRays = 0.0f;
  /// Which of FrameInput::lights the god rays stream from (one with a visible disc gives them
  /// something bright to stream from: DirectionalLight::discRadius).
  std::uint32_t godRayLight = 0;
  /// Luminance (linear HDR units, before the gain) above which a texel emits rays; below it, and
  /// anything dark, occludes. ≥ 0.
  float godRayThreshold = 1.0f;
  /// Per-tap decay of the radial blur along each ray, in (0, 1]: lower gives shorter shafts.
  float godRayDecay = 0.96f;
};

/// What changes every frame.
struct FrameInput {
  Camera camera;
  /// The sea's phases where StaticScene::ocean is set (required there).
  std::optional<OceanFrame> ocean;
  /// Particles, lines and debris drawn over the opaque scene.
  EffectsFrame effects;
  std::vector<DirectionalLight> lights;
  std::vector<MeshInstance> instances;
  glm::vec3 ambient{0.03f};  ///< linear RGB added to every lit surface
  glm::vec3 background{0.02f, 0.022f, 0.028f};
  float exposure = 1.0f;  ///< linear scale before the tone map and the sRGB encode (× the auto gain where on)
  PostSettings post;
  /// Fur materials as shells and fins; off: as Lambert surfaces textured with their photo.
  bool furShells = true;
  /// Spectacle lenses, drawn over the scene refracting it (render/passes/glasses_pass.hpp).
  std::vector<Lens> lenses;
  /// Soft shadows of the surfaces from the first light, as wide as its disc
  /// (render/passes/surface_shadow_pass.hpp); off: only hair and fur shadow the surfaces.
  bool surfaceShadows = true;
};

/// GPU time of each pass of one frame, in milliseconds, in the order the passes ran.
struct PassTiming {
  PassName pass;
  double milliseconds = 0.0;
  /// When the pass began, after the frame's first timestamp. On lavapipe the gaps between passes
  /// are not idle: it rasterizes a render pass's draws when the pass ends, and their cost can fall
  /// between one timer's end and the next one's begin. What a group of passes costs is the span
  /// from the first one's begin to the last one's end, not the sum of their timers.
  double startMilliseconds = 0.0;
};

}  // namespace mane::render
