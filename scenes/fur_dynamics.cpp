#include "scenes/fur_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

namespace mane::scenes {

Result<FurDynamics> FurDynamics::create(const Mesh& mesh, float scale, const FurDynamicsSettings& settings,
                                        const glm::mat4& body) {
  const std::size_t vertices = mesh.positions.size();
  if (vertices == 0 || mesh.normals.size() != vertices)
    return fail("fur dynamics: the mesh has no vertices or normals");
  if (settings.guides < 1) return fail("fur dynamics: at least one guide strand is needed");
  if (!(settings.thickness > 0.0f)) return fail("fur dynamics: the fur's height must be > 0");
  const std::size_t stride = (vertices + std::size_t(settings.guides) - 1) / std::size_t(settings.guides);
  std::vector<std::vector<glm::vec3>> strands;
  std::vector<glm::vec3> roots;
  for (std::size_t v = 0; v < vertices; v += stride) {
    const glm::vec3 root = mesh.positions[v] * scale;
    const glm::vec3 normal = glm::normalize(mesh.normals[v]);
    std::vector<glm::vec3>& strand = strands.emplace_back();
    for (int k = 0; k < kFurGuidePoints; ++k)
      strand.push_back(root + normal * (settings.thickness * float(k) / float(kFurGuidePoints - 1)));
    roots.push_back(root);
  }
  auto hair = physics::HairSystem::create(strands, settings.solver, body);
  if (!hair) return fail("fur dynamics: " + hair.error().message);
  FurDynamics result(std::move(*hair));
  result.thickness_ = settings.thickness;
  for (const auto& strand : strands) result.restTips_.push_back(strand.back());
  // Nearest guide per vertex, by brute force once at load (a vertex's own guide when it has one).
  result.nearestGuide_.resize(vertices);
  result.normals_.resize(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    const glm::vec3 p = mesh.positions[v] * scale;
    float best = std::numeric_limits<float>::max();
    for (std::size_t g = 0; g < roots.size(); ++g) {
      const glm::vec3 d = roots[g] - p;
      const float distance = glm::dot(d, d);
      if (distance < best) {
        best = distance;
        result.nearestGuide_[v] = static_cast<std::uint32_t>(g);
      }
    }
    result.normals_[v] = glm::normalize(mesh.normals[v]);
  }
  result.leans_.assign(vertices, glm::vec3(0.0f));
  result.updateLeans(body);
  return result;
}

Result<void> FurDynamics::advance(const glm::mat4& body, double frameDt, unsigned threads) {
  if (auto set = hair_.setHeadTransform(body); !set) return fail("fur dynamics: " + set.error().message);
  if (auto advanced = hair_.advance(frameDt, threads); !advanced)
    return fail("fur dynamics: " + advanced.error().message);
  updateLeans(body);
  return {};
}

void FurDynamics::updateLeans(const glm::mat4& body) {
  const glm::mat3 rotation(body);
  std::vector<glm::vec3> guideLeans(restTips_.size());
  for (std::size_t g = 0; g < restTips_.size(); ++g) {
    const glm::vec3 restTip = glm::vec3(body * glm::vec4(restTips_[g], 1.0f));
    guideLeans[g] = (hair_.strandPositions(g).back() - restTip) / thickness_;
  }
  for (std::size_t v = 0; v < leans_.size(); ++v) {
    const glm::vec3 normal = rotation * normals_[v];
    glm::vec3 lean = guideLeans[nearestGuide_[v]];
    lean -= glm::dot(lean, normal) * normal;
    const float length = glm::length(lean);
    leans_[v] = length > kMaxFurLean ? lean * (kMaxFurLean / length) : lean;
  }
}

}  // namespace mane::scenes
