#include "render/passes/surface_scene.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "render/descriptors.hpp"

#include <stb_image_resize.h>

namespace mane::render {
namespace {

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
  float curvature;  // 1/r per mesh unit
};
static_assert(sizeof(Vertex) == SurfaceScene::kVertexStride);

// std140 mirror of FrameUniforms in shaders/frame_uniforms.glsl.
struct FrameUniforms {
  glm::mat4 viewProjection;
  glm::vec4 cameraPosition;
  glm::vec4 ambient;
  glm::vec4 lightDirection[SurfaceScene::kMaxLights];
  glm::vec4 lightRadiance[SurfaceScene::kMaxLights];
  glm::ivec4 lightCount;
  HairShadowUniforms hairShadows;
  LightDepthUniforms lightDepth;
  glm::vec4 environmentIrradiance[9];  // rgb: E/π's spherical harmonics; all 0 without an environment
  SurfaceShadowUniforms surfaceShadow;
  HairVisibilityPlacement hairVisibility;  // w = 0: no hair volume this frame
};

// Where the hair shadow descriptors start in the frame set (shaders/surface.frag), and the light
// depth map after them (shaders/light_depth.glsl).
constexpr std::uint32_t kFirstShadowBinding = 1;
constexpr std::uint32_t kLightDepthBinding = kFirstShadowBinding + HairShadowPass::kBindings;
static_assert(kLightDepthBinding == 9, "shaders/light_depth.glsl binds the map at 9");
// The environment's specular chain after it (shaders/frame_uniforms.glsl), then the surfaces'
// shadow map twice, read as depths and compared (shaders/surface_shadows.glsl).
constexpr std::uint32_t kEnvironmentSpecularBinding = kLightDepthBinding + 1;
constexpr std::uint32_t kSurfaceShadowDepthBinding = kEnvironmentSpecularBinding + 1;
constexpr std::uint32_t kSurfaceShadowCompareBinding = kSurfaceShadowDepthBinding + 1;
static_assert(kSurfaceShadowCompareBinding == 12, "shaders/surface_shadows.glsl binds the map at 11 and 12");
// The hair's occlusion volume last (shaders/frame_uniforms.glsl).
constexpr std::uint32_t kHairVisibilityBinding = kSurfaceShadowCompareBinding + 1;

// std140 mirror of the Material block of shaders/skin_lights.glsl (set 1, binding 4).
struct MaterialUniforms {
  glm::vec4 baseColor{1.0f};
  glm::ivec4 flags{0};                      // x: normal map
  glm::vec4 skin{0.0f};                     // SkinMaterialConstants::skin
  glm::vec4 blur{0.0f};                     // SkinMaterialConstants::blur
  glm::vec4 extinction{0.0f};               // rgb: σ, 1/m; w: MaterialData::transmission
  glm::vec4 profile[kSkinGaussianCount]{};  // SkinMaterialConstants::profile
  glm::vec4 specularAlbedo[2]{};            // SkinMaterialConstants::specularAlbedo
  glm::vec4 ambientBands[3 * SkinMaterialConstants::kSkinAmbientSamples]{};  // SkinMaterialConstants::ambientBands
};

Image textureOrDefault(const Device& device, const std::optional<TextureData>& texture,
                       const std::uint8_t (&fallback)[4], vk::Format format) {
  if (texture && texture->width > 0 && texture->height > 0)
    return Image::texture(device, texture->width, texture->height, texture->rgba, format);
  return Image::texture(device, 1, 1, fallback, format);
}

// The albedo texture (sRGB) with the specular map's red in its alpha, so that skin takes both in
// one lookup: in the skin's G-buffer pass a second lookup is a measurable share of the frame on
// lavapipe. Alpha is not sRGB-decoded, so the map filters as it did in a UNORM texture of its own.
// A specular map of another size is resampled to the albedo's; without one, alpha is 1.
Image albedoWithSpecular(const Device& device, const std::optional<TextureData>& albedo,
                         const std::optional<TextureData>& specular) {
  const auto given = [](const std::optional<TextureData>& texture) {
    return texture && texture->width > 0 && texture->height > 0;
  };
  static constexpr std::uint8_t kWhite[4] = {255, 255, 255, 255};
  if (!given(albedo) && !given(specular)) return Image::texture(device, 1, 1, kWhite, vk::Format::eR8G8B8A8Srgb);
  const TextureData& shape = given(albedo) ? *albedo : *specular;
  const std::size_t texels = std::size_t(shape.width) * shape.height;
  std::vector<std::uint8_t> rgba(texels * 4, 255);
  if (given(albedo)) std::copy_n(albedo->rgba.begin(), texels * 4, rgba.begin());
  std::vector<std::uint8_t> resized;
  std::span<const std::uint8_t> red;
  if (given(specular)) {
    red = specular->rgba;
    if (specular->width != shape.width || specular->height != shape.height) {
      resized.resize(texels * 4);
      stbir_resize_uint8(specular->rgba.data(), int(specular->width), int(specular->height), 0, resized.data(),
                         int(shape.width), int(shape.height), 0, 4);
      red = resized;
    }
  }
  for (std::size_t i = 0; i < texels; ++i) rgba[4 * i + 3] = red.empty() ? 255 : red[4 * i];
  return Image::texture(device, shape.width, shape.height, rgba, vk::Format::eR8G8B8A8Srgb);
}

}  // namespace

SurfaceScene::SurfaceScene(const Device& device, const HairShadowPass& shadows, const LightDepthPass& lightDepth,
                           const SurfaceShadowPass& surfaceShadows)
    : device_(&device), shadows_(&shadows), lightDepth_(&lightDepth), surfaceShadows_(&surfaceShadows), skin_(device) {
  using Stage = vk::ShaderStageFlagBits;
  // Vertex too: surface.vert includes the same declarations (frame_uniforms.glsl).
  const std::pair shadow{vk::DescriptorType::eCombinedImageSampler, Stage::eVertex | Stage::eFragment};
  frameLayout_ = makeSetLayout(device, {{vk::DescriptorType::eUniformBuffer, Stage::eVertex | Stage::eFragment},
                                        shadow,
                                        shadow,
                                        shadow,
                                        shadow,  // hair shadow opacity, 4 slots
                                        shadow,
                                        shadow,
                                        shadow,
                                        shadow,    // hair shadow first depth, 4 slots
                                        shadow,    // light 0's depth map of translucent surfaces
                                        shadow,    // the environment's specular chain
                                        shadow,    // light 0's depth map of every surface: depths
                                        shadow,    // and comparisons
                                        shadow});  // the hair's occlusion volume
  // albedo (the specular map in its alpha), normal map, pre-integrated skin table, diffused
  // irradiance, constants
  const vk::ShaderStageFlags fragment = Stage::eFragment;
  const std::pair texture{vk::DescriptorType::eCombinedImageSampler, fragment};
  materialLayout_ =
      makeSetLayout(device, {texture, texture, texture, texture, {vk::DescriptorType::eUniformBuffer, fragment}});
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eRepeat, 1.0f);

  frameUniforms_ = Buffer(device, sizeof(FrameUniforms), vk::BufferUsageFlagBits::eUniformBuffer,
                          vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  framePool_ = makeDescriptorPool(device, 1,
                                  {{vk::DescriptorType::eUniformBuffer, 1},
                                   {vk::DescriptorType::eCombinedImageSampler, HairShadowPass::kBindings + 5}});
  frameSet_ = allocateSet(device, framePool_, frameLayout_);
  writeUniformBuffer(device, frameSet_, 0, frameUniforms_);
  writeSampledImage(device, frameSet_, kLightDepthBinding, lightDepth.image().view(), lightDepth.sampler());
  writeSampledImage(device, frameSet_, kSurfaceShadowDepthBinding, surfaceShadows.image().view(),
                    surfaceShadows.depthSampler());
  writeSampledImage(device, frameSet_, kSurfaceShadowCompareBinding, surfaceShadows.image().view(),
                    surfaceShadows.compareSampler());
  // Without an environment the binding holds a black cube, never read.
  noEnvironment_ = uploadCubeWithMips(device, CubeMap{.size = 1,
                                                      .faces = {{{glm::vec3(0.0f)},
                                                                 {glm::vec3(0.0f)},
                                                                 {glm::vec3(0.0f)},
                                                                 {glm::vec3(0.0f)},
                                                                 {glm::vec3(0.0f)},
                                                                 {glm::vec3(0.0f)}}}});
  setEnvironment(nullptr);
  noHairVisibility_ = clearedVisibilityVolume(device, 1);
  hairVisibilitySampler_ = makeVisibilitySampler(device);
  setHairVisibility(nullptr);
  refreshShadows();
}

void SurfaceScene::setHairVisibility(const HairDensityPass* visibility) {
  hairVisibility_ = visibility;
  writeSampledImage(*device_, frameSet_, kHairVisibilityBinding,
                    visibility ? visibility->occlusion().view() : noHairVisibility_.view(),
                    visibility ? visibility->sampler() : hairVisibilitySampler_);
}

void SurfaceScene::setEnvironment(const EnvironmentPass* environment) {
  environmentIrradiance_.reset();
  if (environment) environmentIrradiance_ = environment->irradianceOverPi();
  writeSampledImage(*device_, frameSet_, kEnvironmentSpecularBinding,
                    environment ? environment->specular().image().view() : noEnvironment_.view(),
                    environment ? environment->sampler() : sampler_);
}

GraphicsPipelineSettings SurfaceScene::meshPipeline(vk::Format depthFormat) const {
  return GraphicsPipelineSettings{
      .vertexShader = "surface.vert",
      .vertexBindings = {{.binding = 0, .stride = sizeof(Vertex), .inputRate = vk::VertexInputRate::eVertex}},
      .vertexAttributes = {{0, 0, vk::Format::eR32G32B32Sfloat, offsetof(Vertex, position)},
                           {1, 0, vk::Format::eR32G32B32Sfloat, offsetof(Vertex, normal)},
                           {2, 0, vk::Format::eR32G32Sfloat, offsetof(Vertex, uv)},
                           {3, 0, vk::Format::eR32Sfloat, offsetof(Vertex, curvature)}},
      .dynamicCulling = true,
      .depthFormat = depthFormat,
      .depthTest = true,
      .depthWrite = true,
      .pushConstants = {{vk::ShaderStageFlagBits::eVertex, 0, sizeof(glm::mat4)}}};
}

void SurfaceScene::refreshShadows() {
  shadows_->writeDescriptors(frameSet_, kFirstShadowBinding);
}

void SurfaceScene::setScene(const StaticScene& scene) {
  meshes_.clear();
  materials_.clear();
  materialPool_ = nullptr;
  for (const MeshData& mesh : scene.meshes) meshes_.push_back(uploadMesh(mesh));
  if (!scene.materials.empty()) {
    const auto count = static_cast<std::uint32_t>(scene.materials.size());
    materialPool_ = makeDescriptorPool(
        *device_, count,
        {{vk::DescriptorType::eCombinedImageSampler, 5 * count}, {vk::DescriptorType::eUniformBuffer, count}});
  }
  for (const MaterialData& material : scene.materials) materials_.push_back(uploadMaterial(material));
}

SurfaceScene::GpuMesh SurfaceScene::uploadMesh(const MeshData& mesh) const {
  std::vector<Vertex> vertices(mesh.positions.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    vertices[i] =
        Vertex{mesh.positions[i], mesh.normals.empty() ? glm::vec3(0, 1, 0) : mesh.normals[i],
               mesh.uvs.empty() ? glm::vec2(0) : mesh.uvs[i], mesh.curvatures.empty() ? 0.0f : mesh.curvatures[i]};
  const auto bytes = std::as_bytes(std::span(vertices));
  GpuMesh gpu{.indices = Buffer::withData(*device_, std::as_bytes(mesh.indices), vk::BufferUsageFlagBits::eIndexBuffer),
              .indexCount = static_cast<std::uint32_t>(mesh.indices.size()),
              .vertexCount = vertices.size(),
              .dynamic = mesh.dynamic,
              .skinned = mesh.skinning != nullptr};
  if (mesh.dynamic) {
    // Rewritten by the CPU between frames: host-visible, mapped for its lifetime.
    gpu.vertices = Buffer(*device_, std::max<vk::DeviceSize>(bytes.size(), 4), vk::BufferUsageFlagBits::eVertexBuffer,
                          vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    std::memcpy(gpu.vertices.mapped().data(), bytes.data(), bytes.size());
  } else if (gpu.skinned) {
    // The bind pose until the first skinning dispatch overwrites positions and normals.
    gpu.vertices = Buffer::withData(*device_, bytes,
                                    vk::BufferUsageFlagBits::eVertexBuffer | vk::BufferUsageFlagBits::eStorageBuffer);
  } else {
    gpu.vertices = Buffer::withData(*device_, bytes, vk::BufferUsageFlagBits::eVertexBuffer);
  }
  if (auto sphere = boundingSphere(mesh.positions)) gpu.bounds = *sphere;
  return gpu;
}

SkinnedVertexTarget SurfaceScene::skinnedVertexTarget(std::size_t mesh) const {
  constexpr auto floats = [](std::size_t bytes) { return static_cast<std::uint32_t>(bytes / sizeof(float)); };
  return {.buffer = &meshes_.at(mesh).vertices,
          .stride = floats(sizeof(Vertex)),
          .positionOffset = floats(offsetof(Vertex, position)),
          .normalOffset = floats(offsetof(Vertex, normal))};
}

void SurfaceScene::replaceMesh(std::size_t mesh, const MeshData& data) {
  // The old buffers are released here: the renderer waits for every frame, so no recorded
  // command still reads them.
  meshes_.at(mesh) = uploadMesh(data);
}

SurfaceScene::GpuMaterial SurfaceScene::uploadMaterial(const MaterialData& material) {
  static constexpr std::uint8_t kFlatNormal[4] = {128, 128, 255, 255};
  GpuMaterial gpu{.albedo = albedoWithSpecular(*device_, material.albedo, material.specularMap),
                  .normalMap = textureOrDefault(*device_, material.normalMap, kFlatNormal, vk::Format::eR8G8B8A8Unorm),
                  .surface = {.shading = material.shading,
                              .skin = material.skin,
                              .translucency = material.translucency,
                              .doubleSided = material.doubleSided},
                  .descriptors = allocateSet(*device_, materialPool_, materialLayout_)};
  writeSampledImage(*device_, gpu.descriptors, 0, gpu.albedo, sampler_);
  writeSampledImage(*device_, gpu.descriptors, 1, gpu.normalMap, sampler_);
  MaterialUniforms uniforms{.baseColor = glm::vec4(material.baseColor, 1.0f),
                            .flags = glm::ivec4(material.normalMap ? 1 : 0, 0, 0, 0),
                            .extinction = glm::vec4(material.translucency.extinction, material.transmission)};
  if (material.shading == SurfaceShading::kSkin) {
    const PreintegratedSkinLut& table = skin_.table(material.skin.range);
    writeSampledImage(*device_, gpu.descriptors, 2, table.view(), table.sampler());
    const SkinMaterialConstants skin = SkinShading::constants(material.skin, table);
    uniforms.skin = skin.skin;
    uniforms.blur = skin.blur;
    std::copy(skin.profile.begin(), skin.profile.end(), uniforms.profile);
    std::copy(skin.specularAlbedo.begin(), skin.specularAlbedo.end(), uniforms.specularAlbedo);
    std::copy(skin.ambientBands.begin(), skin.ambientBands.end(), uniforms.ambientBands);
  } else {
    writeSampledImage(*device_, gpu.descriptors, 2, skin_.unreadTable(), sampler_);
  }
  // Until setDiffusedIrradiance: likewise valid and unread.
  writeSampledImage(*device_, gpu.descriptors, 3, gpu.albedo, sampler_);
  gpu.uniforms =
      Buffer::withData(*device_, std::as_bytes(std::span(&uniforms, 1)), vk::BufferUsageFlagBits::eUniformBuffer);
  writeUniformBuffer(*device_, gpu.descriptors, 4, gpu.uniforms);
  return gpu;
}

void SurfaceScene::setDiffusedIrradiance(std::size_t material, const vk::raii::ImageView& view,
                                         const vk::raii::Sampler& sampler) {
  writeSampledImage(*device_, materials_.at(material).descriptors, 3, view, sampler);
}

void SurfaceScene::updateVertices(std::size_t mesh, std::span<const glm::vec3> positions,
                                  std::span<const glm::vec3> normals) {
  GpuMesh& gpu = meshes_.at(mesh);
  if (auto sphere = boundingSphere(positions)) gpu.bounds = *sphere;
  auto* vertices = reinterpret_cast<Vertex*>(gpu.vertices.mapped().data());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    vertices[i].position = positions[i];
    if (!normals.empty()) vertices[i].normal = normals[i];
  }
}

void SurfaceScene::update(const FrameInput& frame, float aspect) {
  FrameUniforms uniforms{};
  uniforms.viewProjection = frame.camera.projection(aspect) * frame.camera.view();
  uniforms.cameraPosition = glm::vec4(frame.camera.position, 1.0f);
  uniforms.ambient = glm::vec4(frame.ambient, 0.0f);
  const std::size_t lights = std::min(frame.lights.size(), kMaxLights);
  for (std::size_t i = 0; i < lights; ++i) {
    uniforms.lightDirection[i] = glm::vec4(glm::normalize(frame.lights[i].direction), 0.0f);
    uniforms.lightRadiance[i] = glm::vec4(frame.lights[i].color * frame.lights[i].intensity, 0.0f);
  }
  uniforms.lightCount = glm::ivec4(static_cast<int>(lights), environmentIrradiance_ ? 1 : 0, 0, 0);
  if (environmentIrradiance_)
    for (std::size_t i = 0; i < 9; ++i)
      uniforms.environmentIrradiance[i] = glm::vec4((*environmentIrradiance_)[i], 0.0f);
  uniforms.hairShadows = shadows_->uniforms();
  uniforms.lightDepth = lightDepth_->uniforms();
  if (frame.surfaceShadows) uniforms.surfaceShadow = surfaceShadows_->uniforms();
  if (hairVisibility_) uniforms.hairVisibility = hairVisibility_->placement();
  std::memcpy(frameUniforms_.mapped().data(), &uniforms, sizeof(uniforms));
}

void SurfaceScene::drawMesh(const vk::raii::CommandBuffer& commands, vk::PipelineLayout layout,
                            const MeshInstance& instance) const {
  const GpuMesh& mesh = meshes_[instance.mesh];
  commands.pushConstants<glm::mat4>(layout, vk::ShaderStageFlagBits::eVertex, 0, instance.model);
  commands.setCullMode(materials_[instance.material].surface.doubleSided ? vk::CullModeFlagBits::eNone
                                                                         : vk::CullModeFlagBits::eBack);
  // A mirroring model matrix turns the mesh's counter-clockwise faces clockwise.
  commands.setFrontFace(glm::determinant(glm::mat3(instance.model)) < 0.0f ? vk::FrontFace::eClockwise
                                                                           : vk::FrontFace::eCounterClockwise);
  commands.bindVertexBuffers(0, {*mesh.vertices.buffer()}, {vk::DeviceSize{0}});
  commands.bindIndexBuffer(*mesh.indices.buffer(), 0, vk::IndexType::eUint32);
  commands.drawIndexed(mesh.indexCount, 1, 0, 0, 0);
}

}  // namespace mane::render
