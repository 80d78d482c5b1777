#include "render/passes/surface_pass.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "render/descriptors.hpp"
#include "render/luts/skin_profile.hpp"
#include "render/render_target.hpp"

#include <stb_image_resize.h>

namespace mane::render {
namespace {

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
  float curvature;  // 1/r per mesh unit
};

// std140 mirror of FrameUniforms in shaders/frame_uniforms.glsl.
struct FrameUniforms {
  glm::mat4 viewProjection;
  glm::vec4 cameraPosition;
  glm::vec4 ambient;
  glm::vec4 lightDirection[SurfacePass::kMaxLights];
  glm::vec4 lightRadiance[SurfacePass::kMaxLights];
  glm::ivec4 lightCount;
  HairShadowUniforms hairShadows;
  LightDepthUniforms lightDepth;
};

// Where the hair shadow descriptors start in the frame set (shaders/surface.frag), and the light
// depth map after them (shaders/light_depth.glsl).
constexpr std::uint32_t kFirstShadowBinding = 1;
constexpr std::uint32_t kLightDepthBinding = kFirstShadowBinding + HairShadows::kBindings;
static_assert(kLightDepthBinding == 9, "shaders/light_depth.glsl binds the map at 9");

// std140 mirror of the Material block of shaders/skin_lights.glsl (set 1, binding 4).
struct MaterialUniforms {
  glm::vec4 baseColor{1.0f};
  glm::ivec4 flags{0};                      // x: normal map
  glm::vec4 skin{0.0f};                     // x: roughness, y: ρs, z: the table's maxCurvature (1/mm)
  glm::vec4 blur{0.0f};                     // rgb: per channel, the weight of the geometric normal (blurred normals)
  glm::vec4 extinction{0.0f};               // rgb: σ, 1/m
  glm::vec4 profile[kSkinGaussianCount]{};  // rgb: weight, a: variance (mm²)
};

// Pores are a few tenths of a millimetre across: light that spreads wider than that (d'Eon's
// Gaussians from σ ≈ 0.43 mm) exits with the geometric normal's shading rather than the pores'.
constexpr double kPoreVariance = 0.187;  // mm²

Image textureOrDefault(const Device& device, const std::optional<TextureData>& texture,
                       const std::uint8_t (&fallback)[4], vk::Format format) {
  if (texture && texture->width > 0 && texture->height > 0)
    return Image::texture(device, texture->width, texture->height, texture->rgba, format);
  return Image::texture(device, 1, 1, fallback, format);
}

// The albedo texture (sRGB) with the specular map's red in its alpha, so that skin takes both in
// one lookup: in the skin's G-buffer pass a lookup of its own cost lavapipe about 2 ms of nalu's
// frame. Alpha is not sRGB-decoded, so the map filters as it did in a UNORM texture of its own.
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

SurfacePass::SurfacePass(const Device& device, const HairShadows& shadows, vk::Format colorFormat,
                         vk::Format depthFormat, vk::SampleCountFlagBits samples)
    : device_(&device), shadows_(&shadows), lightDepth_(device, sizeof(Vertex)) {
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
                                        shadow});  // light 0's depth map of translucent surfaces
  // albedo (the specular map in its alpha), normal map, pre-integrated skin table, diffused
  // irradiance, constants
  const vk::ShaderStageFlags fragment = Stage::eFragment;
  const std::pair texture{vk::DescriptorType::eCombinedImageSampler, fragment};
  materialLayout_ =
      makeSetLayout(device, {texture, texture, texture, texture, {vk::DescriptorType::eUniformBuffer, fragment}});
  static_assert(RenderTarget::kGBufferImages == 4, "shaders/skin_deferred.frag reads four images");
  gBufferLayout_ = makeSetLayout(device, {texture, texture, texture, texture});
  // A mesh's thickness table: its grid, nearest surface voxels, pair thicknesses.
  thicknessLayout_ = makeSetLayout(device, {{vk::DescriptorType::eUniformBuffer, fragment},
                                            {vk::DescriptorType::eStorageBuffer, fragment},
                                            {vk::DescriptorType::eStorageBuffer, fragment}});
  formats_ = {colorFormat, depthFormat, samples};
  buildPipelines();
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eRepeat, 1.0f);

  frameUniforms_ = Buffer(device, sizeof(FrameUniforms), vk::BufferUsageFlagBits::eUniformBuffer,
                          vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  framePool_ = makeDescriptorPool(device, 1,
                                  {{vk::DescriptorType::eUniformBuffer, 1},
                                   {vk::DescriptorType::eCombinedImageSampler, HairShadows::kBindings + 1}});
  frameSet_ = allocateSet(device, framePool_, frameLayout_);
  writeUniformBuffer(device, frameSet_, 0, frameUniforms_);
  writeSampledImage(device, frameSet_, kLightDepthBinding, lightDepth_.image().view(), lightDepth_.sampler());
  refreshShadows();

  const ThicknessGridUniforms noGrid{};
  emptyGrid_ = Buffer::withData(device, std::as_bytes(std::span(&noGrid, 1)), vk::BufferUsageFlagBits::eUniformBuffer);
  const std::uint32_t noWord = 0;
  emptyWords_ = Buffer::withData(device, std::as_bytes(std::span(&noWord, 1)), vk::BufferUsageFlagBits::eStorageBuffer);
  emptyThicknessPool_ =
      makeDescriptorPool(device, 1, {{vk::DescriptorType::eUniformBuffer, 1}, {vk::DescriptorType::eStorageBuffer, 2}});
  emptyThickness_ = allocateSet(device, emptyThicknessPool_, thicknessLayout_);
  writeUniformBuffer(device, emptyThickness_, 0, emptyGrid_);
  writeStorageBuffer(device, emptyThickness_, 1, emptyWords_);
  writeStorageBuffer(device, emptyThickness_, 2, emptyWords_);
}

void SurfacePass::buildPipelines() {
  using Stage = vk::ShaderStageFlagBits;
  // Every pipeline draws the meshes' vertices through surface.vert.
  const GraphicsPipelineSettings meshes{
      .vertexShader = "surface.vert",
      .vertexBindings = {{.binding = 0, .stride = sizeof(Vertex), .inputRate = vk::VertexInputRate::eVertex}},
      .vertexAttributes = {{0, 0, vk::Format::eR32G32B32Sfloat, offsetof(Vertex, position)},
                           {1, 0, vk::Format::eR32G32B32Sfloat, offsetof(Vertex, normal)},
                           {2, 0, vk::Format::eR32G32Sfloat, offsetof(Vertex, uv)},
                           {3, 0, vk::Format::eR32Sfloat, offsetof(Vertex, curvature)}},
      .dynamicCulling = true,
      .depthFormat = formats_.depth,
      .depthTest = true,
      .depthWrite = true,
      .pushConstants = {{Stage::eVertex, 0, sizeof(glm::mat4)}}};
  std::array<bool, kShadings * kTranslucencyMethods> used{};
  used[0] = true;  // Lambert: its layout binds the frame set even when nothing is drawn
  for (const GpuMaterial& material : materials_) used[pipelineFor(material)] = true;
  for (std::size_t variant = 0; variant < pipelines_.size(); ++variant) {
    pipelines_[variant] = {};
    if (!used[variant]) continue;
    const std::size_t shading = variant / kTranslucencyMethods;
    GraphicsPipelineSettings settings = meshes;
    settings.fragmentShader = "surface.frag";
    settings.colorFormats = {formats_.color};
    settings.samples = formats_.samples;
    settings.setLayouts = {*frameLayout_, *materialLayout_, *thicknessLayout_};
    // Constants 0, 1: the hair shadow maps (shaders/hair_shadows.glsl); 2: skin; 3: its diffuse
    // light from the texture-space diffusion instead of the pre-integrated table; 4: the
    // translucency method (shaders/translucency.glsl).
    settings.constants = shadows_->shaderConstants();
    settings.constants.push_back(shading != 0 ? 1u : 0u);
    settings.constants.push_back(shading == 2 ? 1u : 0u);
    settings.constants.push_back(static_cast<std::uint32_t>(variant % kTranslucencyMethods));
    pipelines_[variant] = makeGraphicsPipeline(*device_, settings);
  }
  skinGBufferPipeline_ = {};
  skinShadingPipeline_ = {};
  // Only with a G-buffer to draw into (single-sample targets alone keep one).
  if (!*gBufferSet_ || std::none_of(materials_.begin(), materials_.end(), deferrable)) return;
  GraphicsPipelineSettings gBuffer = meshes;
  gBuffer.fragmentShader = "skin_gbuffer.frag";
  gBuffer.colorFormats.assign(RenderTarget::kGBufferImages, RenderTarget::kGBufferFormat);
  gBuffer.setLayouts = {*frameLayout_, *materialLayout_};
  // As the forward pipeline of deferrable skin: no translucency, the pre-integrated table.
  gBuffer.constants = shadows_->shaderConstants();
  gBuffer.constants.insert(gBuffer.constants.end(), {1u, 0u, 0u});
  skinGBufferPipeline_ = makeGraphicsPipeline(*device_, gBuffer);
  // Over the screen at the far plane (the viewport's depth range, set when drawn): its depth test
  // passes where the G-buffer pass left skin nearer than that.
  skinShadingPipeline_ = makeGraphicsPipeline(
      *device_, GraphicsPipelineSettings{.vertexShader = "fullscreen.vert",
                                         .fragmentShader = "skin_deferred.frag",
                                         .colorFormats = {formats_.color},
                                         .depthFormat = formats_.depth,
                                         .depthTest = true,
                                         .depthCompare = vk::CompareOp::eGreater,
                                         .setLayouts = {*frameLayout_, *materialLayout_, *gBufferLayout_},
                                         .constants = gBuffer.constants});
}

void SurfacePass::refreshShadows() {
  shadows_->writeDescriptors(frameSet_, kFirstShadowBinding);
}

void SurfacePass::setScene(const StaticScene& scene) {
  meshes_.clear();
  materials_.clear();
  materialPool_ = nullptr;
  const bool voxelTranslucency = std::any_of(scene.materials.begin(), scene.materials.end(), [](const MaterialData& m) {
    return m.translucency.method == TranslucencyMethod::kVoxelLut;
  });

  for (const MeshData& mesh : scene.meshes) meshes_.push_back(uploadMesh(mesh, voxelTranslucency));

  if (!scene.materials.empty()) {
    const auto count = static_cast<std::uint32_t>(scene.materials.size());
    materialPool_ = makeDescriptorPool(
        *device_, count,
        {{vk::DescriptorType::eCombinedImageSampler, 5 * count}, {vk::DescriptorType::eUniformBuffer, count}});
  }
  for (const MaterialData& material : scene.materials) materials_.push_back(uploadMaterial(material));
  buildPipelines();  // for the materials and the hair shadows' current maps
}

SurfacePass::GpuMesh SurfacePass::uploadMesh(const MeshData& mesh, bool keepTriangles) const {
  std::vector<Vertex> vertices(mesh.positions.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    vertices[i] =
        Vertex{mesh.positions[i], mesh.normals.empty() ? glm::vec3(0, 1, 0) : mesh.normals[i],
               mesh.uvs.empty() ? glm::vec2(0) : mesh.uvs[i], mesh.curvatures.empty() ? 0.0f : mesh.curvatures[i]};
  const auto bytes = std::as_bytes(std::span(vertices));
  GpuMesh gpu{.indices = Buffer::withData(*device_, std::as_bytes(mesh.indices), vk::BufferUsageFlagBits::eIndexBuffer),
              .indexCount = static_cast<std::uint32_t>(mesh.indices.size()),
              .vertexCount = vertices.size(),
              .dynamic = mesh.dynamic};
  if (mesh.dynamic) {
    // Rewritten by the CPU between frames: host-visible, mapped for its lifetime.
    gpu.vertices = Buffer(*device_, std::max<vk::DeviceSize>(bytes.size(), 4), vk::BufferUsageFlagBits::eVertexBuffer,
                          vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    std::memcpy(gpu.vertices.mapped().data(), bytes.data(), bytes.size());
  } else {
    gpu.vertices = Buffer::withData(*device_, bytes, vk::BufferUsageFlagBits::eVertexBuffer);
    if (auto sphere = boundingSphere(mesh.positions)) gpu.bounds = *sphere;
    if (keepTriangles) {
      gpu.positions.assign(mesh.positions.begin(), mesh.positions.end());
      gpu.triangles.assign(mesh.indices.begin(), mesh.indices.end());
    }
  }
  return gpu;
}

void SurfacePass::replaceMesh(std::size_t mesh, const MeshData& data) {
  const bool voxelTranslucency = std::any_of(materials_.begin(), materials_.end(), [](const GpuMaterial& m) {
    return m.translucency.method == TranslucencyMethod::kVoxelLut;
  });
  // The old buffers and tables are released here: the renderer waits for every frame, so no
  // recorded command still reads them.
  meshes_.at(mesh) = uploadMesh(data, voxelTranslucency);
}

SurfacePass::GpuMaterial SurfacePass::uploadMaterial(const MaterialData& material) {
  static constexpr std::uint8_t kFlatNormal[4] = {128, 128, 255, 255};
  GpuMaterial gpu{.albedo = albedoWithSpecular(*device_, material.albedo, material.specularMap),
                  .normalMap = textureOrDefault(*device_, material.normalMap, kFlatNormal, vk::Format::eR8G8B8A8Unorm),
                  .shading = material.shading,
                  .skin = material.skin,
                  .translucency = material.translucency,
                  .doubleSided = material.doubleSided,
                  .descriptors = allocateSet(*device_, materialPool_, materialLayout_)};
  writeSampledImage(*device_, gpu.descriptors, 0, gpu.albedo, sampler_);
  writeSampledImage(*device_, gpu.descriptors, 1, gpu.normalMap, sampler_);
  MaterialUniforms uniforms{.baseColor = glm::vec4(material.baseColor, 1.0f),
                            .flags = glm::ivec4(material.normalMap ? 1 : 0, 0, 0, 0),
                            .extinction = glm::vec4(material.translucency.extinction, 0.0f)};
  if (material.shading == SurfaceShading::kSkin) {
    const PreintegratedSkinLut& table = skinTable(material.skin.range);
    writeSampledImage(*device_, gpu.descriptors, 2, table.view(), table.sampler());
    const SkinProfile& profile = table.settings().profile;
    uniforms.skin =
        glm::vec4(material.skin.roughness, material.skin.specularIntensity, float(table.settings().maxCurvature), 0.0f);
    uniforms.blur = glm::vec4(glm::vec3(profile.broadShare(kPoreVariance)), 0.0f);
    for (std::size_t i = 0; i < kSkinGaussianCount; ++i)
      uniforms.profile[i] = glm::vec4(glm::vec3(profile.gaussians[i].weight), float(profile.gaussians[i].variance));
  } else {
    writeSampledImage(*device_, gpu.descriptors, 2, unreadSkinTable(), sampler_);
  }
  // Until setDiffusedIrradiance: likewise valid and unread.
  writeSampledImage(*device_, gpu.descriptors, 3, gpu.albedo, sampler_);
  gpu.uniforms =
      Buffer::withData(*device_, std::as_bytes(std::span(&uniforms, 1)), vk::BufferUsageFlagBits::eUniformBuffer);
  writeUniformBuffer(*device_, gpu.descriptors, 4, gpu.uniforms);
  return gpu;
}

const PreintegratedSkinLut& SurfacePass::skinTable(SkinIntegrationRange range) {
  auto& table = skinTables_[range == SkinIntegrationRange::kPenner ? 0 : 1];
  if (!table) {
    auto baked = PreintegratedSkinLut::create(*device_, {.range = range});
    if (!baked) throw std::runtime_error("baking the pre-integrated skin table: " + baked.error().message);
    table = std::make_unique<PreintegratedSkinLut>(std::move(*baked));
  }
  return *table;
}

const Image& SurfacePass::unreadSkinTable() {
  if (!unreadSkinTable_) {
    unreadSkinTable_ = std::make_unique<Image>(*device_, ImageSettings{.extent = {1, 1},
                                                                       .format = PreintegratedSkinLut::kFormat,
                                                                       .usage = vk::ImageUsageFlagBits::eSampled,
                                                                       .layers = PreintegratedSkinLut::kLayers});
    device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      transition(commands, *unreadSkinTable_, vk::ImageLayout::eUndefined, vk::ImageLayout::eShaderReadOnlyOptimal,
                 vk::PipelineStageFlagBits2::eNone, vk::AccessFlagBits2::eNone,
                 vk::PipelineStageFlagBits2::eFragmentShader, vk::AccessFlagBits2::eShaderSampledRead);
    });
  }
  return *unreadSkinTable_;
}

void SurfacePass::setDiffusedIrradiance(std::size_t material, const vk::raii::ImageView& view,
                                        const vk::raii::Sampler& sampler) {
  writeSampledImage(*device_, materials_.at(material).descriptors, 3, view, sampler);
}

std::size_t SurfacePass::pipelineFor(const GpuMaterial& material) {
  std::size_t shading = 0;
  if (material.shading == SurfaceShading::kSkin)
    shading = material.skin.diffusion == SkinDiffusion::kTextureSpace ? 2 : 1;
  return shading * kTranslucencyMethods + static_cast<std::size_t>(material.translucency.method);
}

const SurfacePass::Thickness* SurfacePass::thicknessOf(const GpuMesh& mesh, const GpuMaterial& material) const {
  if (material.translucency.method != TranslucencyMethod::kVoxelLut) return nullptr;
  const auto found = mesh.thickness.find(material.translucency.voxelResolution);
  return found == mesh.thickness.end() ? nullptr : &found->second;
}

Result<void> SurfacePass::prepareThickness(const FrameInput& frame) {
  for (const MeshInstance& instance : frame.instances) {
    const GpuMaterial& material = materials_[instance.material];
    GpuMesh& mesh = meshes_[instance.mesh];
    if (material.translucency.method != TranslucencyMethod::kVoxelLut || thicknessOf(mesh, material)) continue;
    const std::string name = "mesh " + std::to_string(instance.mesh);
    if (mesh.dynamic) return fail(name + ": voxel translucency needs a static mesh, and this one is dynamic");
    const int resolution = material.translucency.voxelResolution;
    // The table is one storage buffer: the device's range caps it (128 MiB on lavapipe: a cube
    // at N = 40, 9,128 surface voxels, needs 167 MB).
    // (Less a word: an odd count of halves is padded to whole words.)
    const std::size_t maxTableBytes = std::min<std::size_t>(device_->limits().maxStorageBufferRange - 4, 1u << 30);
    auto lut = VoxelThicknessLut::build(mesh.positions, mesh.triangles,
                                        {.resolution = resolution, .maxTableBytes = maxTableBytes});
    if (!lut)
      return fail(name + ": its voxel thickness table at N = " + std::to_string(resolution) + ": " +
                  lut.error().message);
    try {
      Thickness thickness{.table = std::make_unique<ThicknessTable>(*device_, *lut)};
      thickness.pool = makeDescriptorPool(
          *device_, 1, {{vk::DescriptorType::eUniformBuffer, 1}, {vk::DescriptorType::eStorageBuffer, 2}});
      thickness.set = allocateSet(*device_, thickness.pool, thicknessLayout_);
      writeUniformBuffer(*device_, thickness.set, 0, thickness.table->grid());
      writeStorageBuffer(*device_, thickness.set, 1, thickness.table->nearest());
      writeStorageBuffer(*device_, thickness.set, 2, thickness.table->table());
      mesh.thickness.emplace(resolution, std::move(thickness));
    } catch (const std::exception& error) {
      return fail(name + ": uploading its voxel thickness table failed: " + error.what());
    }
  }
  return {};
}

bool SurfacePass::drawsTranslucency(const FrameInput& frame) const {
  return std::any_of(frame.instances.begin(), frame.instances.end(), [&](const MeshInstance& instance) {
    return materials_[instance.material].translucency.method != TranslucencyMethod::kNone;
  });
}

void SurfacePass::recordLightDepth(const vk::raii::CommandBuffer& commands, const FrameInput& frame) {
  std::vector<LightDepthDraw> draws;
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const MeshInstance& instance : frame.instances) {
    const GpuMesh& mesh = meshes_[instance.mesh];
    if (materials_[instance.material].translucency.method == TranslucencyMethod::kNone || mesh.dynamic) continue;
    draws.push_back({.vertices = *mesh.vertices.buffer(),
                     .indices = *mesh.indices.buffer(),
                     .indexCount = mesh.indexCount,
                     .model = instance.model});
    // The mesh's sphere placed in the world: centre moved, radius by the largest axis scale.
    const glm::vec3 centre = glm::vec3(instance.model * glm::vec4(mesh.bounds.centre, 1.0f));
    const float scale = std::max({glm::length(glm::vec3(instance.model[0])), glm::length(glm::vec3(instance.model[1])),
                                  glm::length(glm::vec3(instance.model[2]))});
    lo = glm::min(lo, centre - mesh.bounds.radius * scale);
    hi = glm::max(hi, centre + mesh.bounds.radius * scale);
  }
  const glm::vec3 towardLight = frame.lights.empty() ? glm::vec3(0, 1, 0) : glm::normalize(frame.lights[0].direction);
  BoundingSphere bounds{.centre = glm::vec3(0.0f), .radius = 1.0f};
  if (!draws.empty()) bounds = {.centre = 0.5f * (lo + hi), .radius = 0.5f * glm::length(hi - lo) * 1.001f};
  lightDepth_.record(commands, draws, towardLight, bounds);
}

void SurfacePass::updateVertices(std::size_t mesh, std::span<const glm::vec3> positions,
                                 std::span<const glm::vec3> normals) {
  auto* vertices = reinterpret_cast<Vertex*>(meshes_.at(mesh).vertices.mapped().data());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    vertices[i].position = positions[i];
    if (!normals.empty()) vertices[i].normal = normals[i];
  }
}

void SurfacePass::update(const FrameInput& frame, float aspect) {
  FrameUniforms uniforms{};
  uniforms.viewProjection = frame.camera.projection(aspect) * frame.camera.view();
  uniforms.cameraPosition = glm::vec4(frame.camera.position, 1.0f);
  uniforms.ambient = glm::vec4(frame.ambient, 0.0f);
  const std::size_t lights = std::min(frame.lights.size(), kMaxLights);
  for (std::size_t i = 0; i < lights; ++i) {
    uniforms.lightDirection[i] = glm::vec4(glm::normalize(frame.lights[i].direction), 0.0f);
    uniforms.lightRadiance[i] = glm::vec4(frame.lights[i].color * frame.lights[i].intensity, 0.0f);
  }
  uniforms.lightCount = glm::ivec4(static_cast<int>(lights), 0, 0, 0);
  uniforms.hairShadows = shadows_->uniforms();
  uniforms.lightDepth = lightDepth_.uniforms();
  std::memcpy(frameUniforms_.mapped().data(), &uniforms, sizeof(uniforms));
}

void SurfacePass::draw(const vk::raii::CommandBuffer& commands, const FrameInput& frame, bool skinDeferred) const {
  // Every pipeline shares one layout.
  const vk::PipelineLayout layout = *pipelines_[0].layout;
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 0, {*frameSet_}, {});
  const Pipeline* bound = nullptr;
  for (const MeshInstance& instance : frame.instances) {
    const GpuMesh& mesh = meshes_[instance.mesh];
    const GpuMaterial& material = materials_[instance.material];
    if (material.shading == SurfaceShading::kFur && frame.furShells) continue;  // the fur pass draws its skin
    if (skinDeferred && deferrable(material)) continue;                         // drawn into the G-buffer
    const Pipeline& pipeline = pipelines_[pipelineFor(material)];
    if (bound != &pipeline) commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline.pipeline);
    bound = &pipeline;
    const Thickness* thickness = thicknessOf(mesh, material);
    commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 1,
                                {*material.descriptors, thickness ? *thickness->set : *emptyThickness_}, {});
    drawMesh(commands, layout, instance);
  }
}

void SurfacePass::drawMesh(const vk::raii::CommandBuffer& commands, vk::PipelineLayout layout,
                           const MeshInstance& instance) const {
  const GpuMesh& mesh = meshes_[instance.mesh];
  commands.pushConstants<glm::mat4>(layout, vk::ShaderStageFlagBits::eVertex, 0, instance.model);
  commands.setCullMode(materials_[instance.material].doubleSided ? vk::CullModeFlagBits::eNone
                                                                 : vk::CullModeFlagBits::eBack);
  // A mirroring model matrix turns the mesh's counter-clockwise faces clockwise.
  commands.setFrontFace(glm::determinant(glm::mat3(instance.model)) < 0.0f ? vk::FrontFace::eClockwise
                                                                           : vk::FrontFace::eCounterClockwise);
  commands.bindVertexBuffers(0, {*mesh.vertices.buffer()}, {vk::DeviceSize{0}});
  commands.bindIndexBuffer(*mesh.indices.buffer(), 0, vk::IndexType::eUint32);
  commands.drawIndexed(mesh.indexCount, 1, 0, 0, 0);
}

bool SurfacePass::deferrable(const GpuMaterial& material) {
  return material.shading == SurfaceShading::kSkin && material.skin.diffusion != SkinDiffusion::kTextureSpace &&
         material.translucency.method == TranslucencyMethod::kNone;
}

std::optional<std::size_t> SurfacePass::deferredMaterial(const FrameInput& frame) const {
  std::optional<std::size_t> found;
  for (const MeshInstance& instance : frame.instances) {
    if (!deferrable(materials_[instance.material])) continue;
    if (found && *found != instance.material) return std::nullopt;
    found = instance.material;
  }
  return found;
}

void SurfacePass::setSkinGBuffer(std::span<const Image> gBuffer) {
  if (gBuffer.size() != RenderTarget::kGBufferImages)
    throw std::invalid_argument("setSkinGBuffer: the G-buffer needs " + std::to_string(RenderTarget::kGBufferImages) +
                                " images, got " + std::to_string(gBuffer.size()));
  gBufferPool_ =
      makeDescriptorPool(*device_, 1, {{vk::DescriptorType::eCombinedImageSampler, RenderTarget::kGBufferImages}});
  gBufferSet_ = allocateSet(*device_, gBufferPool_, gBufferLayout_);
  for (std::size_t i = 0; i < gBuffer.size(); ++i)
    writeSampledImage(*device_, gBufferSet_, static_cast<std::uint32_t>(i), gBuffer[i], sampler_);
  gBufferExtent_ = gBuffer.front().extent();
}

bool SurfacePass::defersSkin(const FrameInput& frame) const {
  return *skinShadingPipeline_.pipeline && *gBufferSet_ && deferredMaterial(frame).has_value();
}

void SurfacePass::drawSkinGBuffer(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const {
  const vk::PipelineLayout layout = *skinGBufferPipeline_.layout;
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *skinGBufferPipeline_.pipeline);
  const GpuMaterial& material = materials_[*deferredMaterial(frame)];
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 0, {*frameSet_, *material.descriptors}, {});
  for (const MeshInstance& instance : frame.instances)
    if (deferrable(materials_[instance.material])) drawMesh(commands, layout, instance);
}

void SurfacePass::drawSkinLighting(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const {
  const GpuMaterial& material = materials_[*deferredMaterial(frame)];
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *skinShadingPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *skinShadingPipeline_.layout, 0,
                              {*frameSet_, *material.descriptors, *gBufferSet_}, {});
  commands.setViewport(0, vk::Viewport{.width = float(gBufferExtent_.width),
                                       .height = float(gBufferExtent_.height),
                                       .minDepth = 1.0f,
                                       .maxDepth = 1.0f});
  commands.draw(3, 1, 0, 0);
  setViewportAndScissor(commands, gBufferExtent_);
}

}  // namespace mane::render
