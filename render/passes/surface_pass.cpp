#include "render/passes/surface_pass.hpp"

#include <cstring>
#include <stdexcept>

#include "render/descriptors.hpp"

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
};

// Where the hair shadow descriptors start in the frame set (shaders/surface.frag).
constexpr std::uint32_t kFirstShadowBinding = 1;

// Push constants of shaders/surface.{vert,frag}.
struct DrawConstants {
  glm::mat4 model;
  glm::vec4 baseColor;
  glm::ivec4 flags;  // x: normal map
  glm::vec4 skin;    // x: roughness, y: ρs, z: the table's maxCurvature (1/mm)
  glm::vec4 blur;    // rgb: per channel, the weight of the geometric normal (blurred normals)
};
static_assert(sizeof(DrawConstants) <= 128, "Vulkan guarantees 128 bytes of push constants");

// Pores are a few tenths of a millimetre across: light that spreads wider than that (d'Eon's
// Gaussians from σ ≈ 0.43 mm) exits with the geometric normal's shading rather than the pores'.
constexpr double kPoreVariance = 0.187;  // mm²

Image textureOrDefault(const Device& device, const std::optional<TextureData>& texture,
                       const std::uint8_t (&fallback)[4], vk::Format format) {
  if (texture && texture->width > 0 && texture->height > 0)
    return Image::texture(device, texture->width, texture->height, texture->rgba, format);
  return Image::texture(device, 1, 1, fallback, format);
}

}  // namespace

SurfacePass::SurfacePass(const Device& device, const HairShadows& shadows, vk::Format colorFormat,
                         vk::Format depthFormat, vk::SampleCountFlagBits samples)
    : device_(&device), shadows_(&shadows) {
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
                                        shadow});  // hair shadow first depth, 4 slots
  // albedo, normal map, specular map, pre-integrated skin table, diffused irradiance
  const std::pair texture{vk::DescriptorType::eCombinedImageSampler, vk::ShaderStageFlags(Stage::eFragment)};
  materialLayout_ = makeSetLayout(device, {texture, texture, texture, texture, texture});
  formats_ = {colorFormat, depthFormat, samples};
  buildPipelines();
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eRepeat, 1.0f);

  frameUniforms_ = Buffer(device, sizeof(FrameUniforms), vk::BufferUsageFlagBits::eUniformBuffer,
                          vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  framePool_ = makeDescriptorPool(
      device, 1,
      {{vk::DescriptorType::eUniformBuffer, 1}, {vk::DescriptorType::eCombinedImageSampler, HairShadows::kBindings}});
  frameSet_ = allocateSet(device, framePool_, frameLayout_);
  writeUniformBuffer(device, frameSet_, 0, frameUniforms_);
  refreshShadows();
}

void SurfacePass::buildPipelines() {
  using Stage = vk::ShaderStageFlagBits;
  for (std::size_t variant = 0; variant < pipelines_.size(); ++variant) {
    // Constants 0, 1: the hair shadow maps (shaders/hair_shadows.glsl); 2: skin; 3: its diffuse
    // light from the texture-space diffusion instead of the pre-integrated table.
    SpecializationConstants constants = shadows_->shaderConstants();
    constants.push_back(variant != kLambertPipeline ? 1u : 0u);
    constants.push_back(variant == kTextureSpaceSkinPipeline ? 1u : 0u);
    Pipeline& pipeline = pipelines_[variant];
    pipeline = makeGraphicsPipeline(
        *device_,
        GraphicsPipelineSettings{
            .vertexShader = "surface.vert",
            .fragmentShader = "surface.frag",
            .vertexBindings = {{.binding = 0, .stride = sizeof(Vertex), .inputRate = vk::VertexInputRate::eVertex}},
            .vertexAttributes = {{0, 0, vk::Format::eR32G32B32Sfloat, offsetof(Vertex, position)},
                                 {1, 0, vk::Format::eR32G32B32Sfloat, offsetof(Vertex, normal)},
                                 {2, 0, vk::Format::eR32G32Sfloat, offsetof(Vertex, uv)},
                                 {3, 0, vk::Format::eR32Sfloat, offsetof(Vertex, curvature)}},
            .cullMode = vk::CullModeFlagBits::eNone,
            .colorFormats = {formats_.color},
            .depthFormat = formats_.depth,
            .depthTest = true,
            .depthWrite = true,
            .samples = formats_.samples,
            .setLayouts = {*frameLayout_, *materialLayout_},
            .pushConstants = {{Stage::eVertex | Stage::eFragment, 0, sizeof(DrawConstants)}},
            .constants = constants});
  }
}

void SurfacePass::refreshShadows() {
  shadows_->writeDescriptors(frameSet_, kFirstShadowBinding);
}

void SurfacePass::setScene(const StaticScene& scene) {
  buildPipelines();  // for the hair shadows' current maps
  meshes_.clear();
  materials_.clear();
  materialPool_ = nullptr;

  for (const MeshData& mesh : scene.meshes) {
    std::vector<Vertex> vertices(mesh.positions.size());
    for (std::size_t i = 0; i < vertices.size(); ++i)
      vertices[i] =
          Vertex{mesh.positions[i], mesh.normals.empty() ? glm::vec3(0, 1, 0) : mesh.normals[i],
                 mesh.uvs.empty() ? glm::vec2(0) : mesh.uvs[i], mesh.curvatures.empty() ? 0.0f : mesh.curvatures[i]};
    const auto bytes = std::as_bytes(std::span(vertices));
    GpuMesh gpu{
        .indices = Buffer::withData(*device_, std::as_bytes(mesh.indices), vk::BufferUsageFlagBits::eIndexBuffer),
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
    }
    meshes_.push_back(std::move(gpu));
  }

  if (scene.materials.empty()) return;
  const auto count = static_cast<std::uint32_t>(scene.materials.size());
  materialPool_ = makeDescriptorPool(*device_, count, {{vk::DescriptorType::eCombinedImageSampler, 5 * count}});
  static constexpr std::uint8_t kWhite[4] = {255, 255, 255, 255};
  static constexpr std::uint8_t kFlatNormal[4] = {128, 128, 255, 255};
  for (const MaterialData& material : scene.materials) {
    GpuMaterial gpu{
        .albedo = textureOrDefault(*device_, material.albedo, kWhite, vk::Format::eR8G8B8A8Srgb),
        .normalMap = textureOrDefault(*device_, material.normalMap, kFlatNormal, vk::Format::eR8G8B8A8Unorm),
        .specularMap = textureOrDefault(*device_, material.specularMap, kWhite, vk::Format::eR8G8B8A8Unorm),
        .hasNormalMap = material.normalMap.has_value(),
        .baseColor = material.baseColor,
        .shading = material.shading,
        .skin = material.skin,
        .descriptors = allocateSet(*device_, materialPool_, materialLayout_)};
    writeSampledImage(*device_, gpu.descriptors, 0, gpu.albedo, sampler_);
    writeSampledImage(*device_, gpu.descriptors, 1, gpu.normalMap, sampler_);
    writeSampledImage(*device_, gpu.descriptors, 2, gpu.specularMap, sampler_);
    if (material.shading == SurfaceShading::kSkin) {
      const PreintegratedSkinLut& table = skinTable(material.skin.range);
      writeSampledImage(*device_, gpu.descriptors, 3, table.view(), table.sampler());
      gpu.skinConstants = glm::vec4(material.skin.roughness, material.skin.specularIntensity,
                                    float(table.settings().maxCurvature), 0.0f);
      gpu.blur = glm::vec4(glm::vec3(table.settings().profile.broadShare(kPoreVariance)), 0.0f);
    } else {
      // Never read by Lambert materials, but every binding must hold a valid image.
      writeSampledImage(*device_, gpu.descriptors, 3, gpu.albedo, sampler_);
    }
    // Until setDiffusedIrradiance: likewise valid and unread.
    writeSampledImage(*device_, gpu.descriptors, 4, gpu.albedo, sampler_);
    materials_.push_back(std::move(gpu));
  }
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

void SurfacePass::setDiffusedIrradiance(std::size_t material, const vk::raii::ImageView& view,
                                        const vk::raii::Sampler& sampler) {
  writeSampledImage(*device_, materials_.at(material).descriptors, 4, view, sampler);
}

std::size_t SurfacePass::pipelineFor(const GpuMaterial& material) {
  if (material.shading != SurfaceShading::kSkin) return kLambertPipeline;
  return material.skin.diffusion == SkinDiffusion::kTextureSpace ? kTextureSpaceSkinPipeline : kSkinPipeline;
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
  std::memcpy(frameUniforms_.mapped().data(), &uniforms, sizeof(uniforms));
}

void SurfacePass::draw(const vk::raii::CommandBuffer& commands, const FrameInput& frame) const {
  // Both pipelines share one layout.
  const vk::PipelineLayout layout = *pipelines_[0].layout;
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 0, {*frameSet_}, {});
  const Pipeline* bound = nullptr;
  for (const MeshInstance& instance : frame.instances) {
    const GpuMesh& mesh = meshes_[instance.mesh];
    const GpuMaterial& material = materials_[instance.material];
    const Pipeline& pipeline = pipelines_[pipelineFor(material)];
    if (bound != &pipeline) commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline.pipeline);
    bound = &pipeline;
    commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 1, {*material.descriptors}, {});
    const DrawConstants constants{instance.model, glm::vec4(material.baseColor, 1.0f),
                                  glm::ivec4(material.hasNormalMap ? 1 : 0, 0, 0, 0), material.skinConstants,
                                  material.blur};
    commands.pushConstants<DrawConstants>(layout, vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment,
                                          0, constants);
    commands.bindVertexBuffers(0, {*mesh.vertices.buffer()}, {vk::DeviceSize{0}});
    commands.bindIndexBuffer(*mesh.indices.buffer(), 0, vk::IndexType::eUint32);
    commands.drawIndexed(mesh.indexCount, 1, 0, 0, 0);
  }
}

}  // namespace mane::render
