#pragma once
// Skin's share of the surface materials (shaders/surface.frag, shaders/preintegrated_skin.glsl):
//  - diffuse: the pre-integrated table (render/luts/preintegrated_skin_lut.hpp) in place of
//    max(N·L, 0), looked up per RGB at the vertex curvature (MeshData::curvatures, converted to
//    1/mm with the instance's scale: world units are metres);
//  - blurred normals per channel (Penner & Borshukov 2011): channel c reads N·L with
//    normalize(mix(N_detail, N_geometric, w_c)); w_c is the share of the channel's profile
//    weight in d'Eon's Gaussians of variance ≥ 0.187 mm² (σ ≥ 0.43 mm, wider than pores;
//    SkinProfile::broadShare): (0.667, 0.209, 0.007) — red light has left the pores' scale
//    before it exits, blue has not;
//  - the environment's irradiance: each spherical-harmonic band scaled as the profile scatters
//    it at the curvature (preintegratedAmbientBands), through the blurred normals;
//  - specular: Kelemen/Szirmay-Kalos with the table's Beckmann term and Schlick's Fresnel
//    (F0 = 0.028) on the detail normal, ρs scaled by the specular map's red channel; under an
//    environment, its pre-filtered radiance in the reflected direction (GGX of α = the Beckmann
//    roughness, close to it at skin's roughness) times the BRDF's albedo at N·V (a split sum).
// The tables are baked once per integration range, when a scene first needs one. Skin diffused
// in texture space (render/passes/skin_diffusion_pass.hpp) reads its diffuse light from the diffused
// irradiance instead (SurfaceScene::setDiffusedIrradiance); it is drawn forward
// (render/passes/surface_pass.hpp), and pre-integrated skin where it is not deferred
// (render/passes/deferred_skin_pass.hpp).

#include <array>
#include <memory>

#include <glm/vec4.hpp>

#include "render/frame.hpp"
#include "render/luts/preintegrated_skin_lut.hpp"
#include "render/luts/skin_profile.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// The skin constants of a material block (`Material` in shaders/skin_lights.glsl).
struct SkinMaterialConstants {
  glm::vec4 skin{0.0f};  ///< x: roughness, y: ρs, z: the table's maxCurvature (1/mm)
  glm::vec4 blur{0.0f};  ///< rgb: per channel, the weight of the geometric normal (blurred normals)
  std::array<glm::vec4, kSkinGaussianCount> profile{};  ///< rgb: weight, a: variance (mm²)
  /// The specular's albedo with ρs = 1 (kelemenSzirmayKalosAlbedo) at N·V = 0, 1/7, …, 1, in
  /// order: what scales the environment's pre-filtered radiance.
  std::array<glm::vec4, 2> specularAlbedo{};
  /// rgb: preintegratedAmbientBands' factor of band ℓ at curvature maxCurvature·(i/15)², at
  /// [kSkinAmbientSamples·ℓ + i]: the samples crowd where skin's curvatures lie.
  static constexpr std::size_t kSkinAmbientSamples = 16;
  std::array<glm::vec4, 3 * kSkinAmbientSamples> ambientBands{};
};

class SkinShading {
public:
  /// `device` must outlive the tables.
  explicit SkinShading(const Device& device) : device_(&device) {}

  /// The pre-integrated table for `range`, baked the first time a scene asks for it. Throws
  /// std::runtime_error when it cannot be baked.
  const PreintegratedSkinLut& table(SkinIntegrationRange range);
  /// What materials that never read the skin table bind in its place, made on first use: the
  /// binding must hold an image of the type the shader declares, a 2D array.
  const Image& unreadTable();

  /// The constants of a skin material with parameters `skin`, read through `table`.
  [[nodiscard]] static SkinMaterialConstants constants(const SkinParameters& skin, const PreintegratedSkinLut& table);

private:
  const Device* device_;
  std::array<std::unique_ptr<PreintegratedSkinLut>, 2> tables_;  ///< Penner, curvature-dependent
  std::unique_ptr<Image> unreadTable_;
};

}  // namespace mane::render
