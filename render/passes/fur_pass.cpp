#include "render/passes/fur_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "render/descriptors.hpp"
#include "render/passes/mesh_welding.hpp"

namespace mane::render {
namespace {

// std140 mirror of FurUniforms in shaders/fur_common.glsl.
struct FurUniforms {
  glm::mat4 model;
  glm::mat4 normalMatrix;
  glm::mat4 viewProjection;
  glm::vec4 eye;
  glm::vec4 lightDirection;
  glm::vec4 lightRadiance;
  glm::vec4 ambient;
  glm::vec4 shells;    // x: h_b, y: N, z: Kajiya-Kay exponent, w: specular strength
  glm::vec4 lay;       // x: cos, y: sin of the lay angle, z: the model's scale
  glm::vec4 layField;  // xyz: the fur-direction field (model space), w: photo repeats per metre (0: by uvs)
  glm::vec4 tint;      // rgb: multiplies the photo's colour
  glm::vec4 comb;      // xyz: world lean of the fur's top, in units of h_b, before its projection on the surface
  std::array<glm::vec4, 9> environment;  // rgb: E/π's harmonics
  std::array<float, 4 * 17> thresholds;
  HairShadowUniforms shadows;
};
static_assert((kMaxFurLayers + 1) <= 4 * 17, "shaders/fur_common.glsl holds I(0 … 64)");
static_assert(sizeof(FurUniforms) == 3 * 64 + 18 * 16 + 17 * 16 + sizeof(HairShadowUniforms));

// Binding of the first hair shadow image (shaders/fur_common.glsl); 2 × 4 of them.
constexpr std::uint32_t kFirstShadowBinding = 5;

// The mesh as both passes read it (shaders/fur_fin.vert: 8 floats per vertex).
struct FurVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
};
static_assert(sizeof(FurVertex) == 8 * sizeof(float));

constexpr std::uint32_t kVerticesPerFin = 6;

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// Constants 0, 1: the hair shadow maps (shaders/hair_shadows.glsl); 2: the coverage; 3: whether
// the pipeline draws the skin layer alone (shaders/fur_shell.frag).
SpecializationConstants pipelineConstants(const FurPassSettings& settings, const SpecializationConstants& shadows,
                                          bool skinLayer = false) {
  SpecializationConstants constants = shadows;
  constants.push_back(static_cast<std::uint32_t>(settings.coverage));
  constants.push_back(skinLayer ? 1u : 0u);
  return constants;
}

Pipeline makeShellPipeline(const Device& device, const FurPassSettings& settings,
                           const vk::raii::DescriptorSetLayout& layout, const SpecializationConstants& shadows,
                           bool skinLayer) {
  using Format = vk::Format;
  return makeGraphicsPipeline(
      device,
      GraphicsPipelineSettings{
          .vertexShader = "fur_shell.vert",
          .fragmentShader = "fur_shell.frag",
          .vertexBindings = {{.binding = 0, .stride = sizeof(FurVertex), .inputRate = vk::VertexInputRate::eVertex}},
          .vertexAttributes =
              {{.location = 0, .binding = 0, .format = Format::eR32G32B32Sfloat, .offset = 0},
               {.location = 1, .binding = 0, .format = Format::eR32G32B32Sfloat, .offset = offsetof(FurVertex, normal)},
               {.location = 2, .binding = 0, .format = Format::eR32G32Sfloat, .offset = offsetof(FurVertex, uv)}},
          .dynamicCulling = true,
          .colorFormats = {settings.colorFormat},
          .depthFormat = settings.depthFormat,
          .depthTest = true,
          .depthWrite = true,
          .samples = settings.samples,
          .setLayouts = {*layout},
          .constants = pipelineConstants(settings, shadows, skinLayer)});
}

Pipeline makeFinPipeline(const Device& device, const FurPassSettings& settings,
                         const vk::raii::DescriptorSetLayout& layout, const SpecializationConstants& shadows) {
  return makeGraphicsPipeline(device, GraphicsPipelineSettings{.vertexShader = "fur_fin.vert",
                                                               .fragmentShader = "fur_fin.frag",
                                                               .colorFormats = {settings.colorFormat},
                                                               .depthFormat = settings.depthFormat,
                                                               .depthTest = true,
                                                               .depthWrite = true,
                                                               .samples = settings.samples,
                                                               .setLayouts = {*layout},
                                                               .constants = pipelineConstants(settings, shadows)});
}

}  // namespace

glm::vec3 furShadowTangent(const glm::vec3& normal) {
  return glm::normalize(std::abs(normal.x) < 0.9f ? glm::cross(normal, glm::vec3(1.0f, 0.0f, 0.0f))
                                                  : glm::cross(normal, glm::vec3(0.0f, 1.0f, 0.0f)));
}

// ---------------------------------------------------------------------------------------------
// Silhouette edges

Result<MeshEdges> MeshEdges::build(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices) {
  if (indices.size() % 3 != 0)
    return fail("fur mesh edges: " + std::to_string(indices.size()) + " indices, not a multiple of 3");
  struct Faces {
    std::uint32_t count = 0;
    std::uint32_t a = 0, b = 0;  // the first face's vertices (their uvs texture the fin)
    std::array<glm::vec3, 2> normals{};
    std::array<std::uint32_t, 2> triangles{};
  };
  for (std::size_t t = 0; t < indices.size(); ++t)
    if (indices[t] >= positions.size())
      return fail("fur mesh edges: triangle " + std::to_string(t / 3) + " names vertex " + std::to_string(indices[t]) +
                  " of " + std::to_string(positions.size()));
  // Vertices split at uv seams share a position: edges are matched by position so that a seam
  // is not taken for a boundary.
  const std::vector<std::uint32_t> canonical = weldByPosition(positions);
  std::unordered_map<std::uint64_t, Faces> faces;
  std::vector<std::uint64_t> order;  // first appearance: a deterministic edge order
  for (std::size_t t = 0; t < indices.size(); t += 3) {
    const std::array<std::uint32_t, 3> v{indices[t], indices[t + 1], indices[t + 2]};
    const glm::vec3 cross = glm::cross(positions[v[1]] - positions[v[0]], positions[v[2]] - positions[v[0]]);
    const float length = glm::length(cross);
    if (!(length > 0.0f)) continue;  // degenerate: no normal, no silhouette
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      const std::uint64_t key = edgeKey(canonical[a], canonical[b]);
      Faces& entry = faces[key];
      if (entry.count == 0) {
        order.push_back(key);
        entry.a = a;
        entry.b = b;
      }
      if (entry.count < 2) {
        entry.normals[entry.count] = cross / length;
        entry.triangles[entry.count] = static_cast<std::uint32_t>(t / 3);
      }
      ++entry.count;
    }
  }
  MeshEdges result;
  result.edges_.reserve(order.size());
  for (const std::uint64_t key : order) {
    const Faces& entry = faces[key];
    if (entry.count > 2) continue;
    Edge edge;
    edge.a = entry.a;
    edge.b = entry.b;
    edge.midpoint = 0.5f * (positions[edge.a] + positions[edge.b]);
    edge.normalA = entry.normals[0];
    edge.boundary = entry.count == 1;
    edge.normalB = edge.boundary ? entry.normals[0] : entry.normals[1];
    edge.faceA = entry.triangles[0];
    edge.faceB = edge.boundary ? entry.triangles[0] : entry.triangles[1];
    result.edges_.push_back(edge);
  }
  result.triangles_.assign(indices.begin(), indices.end());
  result.vertexCount_ = positions.size();
  return result;
}

Result<void> MeshEdges::reshape(std::span<const glm::vec3> positions) {
  if (positions.size() != vertexCount_)
    return fail("fur mesh edges: " + std::to_string(positions.size()) + " positions for a mesh of " +
                std::to_string(vertexCount_));
  const auto faceNormal = [&](std::uint32_t face, const glm::vec3& previous) {
    const glm::vec3& p0 = positions[triangles_[3 * face]];
    const glm::vec3 cross =
        glm::cross(positions[triangles_[3 * face + 1]] - p0, positions[triangles_[3 * face + 2]] - p0);
    const float length = glm::length(cross);
    return length > 0.0f ? cross / length : previous;
  };
  for (Edge& edge : edges_) {
    edge.midpoint = 0.5f * (positions[edge.a] + positions[edge.b]);
    edge.normalA = faceNormal(edge.faceA, edge.normalA);
    edge.normalB = faceNormal(edge.faceB, edge.normalB);
  }
  return {};
}

void MeshEdges::findSilhouette(const glm::vec4& eye, std::vector<glm::uvec2>& out) const {
  out.clear();
  const glm::vec3 eyePoint(eye);
  for (const Edge& edge : edges_) {
    const glm::vec3 toEye = eyePoint - eye.w * edge.midpoint;
    if (edge.boundary || glm::dot(edge.normalA, toEye) * glm::dot(edge.normalB, toEye) <= 0.0f)
      out.emplace_back(edge.a, edge.b);
  }
}

// ---------------------------------------------------------------------------------------------
// The pass

Result<std::unique_ptr<FurPass>> FurPass::create(const Device& device, const FurPassSettings& settings,
                                                 const TextureData& photo, const FurShellSettings& shells,
                                                 const HairShadowPass* shadows) {
  if (settings.depthFormat == vk::Format::eUndefined)
    return fail("fur pass: a depth format is required (the shells composite by depth testing)");
  auto model = FurShellModel::fromPhoto(photo, shells);
  if (!model) return fail("fur pass: " + model.error().message);
  try {
    return std::unique_ptr<FurPass>(new FurPass(device, settings, photo, *model, shadows));
  } catch (const std::exception& error) {
    return fail(std::string("fur pass: Vulkan error while creating it: ") + error.what());
  }
}

FurPass::FurPass(const Device& device, const FurPassSettings& settings, const TextureData& photo, FurShellModel model,
                 const HairShadowPass* shadows)
    : device_(&device), shadows_(shadows), settings_(settings), model_(model) {
  if (shadows_ == nullptr) {
    auto empty = HairShadowPass::create(device);
    if (!empty) throw std::runtime_error(empty.error().message);
    ownShadows_ = std::move(*empty);
    shadows_ = ownShadows_.get();
  }
  using Stage = vk::ShaderStageFlagBits;
  using Type = vk::DescriptorType;
  photo_ = Image::texture(device, photo.width, photo.height,
                          photo.rgba.first(std::size_t(photo.width) * photo.height * 4), vk::Format::eR8G8B8A8Srgb);
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eRepeat, 1.0f);
  // The shells are lit per vertex, the fins per fragment: both read the hair shadows.
  const std::pair shadowMap{Type::eCombinedImageSampler, vk::ShaderStageFlags(Stage::eVertex | Stage::eFragment)};
  setLayout_ = makeSetLayout(device, {{Type::eUniformBuffer, Stage::eVertex | Stage::eFragment},
                                      {Type::eCombinedImageSampler, Stage::eFragment},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      shadowMap,  // hair shadows: opacity × 4
                                      shadowMap,
                                      shadowMap,
                                      shadowMap,
                                      shadowMap,  // first depth × 4
                                      shadowMap,
                                      shadowMap,
                                      shadowMap});
  static_assert(HairShadowPass::kBindings == 8);
  buildPipelines();
  pool_ = makeDescriptorPool(device, 1,
                             {{Type::eUniformBuffer, 1},
                              {Type::eCombinedImageSampler, 1 + HairShadowPass::kBindings},
                              {Type::eStorageBuffer, 3}});
  set_ = allocateSet(device, pool_, setLayout_);
  uniforms_ = Buffer(device, sizeof(FurUniforms), vk::BufferUsageFlagBits::eUniformBuffer,
                     vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  writeUniformBuffer(device, set_, 0, uniforms_);
  writeSampledImage(device, set_, 1, photo_, sampler_);
  shadows_->writeDescriptors(set_, kFirstShadowBinding);
  std::memset(uniforms_.mapped().data(), 0, sizeof(FurUniforms));
}

void FurPass::buildPipelines() {
  shadowConstants_ = shadows_->shaderConstants();
  skinPipeline_ = makeShellPipeline(*device_, settings_, setLayout_, shadowConstants_, true);
  shellPipeline_ = makeShellPipeline(*device_, settings_, setLayout_, shadowConstants_, false);
  if (settings_.fins) finPipeline_ = makeFinPipeline(*device_, settings_, setLayout_, shadowConstants_);
}

void FurPass::refreshShadows() {
  if (shadows_->shaderConstants() != shadowConstants_) buildPipelines();
  shadows_->writeDescriptors(set_, kFirstShadowBinding);
}

void FurPass::setShadowUniforms(const HairShadowUniforms& uniforms) {
  std::memcpy(uniforms_.mapped().data() + offsetof(FurUniforms, shadows), &uniforms, sizeof(uniforms));
}

void FurPass::writeShadowStrands(const glm::mat4& model, const glm::vec3& comb) {
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
  std::vector<glm::vec4> points(2 * meshPositions_.size());
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  shadowColumnWidth_ = meanEdgeLength_ * glm::length(glm::vec3(model[0]));
  const float across = 0.5f * shadowColumnWidth_;  // half a column, world
  for (std::size_t v = 0; v < meshPositions_.size(); ++v) {
    // As shaders/fur_shell.vert puts the top shell (s = 1): p + h_b·(n + lean); then tilted
    // across the column (shadowStrands()).
    const glm::vec3 normal = glm::normalize(normalMatrix * meshNormals_[v]);
    const glm::vec3 lean = comb - glm::dot(comb, normal) * normal + vertexLeans_[v];
    const glm::vec3 tangent = furShadowTangent(normal);
    const glm::vec3 root = glm::vec3(model * glm::vec4(meshPositions_[v], 1.0f)) - across * tangent;
    const glm::vec3 tip = root + model_.thickness() * (normal + lean) + 2.0f * across * tangent;
    points[2 * v] = glm::vec4(root, 1.0f);
    points[2 * v + 1] = glm::vec4(tip, 1.0f);
    lo = glm::min(lo, glm::min(root, tip));
    hi = glm::max(hi, glm::max(root, tip));
  }
  std::memcpy(shadowStrands_.mapped().data(), points.data(), points.size() * sizeof(glm::vec4));
  shadowBounds_ = {.centre = 0.5f * (lo + hi), .radius = 0.5f * glm::length(hi - lo) * 1.001f + 1e-6f};
  if (auto tight = boundingSphere(std::span<const glm::vec4>(points))) furBounds_ = *tight;
}

Result<void> FurPass::setMesh(const MeshData& mesh) {
  const std::size_t count = mesh.positions.size();
  if (count == 0 || mesh.indices.empty()) return fail("fur mesh: no vertices or no triangles");
  if (mesh.normals.size() != count || mesh.uvs.size() != count)
    return fail("fur mesh: needs one normal and one uv per position (" + std::to_string(count) + " positions, " +
                std::to_string(mesh.normals.size()) + " normals, " + std::to_string(mesh.uvs.size()) + " uvs)");
  auto edges = MeshEdges::build(mesh.positions, mesh.indices);
  if (!edges) return fail(edges.error().message);
  std::vector<FurVertex> vertices(count);
  for (std::size_t i = 0; i < count; ++i) vertices[i] = {mesh.positions[i], mesh.normals[i], mesh.uvs[i]};
  double edgeSum = 0.0;
  for (const MeshEdges::Edge& edge : edges->edges())
    edgeSum += glm::distance(mesh.positions[edge.a], mesh.positions[edge.b]);
  try {
    vertices_ = Buffer::withData(*device_, std::as_bytes(std::span(vertices)),
                                 vk::BufferUsageFlagBits::eVertexBuffer | vk::BufferUsageFlagBits::eStorageBuffer);
    indices_ = Buffer::withData(*device_, std::as_bytes(mesh.indices), vk::BufferUsageFlagBits::eIndexBuffer);
    // Room for a fin on every edge: the most a view can ask for, so the buffer never grows.
    finEdges_ = Buffer(*device_, std::max<std::size_t>(edges->edges().size(), 1) * sizeof(glm::uvec2),
                       vk::BufferUsageFlagBits::eStorageBuffer,
                       vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    leans_ = Buffer(*device_, count * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer,
                    vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    std::memset(leans_.mapped().data(), 0, count * sizeof(glm::vec4));
    shadowStrands_ = Buffer(*device_, 2 * count * sizeof(glm::vec4),
                            vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer,
                            vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  } catch (const vk::SystemError& error) {
    return fail(std::string("fur mesh: Vulkan error while uploading it: ") + error.what());
  }
  writeStorageBuffer(*device_, set_, 2, vertices_);
  writeStorageBuffer(*device_, set_, 3, finEdges_);
  writeStorageBuffer(*device_, set_, 4, leans_);
  vertexCount_ = static_cast<std::uint32_t>(count);
  meshPositions_.assign(mesh.positions.begin(), mesh.positions.end());
  meshNormals_.assign(mesh.normals.begin(), mesh.normals.end());
  vertexLeans_.assign(count, glm::vec3(0.0f));
  meanEdgeLength_ = edges->edges().empty() ? 0.0f : float(edgeSum / double(edges->edges().size()));
  // Columns across the map: the square root of the surface's area in columns (on a sphere about
  // its diameter in columns, 2√π·r against 2·r). Unlike its extent, the area barely changes as
  // a skinned mesh bends, so the map stays the same however the body is posed.
  double area = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  const double columnsAcross = meanEdgeLength_ > 0.0f ? std::sqrt(area) / meanEdgeLength_ : 0.0;
  // Rounded up to a multiple of 8 texels, so that a slightly different area gives the same map.
  const double texels = 8.0 * std::ceil(columnsAcross / 8.0);
  shadowResolution_ = static_cast<std::uint32_t>(std::clamp(texels, 16.0, 4096.0));
  writeShadowStrands(glm::mat4(1.0f), glm::vec3(0.0f));
  indexCount_ = static_cast<std::uint32_t>(mesh.indices.size());
  edges_ = std::move(*edges);
  fins_.clear();
  fins_.reserve(edges_.edges().size());
  finCount_ = 0;
  return {};
}

Result<void> FurPass::setPose(std::span<const glm::vec4> positions, std::span<const glm::vec4> normals) {
  if (positions.size() != vertexCount_ || normals.size() != vertexCount_)
    return fail("fur pose: " + std::to_string(positions.size()) + " positions and " + std::to_string(normals.size()) +
                " normals for a mesh of " + std::to_string(vertexCount_) + " vertices");
  std::vector<glm::vec3> shape(vertexCount_);
  for (std::size_t i = 0; i < shape.size(); ++i) {
    shape[i] = glm::vec3(positions[i]);
    const glm::vec3 normal(normals[i]);
    if (!std::isfinite(shape[i].x + shape[i].y + shape[i].z + normal.x + normal.y + normal.z))
      return fail("fur pose: vertex " + std::to_string(i) + " is not finite");
  }
  if (auto reshaped = edges_.reshape(shape); !reshaped) return reshaped;
  for (std::size_t i = 0; i < shape.size(); ++i) meshNormals_[i] = glm::vec3(normals[i]);
  meshPositions_ = std::move(shape);
  return {};
}

SkinnedVertexTarget FurPass::vertexTarget() const {
  constexpr auto floats = [](std::size_t bytes) { return static_cast<std::uint32_t>(bytes / sizeof(float)); };
  return {.buffer = &vertices_,
          .stride = floats(sizeof(FurVertex)),
          .positionOffset = floats(offsetof(FurVertex, position)),
          .normalOffset = floats(offsetof(FurVertex, normal))};
}

Result<void> FurPass::setLeans(std::span<const glm::vec3> leans) {
  if (leans.size() != vertexCount_)
    return fail("fur leans: " + std::to_string(leans.size()) + " for a mesh of " + std::to_string(vertexCount_) +
                " vertices");
  std::vector<glm::vec4> padded(leans.size());
  for (std::size_t i = 0; i < leans.size(); ++i) {
    if (!std::isfinite(leans[i].x) || !std::isfinite(leans[i].y) || !std::isfinite(leans[i].z))
      return fail("fur leans: vertex " + std::to_string(i) + "'s lean is not finite");
    padded[i] = glm::vec4(leans[i], 0.0f);
  }
  vertexLeans_.assign(leans.begin(), leans.end());
  std::memcpy(leans_.mapped().data(), padded.data(), padded.size() * sizeof(glm::vec4));
  return {};
}

Result<void> FurPass::setShells(std::uint32_t layers, float thickness) {
  auto model = FurShellModel::create(model_.range(), layers, thickness);
  if (!model) return fail(model.error().message);
  model_ = *model;
  return {};
}

Result<void> FurPass::update(const FurView& view) {
  if (view.extent.width == 0 || view.extent.height == 0) return fail("fur view: the extent is empty");
  if (!finite(view.model) || !finite(view.viewProjection) || std::abs(glm::determinant(view.model)) == 0.0f)
    return fail("fur view: the model matrix is singular or a matrix is not finite");
  FurUniforms uniforms{};
  uniforms.model = view.model;
  uniforms.normalMatrix = glm::mat4(glm::transpose(glm::inverse(glm::mat3(view.model))));
  uniforms.viewProjection = view.viewProjection;
  uniforms.eye = view.eye;
  uniforms.lightDirection = glm::vec4(glm::normalize(view.light.direction), 0.0f);
  uniforms.lightRadiance = glm::vec4(view.light.color * view.light.intensity, 0.0f);
  uniforms.ambient = glm::vec4(view.ambient, 0.0f);
  uniforms.lay = glm::vec4(std::cos(view.look.layAngle), std::sin(view.look.layAngle),
                           glm::length(glm::vec3(view.model[0])), 0.0f);
  const bool field = glm::length(view.look.layDirection) > 0.0f;
  uniforms.layField =
      field ? glm::vec4(glm::normalize(view.look.layDirection), view.look.layRepeatsPerMetre) : glm::vec4(0.0f);
  uniforms.tint = glm::vec4(view.look.tint, 1.0f);
  uniforms.comb = glm::vec4(view.look.comb, 0.0f);
  for (std::size_t i = 0; i < 9; ++i) uniforms.environment[i] = glm::vec4(view.environment[i], 0.0f);
  if (vertexCount_ > 0) writeShadowStrands(view.model, view.look.comb);
  // About one shell per `pixelsPerLayer` of the fur's height on screen: where it is a few pixels
  // tall, shells closer together than a pixel add cost and no parallax.
  drawnLayers_ = model_.layers();
  if (view.look.pixelsPerLayer > 0.0f && vertexCount_ > 0) {
    const float wanted = std::ceil(furHeightInPixels(view) / view.look.pixelsPerLayer);
    drawnLayers_ = std::uint32_t(std::clamp(wanted, 1.0f, float(model_.layers())));
  }
  // The drawn shells split the same photo over their own count: Ukaji et al.'s thresholds for N'.
  const auto drawn = FurShellModel::create(model_.range(), drawnLayers_, model_.thickness());
  if (!drawn) return fail("fur view: " + drawn.error().message);
  uniforms.shells =
      glm::vec4(model_.thickness(), float(drawnLayers_), view.look.specularExponent, view.look.specularStrength);
  const std::vector<float> thresholds = drawn->thresholds();
  std::copy(thresholds.begin(), thresholds.end(), uniforms.thresholds.begin());
  // The shadows' part is setShadowUniforms'.
  std::memcpy(uniforms_.mapped().data(), &uniforms, offsetof(FurUniforms, shadows));

  finCount_ = 0;
  if (settings_.fins && indexCount_ > 0) {
    // The eye in object space, where the edges' face normals are.
    const glm::vec4 eye = glm::inverse(view.model) * view.eye;
    edges_.findSilhouette(eye, fins_);
    std::memcpy(finEdges_.mapped().data(), fins_.data(), fins_.size() * sizeof(glm::uvec2));
    finCount_ = static_cast<std::uint32_t>(fins_.size());
  }
  extent_ = view.extent;
  cullMode_ = view.look.doubleSided ? vk::CullModeFlagBits::eNone : vk::CullModeFlagBits::eBack;
  // A mirroring model matrix turns the mesh's counter-clockwise faces clockwise.
  frontFace_ =
      glm::determinant(glm::mat3(view.model)) < 0.0f ? vk::FrontFace::eClockwise : vk::FrontFace::eCounterClockwise;
  updated_ = true;
  return {};
}

float FurPass::furHeightInPixels(const FurView& view) const {
  // The point of the fur's bounding sphere nearest the eye, and a step of h_b across the view
  // there, both projected.
  const glm::vec3 centre = furBounds_.centre;
  const glm::vec3 towardEye = view.eye.w > 0.0f ? glm::vec3(view.eye) - centre : glm::vec3(view.eye);
  const float distance = glm::length(towardEye);
  if (!(distance > furBounds_.radius)) return std::numeric_limits<float>::infinity();  // the eye is inside
  const glm::vec3 toward = towardEye / distance;
  const glm::vec3 nearest = centre + furBounds_.radius * toward;
  const glm::vec3 across = furShadowTangent(toward);
  const glm::vec4 a = view.viewProjection * glm::vec4(nearest, 1.0f);
  const glm::vec4 b = view.viewProjection * glm::vec4(nearest + model_.thickness() * across, 1.0f);
  if (!(a.w > 0.0f && b.w > 0.0f)) return std::numeric_limits<float>::infinity();
  const glm::vec2 pixels =
      (glm::vec2(b) / b.w - glm::vec2(a) / a.w) * 0.5f * glm::vec2(float(view.extent.width), float(view.extent.height));
  return glm::length(pixels);
}

void FurPass::draw(const vk::raii::CommandBuffer& commands) const {
  if (indexCount_ == 0 || !updated_) return;
  setViewportAndScissor(commands, extent_);
  // The skin (instance 0) keeps every pixel: its own pipeline has no discard, so depth is tested
  // before shading; then the shells, instances 1 … N − 1, which alpha-test.
  const vk::PipelineLayout layout = *skinPipeline_.layout;
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *skinPipeline_.pipeline);
  commands.setCullMode(cullMode_);
  commands.setFrontFace(frontFace_);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 0, {*set_}, {});
  commands.bindVertexBuffers(0, {*vertices_.buffer()}, {vk::DeviceSize{0}});
  commands.bindIndexBuffer(*indices_.buffer(), 0, vk::IndexType::eUint32);
  commands.drawIndexed(indexCount_, 1, 0, 0, 0);
  if (drawnLayers_ > 1) {
    commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *shellPipeline_.pipeline);
    commands.drawIndexed(indexCount_, drawnLayers_ - 1, 0, 0, 1);
  }
  if (finCount_ == 0) return;
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *finPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *finPipeline_.layout, 0, {*set_}, {});
  commands.draw(finCount_ * kVerticesPerFin, 1, 0, 0);
}

}  // namespace mane::render
