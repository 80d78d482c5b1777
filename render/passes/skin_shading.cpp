#include "render/passes/skin_shading.hpp"

#include <stdexcept>

#include "render/luts/preintegrated_skin.hpp"
#include "render/luts/skin_specular.hpp"

namespace mane::render {
namespace {

// Pores are a few tenths of a millimetre across: light that spreads wider than that (d'Eon's
// Gaussians from σ ≈ 0.43 mm) exits with the geometric normal's shading rather than the pores'.
constexpr double kPoreVariance = 0.187;  // mm²

}  // namespace

const PreintegratedSkinLut& SkinShading::table(SkinIntegrationRange range) {
  auto& table = tables_[range == SkinIntegrationRange::kPenner ? 0 : 1];
  if (!table) {
    auto baked = PreintegratedSkinLut::create(*device_, {.range = range});
    if (!baked) throw std::runtime_error("baking the pre-integrated skin table: " + baked.error().message);
    table = std::make_unique<PreintegratedSkinLut>(std::move(*baked));
  }
  return *table;
}

const Image& SkinShading::unreadTable() {
  if (!unreadTable_) {
    unreadTable_ = std::make_unique<Image>(*device_, ImageSettings{.extent = {1, 1},
                                                                   .format = PreintegratedSkinLut::kFormat,
                                                                   .usage = vk::ImageUsageFlagBits::eSampled,
                                                                   .layers = PreintegratedSkinLut::kLayers});
    device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      transition(commands, *unreadTable_, vk::ImageLayout::eUndefined, vk::ImageLayout::eShaderReadOnlyOptimal,
                 vk::PipelineStageFlagBits2::eNone, vk::AccessFlagBits2::eNone,
                 vk::PipelineStageFlagBits2::eFragmentShader, vk::AccessFlagBits2::eShaderSampledRead);
    });
  }
  return *unreadTable_;
}

SkinMaterialConstants SkinShading::constants(const SkinParameters& skin, const PreintegratedSkinLut& table) {
  const SkinProfile& profile = table.settings().profile;
  SkinMaterialConstants constants{
      .skin = glm::vec4(skin.roughness, skin.specularIntensity, float(table.settings().maxCurvature), 0.0f),
      .blur = glm::vec4(glm::vec3(profile.broadShare(kPoreVariance)), 0.0f)};
  for (std::size_t i = 0; i < kSkinGaussianCount; ++i)
    constants.profile[i] = glm::vec4(glm::vec3(profile.gaussians[i].weight), float(profile.gaussians[i].variance));
  for (int k = 0; k < 8; ++k)
    constants.specularAlbedo[std::size_t(k / 4)][k % 4] = float(kelemenSzirmayKalosAlbedo(k / 7.0, skin.roughness));
  constexpr std::size_t kSamples = SkinMaterialConstants::kSkinAmbientSamples;
  for (std::size_t i = 0; i < kSamples; ++i) {
    const double share = double(i) / double(kSamples - 1);
    const auto bands =
        preintegratedAmbientBands(profile, table.settings().range, table.settings().maxCurvature * share * share);
    for (std::size_t l = 0; l < 3; ++l) constants.ambientBands[kSamples * l + i] = glm::vec4(glm::vec3(bands[l]), 0.0f);
  }
  return constants;
}

}  // namespace mane::render
