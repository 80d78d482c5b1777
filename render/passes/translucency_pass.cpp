#include "render/passes/translucency_pass.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "render/descriptors.hpp"

namespace mane::render {

TranslucencyPass::TranslucencyPass(const Device& device)
    : device_(&device), lightDepth_(device, SurfaceScene::kVertexStride) {
  // A mesh's thickness table: its grid, nearest surface voxels, pair thicknesses.
  const vk::ShaderStageFlags fragment = vk::ShaderStageFlagBits::eFragment;
  thicknessLayout_ = makeSetLayout(device, {{vk::DescriptorType::eUniformBuffer, fragment},
                                            {vk::DescriptorType::eStorageBuffer, fragment},
                                            {vk::DescriptorType::eStorageBuffer, fragment}});
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

TranslucencyPass::MeshTables TranslucencyPass::trianglesOf(const MeshData& mesh, bool keep) {
  MeshTables tables;
  if (keep && !mesh.dynamic && mesh.skinning == nullptr) {
    tables.positions.assign(mesh.positions.begin(), mesh.positions.end());
    tables.triangles.assign(mesh.indices.begin(), mesh.indices.end());
  }
  return tables;
}

void TranslucencyPass::setScene(const StaticScene& scene) {
  voxelMaterials_ = std::any_of(scene.materials.begin(), scene.materials.end(), [](const MaterialData& m) {
    return m.translucency.method == TranslucencyMethod::kVoxelLut;
  });
  meshes_.clear();
  for (const MeshData& mesh : scene.meshes) meshes_.push_back(trianglesOf(mesh, voxelMaterials_));
}

void TranslucencyPass::replaceMesh(std::size_t mesh, const MeshData& data) {
  meshes_.at(mesh) = trianglesOf(data, voxelMaterials_);
}

const TranslucencyPass::Thickness* TranslucencyPass::thicknessOf(const MeshInstance& instance,
                                                                 const SurfaceScene& scene) const {
  const TranslucencyParameters& translucency = scene.material(instance).translucency;
  if (translucency.method != TranslucencyMethod::kVoxelLut) return nullptr;
  const std::map<int, Thickness>& tables = meshes_.at(instance.mesh).thickness;
  const auto found = tables.find(translucency.voxelResolution);
  return found == tables.end() ? nullptr : &found->second;
}

const vk::raii::DescriptorSet& TranslucencyPass::thicknessSet(const MeshInstance& instance,
                                                              const SurfaceScene& scene) const {
  const Thickness* thickness = thicknessOf(instance, scene);
  return thickness ? thickness->set : emptyThickness_;
}

Result<void> TranslucencyPass::prepareThickness(const FrameInput& frame, const SurfaceScene& scene) {
  for (const MeshInstance& instance : frame.instances) {
    const TranslucencyParameters& translucency = scene.material(instance).translucency;
    if (translucency.method != TranslucencyMethod::kVoxelLut || thicknessOf(instance, scene)) continue;
    MeshTables& mesh = meshes_[instance.mesh];
    const std::string name = "mesh " + std::to_string(instance.mesh);
    if (scene.isDeforming(instance.mesh))
      return fail(name + ": voxel translucency needs a static mesh, and this one is dynamic or skinned");
    const int resolution = translucency.voxelResolution;
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

bool TranslucencyPass::drawsTranslucency(const FrameInput& frame, const SurfaceScene& scene) const {
  return std::any_of(frame.instances.begin(), frame.instances.end(), [&](const MeshInstance& instance) {
    return scene.material(instance).translucency.method != TranslucencyMethod::kNone;
  });
}

void TranslucencyPass::prepareLightDepth(const FrameInput& frame, const SurfaceScene& scene) {
  lightDepthDraws_.clear();
  DrawnBounds bounds;
  for (const MeshInstance& instance : frame.instances) {
    if (scene.material(instance).translucency.method == TranslucencyMethod::kNone || scene.isDeforming(instance.mesh))
      continue;
    lightDepthDraws_.push_back({.vertices = scene.vertices(instance.mesh),
                                .indices = scene.indices(instance.mesh),
                                .indexCount = scene.indexCount(instance.mesh),
                                .model = instance.model});
    bounds.add(scene.bounds(instance.mesh), instance.model);
  }
  const glm::vec3 towardLight = frame.lights.empty() ? glm::vec3(0, 1, 0) : glm::normalize(frame.lights[0].direction);
  lightDepth_.prepare(towardLight, bounds.sphere(), !lightDepthDraws_.empty());
}

void TranslucencyPass::declareLightDepth(FrameGraph::Builder& pass) const {
  lightDepth_.declare(pass);
}

void TranslucencyPass::recordLightDepth(const vk::raii::CommandBuffer& commands) const {
  lightDepth_.execute(commands, lightDepthDraws_);
}

void TranslucencyPass::declareReads(FrameGraph::Builder& pass) const {
  pass.read(lightDepth_.image(), ResourceUse::sampled(vk::PipelineStageFlagBits2::eFragmentShader));
}

}  // namespace mane::render
