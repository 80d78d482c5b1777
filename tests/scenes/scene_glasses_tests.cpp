// Spectacles (scenes/README.md, "Glasses"): the block as it arrives in the Scene, its errors, and
// the glasses built from it (scenes/glasses.hpp) against their measurements: lenses of the
// prescribed power where the measurements put them, rims that hide each lens's edge from the
// front and leave its middle clear, temples that end where the temple width says.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include <glm/geometric.hpp>

#include "scenes/glasses.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {
namespace {

std::string sceneWithGlasses(const std::string& glasses) {
  return R"({"name": "g", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
    "materials": [{"name": "frame", "base_colour": [0.02, 0.02, 0.02]}, {"name": "furry", "kind": "fur", "albedo_texture": "fur.png"}],
    "meshes": [{"name": "head", "source": "procedural:sphere", "transform": {"scale": 0.1}}],
    "glasses": [{"name": "specs", "attached_mesh": "head", )" +
         glasses + "}]}";
}

std::string errorOf(const std::string& glasses) {
  auto scene = parseScene(sceneWithGlasses(glasses), "dir/bad.json");
  return scene ? std::string() : scene.error().message;
}

TEST(SceneGlasses, TheFieldsArriveAsWrittenAndDefaultsAsDocumented) {
  auto scene = parseScene(sceneWithGlasses(R"("transform": {"translation": [0, 0.02, 0.09]},
      "power_dioptres": -2.5, "lens_width": 0.04, "lens_height": 0.03, "bridge": 0.015, "temple_length": 0.08,
      "temple_width": 0.14, "ior": 1.6, "tint": [0.5, 0.4, 0.3], "material": "frame")"),
                          "g.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  ASSERT_EQ(scene->glasses.size(), 1u);
  const Glasses& glasses = scene->glasses[0];
  EXPECT_EQ(glasses.name, "specs");
  EXPECT_EQ(glasses.attachedMesh, "head");
  EXPECT_EQ(glasses.transform.translation, glm::vec3(0, 0.02f, 0.09f));
  EXPECT_EQ(glasses.powerDioptres, -2.5f);
  EXPECT_EQ(glasses.lensWidth, 0.04f);
  EXPECT_EQ(glasses.lensHeight, 0.03f);
  EXPECT_EQ(glasses.bridge, 0.015f);
  EXPECT_EQ(glasses.templeLength, 0.08f);
  EXPECT_EQ(glasses.templeWidth, 0.14f);
  EXPECT_EQ(glasses.ior, 1.6f);
  EXPECT_EQ(glasses.tint, glm::vec3(0.5f, 0.4f, 0.3f));
  EXPECT_EQ(glasses.material, "frame");

  auto plain = parseScene(sceneWithGlasses(R"("power_dioptres": 1)"), "g.json");
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  EXPECT_EQ(plain->glasses[0].lensWidth, Glasses{}.lensWidth);
  EXPECT_EQ(plain->glasses[0].ior, 1.5f);
  EXPECT_EQ(plain->glasses[0].tint, glm::vec3(1.0f));
}

TEST(SceneGlasses, MistakesAreReportedAtTheirField) {
  const auto expectError = [](const std::string& glasses, const std::string& field, const std::string& expected) {
    const std::string message = errorOf(glasses);
    EXPECT_NE(message.find("dir/bad.json"), std::string::npos) << message;
    EXPECT_NE(message.find(field), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  };
  expectError(R"("power_dioptres": 25)", "glasses[0].power_dioptres", "[-20, 20]");
  expectError(R"("lens_width": 0)", "glasses[0].lens_width", "(0, 0.2]");
  expectError(R"("bridge": -0.01)", "glasses[0].bridge", "[0, 0.1]");
  expectError(R"("ior": 1)", "glasses[0].ior", "(1, 3]");
  expectError(R"("tint": [1, 1, 2])", "glasses[0].tint", "[0, 1]");
  expectError(R"("transform": {"scale": 2})", "glasses[0].transform.scale", "leave the scale at 1");
  expectError(R"("material": "gold")", "glasses[0].material", "no material named \"gold\"");
  expectError(R"("material": "furry")", "glasses[0].material", "fur grows on meshes");
  expectError(R"("lens_colour": [1, 0, 0])", "glasses[0].lens_colour", "");
  auto unattached = parseScene(R"({"name": "g", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
      "glasses": [{"name": "specs", "attached_mesh": "nobody"}]})",
                               "bad.json");
  ASSERT_FALSE(unattached.has_value());
  EXPECT_NE(unattached.error().message.find("glasses[0].attached_mesh"), std::string::npos)
      << unattached.error().message;
  auto twice = parseScene(R"({"name": "g", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
      "meshes": [{"name": "head", "source": "procedural:sphere"}],
      "glasses": [{"name": "specs", "attached_mesh": "head"}, {"name": "specs", "attached_mesh": "head"}]})",
                          "bad.json");
  ASSERT_FALSE(twice.has_value());
  EXPECT_NE(twice.error().message.find("duplicate glasses name"), std::string::npos) << twice.error().message;
}

/// Where the ray from `origin` along `direction` first meets a triangle of `mesh`
/// (Möller–Trumbore), as a distance along the ray.
std::optional<float> firstHit(const Mesh& mesh, glm::vec3 origin, glm::vec3 direction) {
  std::optional<float> nearest;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                    c = mesh.positions[mesh.indices[t + 2]];
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(direction, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) continue;
    const glm::vec3 s = origin - a;
    const float u = glm::dot(s, p) / det;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(direction, q) / det;
    const float distance = glm::dot(e2, q) / det;
    if (u < 0.0f || v < 0.0f || u + v > 1.0f || distance <= 0.0f) continue;
    if (!nearest || distance < *nearest) nearest = distance;
  }
  return nearest;
}

TEST(Glasses, LensesOfThePrescribedPowerSitInRimsThatHideTheirEdges) {
  const Glasses measurements{.name = "specs",
                             .powerDioptres = -3.0f,
                             .lensWidth = 0.05f,
                             .lensHeight = 0.036f,
                             .bridge = 0.018f,
                             .templeLength = 0.1f,
                             .templeWidth = 0.15f};
  auto glasses = buildGlasses(measurements);
  ASSERT_TRUE(glasses.has_value()) << glasses.error().message;
  const Mesh& frame = glasses->frame;
  ASSERT_EQ(frame.normals.size(), frame.positions.size());
  for (const glm::vec3& normal : frame.normals) ASSERT_NEAR(glm::length(normal), 1.0f, 1e-4f);
  for (const std::uint32_t index : frame.indices) ASSERT_LT(index, frame.positions.size());

  for (std::size_t l = 0; l < 2; ++l) {
    SCOPED_TRACE(l);
    const render::Lens& lens = glasses->lenses[l];
    EXPECT_NEAR(render::thinLensPower(lens.shape), -3.0f, 1e-4f);
    EXPECT_EQ(lens.shape.halfAperture, glm::vec2(0.025f, 0.018f));
    const glm::vec3 centre(lens.model[3]);
    EXPECT_NEAR(centre.x, (l == 0 ? -1.0f : 1.0f) * 0.034f, 1e-6f) << "half of bridge + lens width from the middle";
    EXPECT_EQ(centre.y, 0.0f);
    // Seen head on, from in front: the middle is clear, and every point of the outline lies
    // under the rim, which is in front of the lens's front face there.
    const glm::vec3 towardsFace(0, 0, -1);
    EXPECT_FALSE(firstHit(frame, centre + glm::vec3(0, 0, 1), towardsFace).has_value());
    for (int k = 0; k < 90; ++k) {
      const float theta = 2.0f * 3.14159265f * float(k) / 90.0f;
      const glm::vec2 outline = lens.shape.halfAperture * glm::vec2(std::cos(theta), std::sin(theta));
      const float front = -render::lensSag(lens.shape.frontCurvature, glm::length(outline));
      const auto hit = firstHit(frame, centre + glm::vec3(outline, 1.0f), towardsFace);
      ASSERT_TRUE(hit.has_value()) << "the outline at " << theta << " rad shows";
      EXPECT_GT(1.0f - *hit, front) << "the lens's face stands out of the rim at " << theta << " rad";
      // And from behind, where the eye is: the rim covers the back face's edge too.
      const float back = -lens.shape.centreThickness - render::lensSag(lens.shape.backCurvature, glm::length(outline));
      const auto behind = firstHit(frame, centre + glm::vec3(outline, -1.0f), -towardsFace);
      ASSERT_TRUE(behind.has_value());
      EXPECT_LT(-1.0f + *behind, back) << "the lens's back stands out of the rim at " << theta << " rad";
    }
  }
  // The temples end temple_width apart, then bend down over the ears.
  const Bounds bounds = frame.bounds();
  EXPECT_NEAR(bounds.max.x, 0.075f + 1.1e-3f, 1e-4f);
  EXPECT_NEAR(bounds.min.x, -0.075f - 1.1e-3f, 1e-4f);
  EXPECT_LT(bounds.min.z, -0.1f);
}

TEST(Glasses, ALensTooStrongForItsOutlineIsRefusedByName) {
  const Glasses measurements{.name = "pebbles", .powerDioptres = 20.0f, .lensWidth = 0.1f, .lensHeight = 0.08f};
  auto glasses = buildGlasses(measurements);
  ASSERT_FALSE(glasses.has_value());
  EXPECT_NE(glasses.error().message.find("glasses 'pebbles'"), std::string::npos) << glasses.error().message;
}

}  // namespace
}  // namespace mane::scenes
