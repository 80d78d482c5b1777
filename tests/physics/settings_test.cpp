// Settings structs make the systems (HairSettings → HairSystem, ClothSettings → Cloth,
// InterpolationSettings → DenseStrandInterpolator): every bad field is refused with a message
// that names it, and good settings reach the system whole.

#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/cloth.hpp"
#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/interpolation.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;

HairSettings smallHair() {
  GroomSettings groom;
  groom.strandCount = 8;
  groom.particlesPerStrand = 6;
  HairSettings settings;
  settings.strands = *generateGroom(groom);
  return settings;
}

std::string hairError(const HairSettings& settings) {
  auto hair = HairSystem::create(settings);
  return hair ? std::string("(created)") : hair.error().message;
}

TEST(HairSettings, GoodSettingsReachTheSystem) {
  HairSettings settings = smallHair();
  settings.solver.constraintIterations = 7;
  settings.colliders.spheres = {{{0.0f, 0.0f, 0.0f}, 0.05f}};
  settings.wind = WindSettings{.direction = {1, 0, 0}, .speed = 2.0f};
  settings.vectorised = false;
  settings.tasks = builtInTaskRunner(2);
  auto hair = HairSystem::create(settings);
  ASSERT_TRUE(hair) << hair.error().message;
  EXPECT_EQ(hair->strandCount(), 8u);
  EXPECT_EQ(hair->settings().constraintIterations, 7);
  EXPECT_EQ(hair->colliders().spheres.size(), 1u);
  ASSERT_TRUE(hair->wind());
  EXPECT_EQ(hair->wind()->speed, 2.0f);
  EXPECT_FALSE(hair->vectorised());
  EXPECT_EQ(hair->taskRunner().concurrency, 2u);
  EXPECT_TRUE(hair->advance(1.0 / 60.0));
}

TEST(HairSettings, EachBadFieldIsNamed) {
  EXPECT_THAT(hairError(HairSettings{}), HasSubstr("HairSettings.strands"));
  HairSettings shortStrand = smallHair();
  shortStrand.strands[3].resize(1);
  EXPECT_THAT(hairError(shortStrand), HasSubstr("HairSettings.strands: Hair strand 3"));
  HairSettings solver = smallHair();
  solver.solver.constraintIterations = 0;
  EXPECT_THAT(hairError(solver), HasSubstr("HairSettings.solver"));
  HairSettings head = smallHair();
  head.headTransform[3][1] = std::nanf("");
  EXPECT_THAT(hairError(head), HasSubstr("HairSettings.headTransform"));
  HairSettings colliders = smallHair();
  colliders.colliders.spheres = {{{0.0f, 0.0f, 0.0f}, -1.0f}};
  EXPECT_THAT(hairError(colliders), HasSubstr("HairSettings.colliders"));
  HairSettings wind = smallHair();
  wind.wind = WindSettings{.speed = -1.0f};
  EXPECT_THAT(hairError(wind), HasSubstr("HairSettings.wind"));
  HairSettings normals = smallHair();
  normals.rootRestNormals = {{0.0f, 1.0f, 0.0f}};
  EXPECT_THAT(hairError(normals), HasSubstr("HairSettings.rootRestNormals"));
  HairSettings concurrency = smallHair();
  concurrency.tasks.concurrency = 0;
  EXPECT_THAT(hairError(concurrency), HasSubstr("HairSettings.tasks.concurrency"));
  HairSettings halfRunner = smallHair();
  halfRunner.tasks.wait = nullptr;
  halfRunner.tasks.enqueue = [](std::uint32_t, const TaskFunction&) -> Result<TaskGroup> { return nullptr; };
  EXPECT_THAT(hairError(halfRunner), HasSubstr("HairSettings.tasks has an enqueue but no wait"));
}

TEST(ClothSettings, EachBadFieldIsNamed) {
  ClothSettings good;
  good.positions = {{0, 0, 0}, {1, 0, 0}, {0, -1, 0}, {1, -1, 0}};
  good.triangles = {0, 2, 1, 1, 2, 3};
  good.pinnedVertices = {0, 1};
  ASSERT_TRUE(Cloth::create(good));
  const auto error = [](const ClothSettings& settings) {
    auto cloth = Cloth::create(settings);
    return cloth ? std::string("(created)") : cloth.error().message;
  };
  ClothSettings bend = good;
  bend.bendingStiffness = 2.0f;
  EXPECT_THAT(error(bend), HasSubstr("ClothSettings.bendingStiffness"));
  ClothSettings solver = good;
  solver.solver.fixedStep = 0.0;
  EXPECT_THAT(error(solver), HasSubstr("ClothSettings.solver"));
  ClothSettings body = good;
  body.bodyTransform[0][0] = INFINITY;
  EXPECT_THAT(error(body), HasSubstr("ClothSettings.bodyTransform"));
  ClothSettings positions = good;
  positions.positions[2].y = std::nanf("");
  EXPECT_THAT(error(positions), HasSubstr("ClothSettings.positions: cloth vertex 2"));
  ClothSettings triangles = good;
  triangles.triangles[4] = 9;
  EXPECT_THAT(error(triangles), HasSubstr("ClothSettings.triangles: cloth triangle 1 uses vertex 9"));
  ClothSettings pins = good;
  pins.pinnedVertices = {7};
  EXPECT_THAT(error(pins), HasSubstr("ClothSettings.pinnedVertices"));
  ClothSettings colliders = good;
  colliders.colliders.capsules = {{{0, 0, 0}, {0, 1, 0}, 0.0f}};
  EXPECT_THAT(error(colliders), HasSubstr("ClothSettings.colliders"));
  ClothSettings tasks = good;
  tasks.tasks.concurrency = 0;
  EXPECT_THAT(error(tasks), HasSubstr("ClothSettings.tasks.concurrency"));
}

TEST(InterpolationSettings, EachBadFieldIsNamed) {
  GroomSettings groom;
  groom.strandCount = 6;
  groom.particlesPerStrand = 5;
  InterpolationSettings good;
  good.restGuides = *generateGroom(groom);
  good.groom.strandCount = 30;
  auto interpolator = DenseStrandInterpolator::create(good);
  ASSERT_TRUE(interpolator) << interpolator.error().message;
  EXPECT_EQ(interpolator->layout().strands.size(), 30u);
  const auto error = [](const InterpolationSettings& settings) {
    auto made = DenseStrandInterpolator::create(settings);
    return made ? std::string("(created)") : made.error().message;
  };
  InterpolationSettings guides = good;
  guides.restGuides.clear();
  EXPECT_THAT(error(guides), HasSubstr("InterpolationSettings.restGuides"));
  InterpolationSettings clump = good;
  clump.groom.clump = 3.0f;
  EXPECT_THAT(error(clump), HasSubstr("InterpolationSettings.groom"));
  EXPECT_THAT(error(clump), HasSubstr("clump"));
  InterpolationSettings tasks = good;
  tasks.tasks.concurrency = 0;
  EXPECT_THAT(error(tasks), HasSubstr("InterpolationSettings.tasks.concurrency"));
}

}  // namespace
}  // namespace mane::physics
