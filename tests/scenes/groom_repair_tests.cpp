// Grooms with flawed strands: each flaw (groom_repair.hpp) in a synthetic .tfx or .hair file is
// repaired or dropped, with a report naming how many strands, which and why; loaded strictly, the
// same file is refused naming the strand. Then what the formats carry beyond positions (HAIR
// thickness, transparency and colours; TressFX per-strand thickness and UVs), read back as
// written and kept aligned through repairs; then the World's one note per groom.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "groom_test_files.hpp"
#include "scenes/groom_loader.hpp"
#include "scenes/groom_repair.hpp"
#include "scenes/scene.hpp"
#include "scenes/world.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using testing::cyHair;
using testing::expectError;
using testing::putF32;
using testing::putU32;
using testing::ScratchDir;
using testing::sharedResolver;
using testing::syntheticPoint;
using testing::tfxV3;
using testing::tfxV4;

constexpr GroomLoadOptions kStrict{.strict = true};
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Byte of vertex v of strand s in a tfxV3 file of `verts` vertices per strand.
std::size_t tfxByte(std::size_t s, std::size_t v, std::size_t verts) {
  return 296 + (s * verts + v) * 12;
}

/// Copies vertex `from` of strand s over vertex `to` (a repeated point).
void repeatTfxVertex(std::string& bytes, std::size_t s, std::size_t from, std::size_t to, std::size_t verts) {
  std::memmove(bytes.data() + tfxByte(s, to, verts), bytes.data() + tfxByte(s, from, verts), 12);
}

std::string summaryOf(const Result<StrandSet>& groom) {
  return groom ? groom->repairs.summary() : groom.error().message;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// --- Each flaw ---------------------------------------------------------------------------

TEST(GroomRepair, RepeatedPointsAreMergedAndTheStrandsKept) {
  ScratchDir dir;
  std::string bytes = tfxV3(4, 4, 16);
  repeatTfxVertex(bytes, 1, 1, 2, 4);  // strand 1: vertex 2 := vertex 1
  repeatTfxVertex(bytes, 3, 2, 3, 4);  // strand 3: the tip := vertex 2
  auto groom = loadTfx(dir.write("repeated.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  ASSERT_EQ(groom->strands.size(), 4u);
  EXPECT_EQ(groom->strands[0].size(), 4u);
  // Merged, then resampled back to 4 points: the longest segment (vertex 1 to 3) is split.
  ASSERT_EQ(groom->strands[1].size(), 4u);
  EXPECT_EQ(groom->strands[1][1], syntheticPoint(1, 1));
  EXPECT_EQ(groom->strands[1][2], (syntheticPoint(1, 1) + syntheticPoint(1, 3)) * 0.5f);
  EXPECT_EQ(groom->strands[1][3], syntheticPoint(1, 3));
  EXPECT_EQ(groom->strands[3].size(), 4u);

  const GroomRepairReport& report = groom->repairs;
  EXPECT_EQ(report.strandsRead, 4u);
  ASSERT_EQ(report.repairs.size(), 2u);
  EXPECT_EQ(report.repairs[0].strand, 1u);
  EXPECT_EQ(report.repairs[0].point, 2u);
  EXPECT_EQ(report.repairs[0].flaw, StrandFlaw::kRepeatedPoint);
  EXPECT_EQ(report.repairs[0].pointsMerged, 1u);
  EXPECT_EQ(report.droppedCount(), 0u);
  EXPECT_EQ(report.summary(), "4 strands read: 2 repaired (2 with a repeated point: 1, 3)");

  expectError(loadTfx(dir.write("repeated.tfx", bytes), kStrict),
              {"repeated.tfx", "strand 1, vertex 2", "byte 368", "vertex 1", "zero-length", "strict", "2 in this file"});
}

TEST(GroomRepair, NearlyCoincidentPointsAreZeroLengthSegments) {
  // The synthetic segments are about 1 cm; 1e-9 is under kZeroLengthFraction of that, yet not equal.
  ScratchDir dir;
  std::string bytes = tfxV3(3, 4, 12);
  putF32(bytes, tfxByte(2, 1, 4) + 4, syntheticPoint(2, 0).y + 1e-9f);
  putF32(bytes, tfxByte(2, 1, 4), syntheticPoint(2, 0).x);
  putF32(bytes, tfxByte(2, 1, 4) + 8, syntheticPoint(2, 0).z);
  auto groom = loadTfx(dir.write("near.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  ASSERT_EQ(groom->strands.size(), 3u);
  EXPECT_EQ(groom->strands[2].size(), 4u);
  ASSERT_EQ(groom->repairs.repairs.size(), 1u);
  EXPECT_EQ(groom->repairs.repairs[0].flaw, StrandFlaw::kZeroLengthSegment);
  EXPECT_TRUE(contains(summaryOf(groom), "1 with a zero-length segment: 2")) << summaryOf(groom);
  expectError(loadTfx(dir.write("near.tfx", bytes), kStrict), {"near.tfx", "strand 2, vertex 1", "zero-length"});
}

TEST(GroomRepair, NonFinitePointDropsItsStrand) {
  ScratchDir dir;
  std::string bytes = tfxV3(3, 4, 12);
  putF32(bytes, tfxByte(1, 3, 4) + 8, kNaN);  // the tip of strand 1
  auto groom = loadTfx(dir.write("nan.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  ASSERT_EQ(groom->strands.size(), 2u);
  EXPECT_EQ(groom->strands[0][3], syntheticPoint(0, 3));
  EXPECT_EQ(groom->strands[1][3], syntheticPoint(2, 3));  // strand 2 moved up
  EXPECT_EQ(groom->repairs.summary(), "3 strands read: 1 dropped (1 with a non-finite point: 1)");
}

TEST(GroomRepair, StrandsWithFewerThanTwoPointsAreDropped) {
  ScratchDir dir;
  // A HAIR hair of 0 segments is one point.
  auto hair = loadCyHair(dir.write("short.hair", cyHair({2, 0, 1}, 3, 0)));
  ASSERT_TRUE(hair.has_value()) << hair.error().message;
  ASSERT_EQ(hair->strands.size(), 2u);
  EXPECT_EQ(hair->strands[1][1], syntheticPoint(2, 1));
  EXPECT_EQ(hair->repairs.summary(), "3 strands read: 1 dropped (1 with fewer than two distinct points: 1)");

  // A TressFX strand whose four vertices coincide is one point once merged.
  std::string bytes = tfxV3(3, 4, 12);
  for (std::size_t v = 1; v < 4; ++v) repeatTfxVertex(bytes, 0, 0, v, 4);
  auto tfx = loadTfx(dir.write("collapsed.tfx", bytes));
  ASSERT_TRUE(tfx.has_value()) << tfx.error().message;
  ASSERT_EQ(tfx->strands.size(), 2u);
  ASSERT_EQ(tfx->repairs.repairs.size(), 1u);
  EXPECT_EQ(tfx->repairs.repairs[0].flaw, StrandFlaw::kTooFewPoints);
  EXPECT_EQ(tfx->repairs.repairs[0].pointsMerged, 3u);
  expectError(loadTfx(dir.write("collapsed.tfx", bytes), kStrict), {"collapsed.tfx", "strand 0, vertex 1"});
}

TEST(GroomRepair, AbsurdlyLongStrandsAreDropped) {
  // One vertex a kilometre off: its segment is ~10^5 × the 1 cm median.
  ScratchDir dir;
  std::string bytes = tfxV3(5, 4, 20);
  putF32(bytes, tfxByte(2, 3, 4), 1000.0f);
  auto groom = loadTfx(dir.write("far.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  EXPECT_EQ(groom->strands.size(), 4u);
  EXPECT_EQ(groom->repairs.summary(), "5 strands read: 1 dropped (1 of absurd length: 2)");
  expectError(loadTfx(dir.write("far.tfx", bytes), kStrict),
              {"far.tfx", "strand 2, vertex 3", std::to_string(tfxByte(2, 3, 4)).c_str(), "absurd"});
}

TEST(GroomRepair, SummaryListsTheFirstFewStrandsThenCounts) {
  ScratchDir dir;
  std::string bytes = tfxV3(10, 3, 30);
  for (std::size_t s = 0; s < 8; ++s) repeatTfxVertex(bytes, s, 0, 1, 3);
  putF32(bytes, tfxByte(9, 0, 3), kNaN);
  auto groom = loadTfx(dir.write("many.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  EXPECT_EQ(groom->strands.size(), 9u);
  EXPECT_EQ(groom->repairs.summary(),
            "10 strands read: 8 repaired (8 with a repeated point: 0, 1, 2, 3, 4 and 3 more), "
            "1 dropped (1 with a non-finite point: 9)");
}

TEST(GroomRepair, EveryStrandFlawedIsAnError) {
  ScratchDir dir;
  std::string bytes = tfxV3(2, 4, 8);
  putF32(bytes, tfxByte(0, 1, 4), kNaN);
  putF32(bytes, tfxByte(1, 2, 4), std::numeric_limits<float>::infinity());
  expectError(loadTfx(dir.write("broken.tfx", bytes)), {"broken.tfx", "every strand is flawed", "2 with a non-finite"});
}

TEST(GroomRepair, CleanFilesReportNothing) {
  ScratchDir dir;
  auto groom = loadTfx(dir.write("clean.tfx", tfxV4(3, 5)), kStrict);
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  EXPECT_TRUE(groom->repairs.clean());
  EXPECT_EQ(groom->repairs.summary(), "3 strands read: none flawed");
}

// --- Attributes beyond positions ---------------------------------------------------------

/// A HAIR file of 3 hairs × 4 points with thickness, transparency and colour arrays whose values
/// encode the point's index in the file.
std::string hairWithAttributes() {
  std::string bytes = cyHair({}, 3, 3, 4u | 8u | 16u);
  for (int i = 0; i < 12; ++i) putF32(bytes, bytes.size(), 0.1f * float(i));
  for (int i = 0; i < 12; ++i) putF32(bytes, bytes.size(), 0.01f * float(i));
  for (int i = 0; i < 12; ++i)
    for (int c = 1; c <= 3; ++c) putF32(bytes, bytes.size(), 0.001f * float(c * i));
  return bytes;
}

TEST(GroomAttributes, CyHairThicknessTransparencyAndColoursReadBackAsWritten) {
  ScratchDir dir;
  auto hair = loadCyHair(dir.write("full.hair", hairWithAttributes()));
  ASSERT_TRUE(hair.has_value()) << hair.error().message;
  ASSERT_EQ(hair->thickness.size(), 3u);
  ASSERT_EQ(hair->transparency.size(), 3u);
  ASSERT_EQ(hair->colours.size(), 3u);
  for (std::size_t h = 0; h < 3; ++h) {
    ASSERT_EQ(hair->thickness[h].size(), 4u);
    for (std::size_t v = 0; v < 4; ++v) {
      const float i = float(4 * h + v);
      EXPECT_EQ(hair->thickness[h][v], 0.1f * i);
      EXPECT_EQ(hair->transparency[h][v], 0.01f * i);
      EXPECT_EQ(hair->colours[h][v], glm::vec3(0.001f * i, 0.001f * (2 * i), 0.001f * (3 * i)));
    }
  }
  EXPECT_TRUE(hair->strandThickness.empty());

  auto bare = loadCyHair(dir.write("bare.hair", cyHair({}, 3, 3)));
  ASSERT_TRUE(bare.has_value()) << bare.error().message;
  EXPECT_TRUE(bare->thickness.empty() && bare->transparency.empty() && bare->colours.empty());
}

TEST(GroomAttributes, CyHairHeaderDefaultsStandForTheArraysTheFileLacks) {
  // cyHairFile.h: bytes 20–39 of the header hold the default thickness, transparency and colour,
  // which every point has where the file carries no array of its own. They come back as stored,
  // beside whatever arrays the file has; a TressFX file has no such defaults.
  ScratchDir dir;
  std::string bytes = cyHair({}, 3, 3, 16u);  // a colour array, no thickness or transparency
  for (int i = 0; i < 12 * 3; ++i) putF32(bytes, bytes.size(), 0.5f);
  putF32(bytes, 20, 0.25f);
  putF32(bytes, 24, 0.4f);
  putF32(bytes, 28, 0.9f);
  putF32(bytes, 32, 0.1f);
  putF32(bytes, 36, 0.2f);
  auto hair = loadCyHair(dir.write("defaults.hair", bytes));
  ASSERT_TRUE(hair.has_value()) << hair.error().message;
  ASSERT_TRUE(hair->hairDefaults.has_value());
  EXPECT_EQ(hair->hairDefaults->thickness, 0.25f);
  EXPECT_EQ(hair->hairDefaults->transparency, 0.4f);
  EXPECT_EQ(hair->hairDefaults->colour, glm::vec3(0.9f, 0.1f, 0.2f));
  EXPECT_TRUE(hair->thickness.empty() && hair->transparency.empty());
  ASSERT_EQ(hair->colours.size(), 3u);
  EXPECT_EQ(hair->colours[2][3], glm::vec3(0.5f));

  auto tfx = loadTfx(dir.write("plain.tfx", tfxV3(2, 3, 6)));
  ASSERT_TRUE(tfx.has_value()) << tfx.error().message;
  EXPECT_FALSE(tfx->hairDefaults.has_value());
}

TEST(GroomAttributes, CyHairAttributesFollowTheirPointsThroughRepairs) {
  // Hair 0 gets a NaN (dropped); hair 1's point 2 repeats point 1 (merged): what was hair 1 is
  // now strand 0, its point-2 attributes are gone with the point, and the point put back in the
  // middle of its longest segment (points 1 to 3) has the mean of their attributes.
  ScratchDir dir;
  std::string bytes = hairWithAttributes();
  putF32(bytes, 128 + 12 * 2, kNaN);
  std::memmove(bytes.data() + 128 + 12 * 6, bytes.data() + 128 + 12 * 5, 12);
  auto hair = loadCyHair(dir.write("flawed.hair", bytes));
  ASSERT_TRUE(hair.has_value()) << hair.error().message;
  ASSERT_EQ(hair->strands.size(), 2u);
  ASSERT_EQ(hair->thickness.size(), 2u);
  ASSERT_EQ(hair->colours.size(), 2u);
  ASSERT_EQ(hair->strands[0].size(), 4u);
  ASSERT_EQ(hair->thickness[0].size(), 4u);
  ASSERT_EQ(hair->transparency[0].size(), 4u);
  ASSERT_EQ(hair->colours[0].size(), 4u);
  EXPECT_EQ(hair->thickness[0][0], 0.1f * 4.0f);
  EXPECT_EQ(hair->thickness[0][1], 0.1f * 5.0f);
  EXPECT_EQ(hair->thickness[0][2], (0.1f * 5.0f + 0.1f * 7.0f) * 0.5f);
  EXPECT_EQ(hair->thickness[0][3], 0.1f * 7.0f);
  EXPECT_EQ(hair->transparency[0][3], 0.01f * 7.0f);
  EXPECT_EQ(hair->colours[0][3], glm::vec3(0.001f * 7.0f, 0.001f * 14.0f, 0.001f * 21.0f));
  EXPECT_EQ(hair->thickness[1][0], 0.1f * 8.0f);
  EXPECT_EQ(hair->repairs.summary(),
            "3 strands read: 1 repaired (1 with a repeated point: 1), 1 dropped (1 with a non-finite point: 0)");
}

/// Appends TressFX per-strand thickness (0.5 + s) and UVs (s/10, 1 − s/10) and points the
/// header's offsets (v3: UVs at 148, thickness at 156; v4: 16 and 24) at them.
void appendStrandArrays(std::string& bytes, std::uint32_t strands, bool v4) {
  putU32(bytes, v4 ? 24 : 156, static_cast<std::uint32_t>(bytes.size()));
  for (std::uint32_t s = 0; s < strands; ++s) putF32(bytes, bytes.size(), 0.5f + float(s));
  putU32(bytes, v4 ? 16 : 148, static_cast<std::uint32_t>(bytes.size()));
  for (std::uint32_t s = 0; s < strands; ++s) {
    putF32(bytes, bytes.size(), float(s) / 10.0f);
    putF32(bytes, bytes.size(), 1.0f - float(s) / 10.0f);
  }
}

TEST(GroomAttributes, TfxPerStrandThicknessAndUvsReadBackAndFollowDroppedStrands) {
  ScratchDir dir;
  for (bool v4 : {false, true}) {
    SCOPED_TRACE(v4 ? "v4" : "v3");
    std::string bytes = v4 ? tfxV4(3, 4) : tfxV3(3, 4, 12);
    appendStrandArrays(bytes, 3, v4);
    auto groom = loadTfx(dir.write("strands.tfx", bytes));
    ASSERT_TRUE(groom.has_value()) << groom.error().message;
    ASSERT_EQ(groom->strandThickness, (std::vector<float>{0.5f, 1.5f, 2.5f}));
    ASSERT_EQ(groom->strandUvs.size(), 3u);
    EXPECT_EQ(groom->strandUvs[2], glm::vec2(0.2f, 1.0f - 0.2f));

    putF32(bytes, (v4 ? 160 + 16 * 5 : tfxByte(1, 1, 4)) + 4, kNaN);  // strand 1 is dropped
    auto flawed = loadTfx(dir.write("strands.tfx", bytes));
    ASSERT_TRUE(flawed.has_value()) << flawed.error().message;
    EXPECT_EQ(flawed->strandThickness, (std::vector<float>{0.5f, 2.5f}));
    ASSERT_EQ(flawed->strandUvs.size(), 2u);
    EXPECT_EQ(flawed->strandUvs[1], glm::vec2(0.2f, 1.0f - 0.2f));
  }
  // Without offsets there is nothing.
  auto plain = loadTfx(dir.write("plain.tfx", tfxV3(3, 4, 12)));
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  EXPECT_TRUE(plain->strandThickness.empty() && plain->strandUvs.empty());
}

TEST(GroomAttributes, TfxPerStrandArrayOutsideTheFileIsAnError) {
  ScratchDir dir;
  std::string bytes = tfxV3(3, 4, 12);
  putU32(bytes, 156, static_cast<std::uint32_t>(bytes.size() - 4));  // 3 floats need 12 bytes
  expectError(loadTfx(dir.write("cut.tfx", bytes)), {"cut.tfx", "per-strand thickness", "byte 156", "truncated"});
  putU32(bytes, 156, 0);
  putU32(bytes, 148, 100);
  expectError(loadTfx(dir.write("inside.tfx", bytes)), {"inside.tfx", "per-strand UV", "points into"});
}

// --- The World and the scene -------------------------------------------------------------

std::string flawedGroomScene(bool strict) {
  return std::string(R"({"name": "flawed", "camera": {"position": [0, 1, 3], "target": [0, 1, 0]},
      "meshes": [{"name": "head", "source": "procedural:sphere", "transform": {"scale": 0.5}}],
      "grooms": [{"name": "hair", "source": "user.hair", "attached_mesh": "head")") +
         (strict ? R"(, "strict": true)" : "") + "}]}";
}

/// user.hair: 4 hairs of 5 points; hair 1 has a repeated point, hair 3 a NaN.
void writeFlawedHair(const ScratchDir& dir) {
  std::string bytes = cyHair({}, 4, 4);
  std::memmove(bytes.data() + 128 + 12 * 7, bytes.data() + 128 + 12 * 6, 12);
  putF32(bytes, 128 + 12 * 16, kNaN);
  dir.write("user.hair", bytes);
}

TEST(GroomRepairWorld, AFlawedGroomLoadsWithOneNote) {
  ScratchDir dir;
  writeFlawedHair(dir);
  auto scene = loadScene(dir.write("scene.json", flawedGroomScene(false)));
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  auto world = World::create(std::move(*scene), sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world.has_value()) << world.error().message;
  EXPECT_EQ(world->guideStrandCount(), 3u);
  EXPECT_EQ(world->particleCount(), 3u * 5u);  // the repaired hair keeps its 5 points
  ASSERT_EQ(world->notes().size(), 1u) << ::testing::PrintToString(world->notes());
  const std::string& note = world->notes()[0];
  for (const char* part : {"groom hair", "user.hair", "4 strands read", "1 repaired (1 with a repeated point: 1)",
                           "1 dropped (1 with a non-finite point: 3)"})
    EXPECT_TRUE(contains(note, part)) << "missing \"" << part << "\" in: " << note;
  ASSERT_TRUE(world->advance(0.1, 1).has_value());
}

TEST(GroomRepairWorld, AStrictGroomRefusesTheFlawedFile) {
  ScratchDir dir;
  writeFlawedHair(dir);
  auto scene = loadScene(dir.write("scene.json", flawedGroomScene(true)));
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  EXPECT_TRUE(scene->grooms[0].strict);
  auto world = World::create(std::move(*scene), sharedResolver(), {.loadTextures = false});
  expectError(world, {"groom hair", "user.hair", "strand 1, point 2", "strict"});
}

TEST(GroomRepairWorld, StrictIsForGroomFilesOnly) {
  auto scene = parseScene(R"({"name": "p", "camera": {"position": [0, 1, 3], "target": [0, 1, 0]},
      "meshes": [{"name": "head", "source": "procedural:sphere"}],
      "grooms": [{"name": "hair", "source": "procedural", "attached_mesh": "head", "strict": true}]})",
                          "p.json");
  expectError(scene, {"strict", "groom files only"});
}

}  // namespace
}  // namespace mane::scenes
