// The surfaces' soft shadows (render/passes/surface_shadow_pass.hpp) against the penumbra of a
// straight edge under a sun of angular radius α, in closed form: a plate h above the ground, the
// sun overhead, hides from a ground point x from the edge the part of the sun's disc that,
// projected onto the plate's plane (a disc of radius R = h·tan α), lies past the edge, the
// circular segment at distance |x| from the disc's centre: (acos u − u·√(1 − u²))/π of it, u = |x|/R.

#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "render/renderer.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{256, 256};
constexpr float kPlateHeight = 0.3f, kHalfSide = 0.5f;
const Camera kCamera{.position = {0.6f, 0.5f, 0.0f}, .target = {0.0f, 0.0f, 0.0f}, .verticalFovRadians = 0.35f};

/// The circular segment's share of a unit disc beyond distance u (0 ≤ u ≤ 1) from its centre.
double segmentShare(double u) {
  u = std::min(u, 1.0);
  return (std::acos(u) - u * std::sqrt(1.0 - u * u)) / std::numbers::pi;
}

/// The share of the sun's disc seen from ground point x (the plate covers x < 0).
double visibleShare(double x, double radius) {
  const double pastEdge = segmentShare(std::abs(x) / radius);
  return x >= 0.0 ? 1.0 - pastEdge : pastEdge;
}

glm::vec3 pixelRay(int x, int y) {
  const float aspect = float(kExtent.width) / float(kExtent.height);
  const glm::mat4 toWorld = glm::inverse(kCamera.projection(aspect) * kCamera.view());
  const glm::vec2 ndc((float(x) + 0.5f) / float(kExtent.width) * 2.0f - 1.0f,
                      (float(y) + 0.5f) / float(kExtent.height) * 2.0f - 1.0f);
  const glm::vec4 far = toWorld * glm::vec4(ndc, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(far) / far.w - kCamera.position);
}

struct Quad {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices{0, 1, 2, 0, 2, 3};
  // Facing up, over x ∈ [x0, x1], z ∈ [−kHalfSide, kHalfSide], at height y.
  Quad(float x0, float x1, float y)
      : positions{{x0, y, -kHalfSide}, {x0, y, kHalfSide}, {x1, y, kHalfSide}, {x1, y, -kHalfSide}},
        normals(4, glm::vec3(0, 1, 0)),
        uvs{{0, 0}, {0, 1}, {1, 1}, {1, 0}} {}
  MeshData data() const { return {.positions = positions, .normals = normals, .uvs = uvs, .indices = indices}; }
};

class SurfaceShadows : public testing::VulkanTest {};

TEST_F(SurfaceShadows, AnEdgesPenumbraIsTheSunsDiscCutByIt) {
  const Quad ground(-kHalfSide, kHalfSide, 0.0f), plate(-kHalfSide, 0.0f, kPlateHeight);
  auto renderer = Renderer::create(device(), {.extent = kExtent, .msaaSamples = 1});
  ASSERT_TRUE(renderer.has_value());
  const StaticScene scene{.meshes = {ground.data(), plate.data()}, .materials = {MaterialData{}}};
  ASSERT_TRUE((*renderer)->setScene(scene).has_value());
  for (const float discDegrees : {3.0f, 1.5f}) {
    SCOPED_TRACE(discDegrees);
    const double radius = kPlateHeight * std::tan(glm::radians(double(discDegrees)));
    const FrameInput frame{
        .camera = kCamera,
        .lights = {{.direction = {0, 1, 0}, .intensity = 1.0f, .discRadius = glm::radians(discDegrees)}},
        .instances = {{.mesh = 0, .material = 0}, {.mesh = 1, .material = 0}},
        .ambient = glm::vec3(0.0f)};
    ASSERT_TRUE((*renderer)->render(frame).has_value());
    auto halves = (*renderer)->readHdrOutput();
    ASSERT_TRUE(halves.has_value());
    // Lambert ground of albedo 1 under a unit light overhead: the radiance is the visible share.
    // Averaged over the pixels in bins R/4 wide across the edge (the taps turn from pixel to pixel).
    constexpr int kBins = 16;
    std::vector<double> sum(kBins, 0.0);
    std::vector<int> count(kBins, 0);
    for (int y = 0; y < int(kExtent.height); ++y)
      for (int x = 0; x < int(kExtent.width); ++x) {
        const glm::vec3 ray = pixelRay(x, y);
        if (ray.y >= -1e-3f) continue;
        const glm::vec3 onPlate = kCamera.position + ray * ((kPlateHeight - kCamera.position.y) / ray.y);
        if (onPlate.x < 0.0f && std::abs(onPlate.z) < kHalfSide) continue;  // the plate hides the ground
        const glm::vec3 onGround = kCamera.position + ray * (-kCamera.position.y / ray.y);
        if (std::abs(onGround.z) > 0.8f * kHalfSide) continue;  // away from the plate's corners
        const int bin = int(std::floor((onGround.x / radius + 2.0) * 4.0));
        if (bin < 0 || bin >= kBins) continue;
        const std::size_t i = (std::size_t(y) * kExtent.width + std::size_t(x)) * 4;
        sum[std::size_t(bin)] += glm::unpackHalf1x16((*halves)[i]);
        ++count[std::size_t(bin)];
      }
    for (int bin = 0; bin < kBins; ++bin) {
      ASSERT_GT(count[std::size_t(bin)], 20) << "bin " << bin;
      // The analytic share averaged over the bin.
      double expected = 0.0;
      for (int k = 0; k < 64; ++k) expected += visibleShare(((bin + (k + 0.5) / 64.0) / 4.0 - 2.0) * radius, radius);
      expected /= 64.0;
      EXPECT_NEAR(sum[std::size_t(bin)] / count[std::size_t(bin)], expected, 0.05)
          << "bin " << bin << " at x/R = " << (bin + 0.5) / 4.0 - 2.0;
    }
  }
}

}  // namespace
}  // namespace mane::render
