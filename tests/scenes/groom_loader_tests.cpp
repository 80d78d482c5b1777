// Groom loaders (.tfx, .hair) on the shipped TressFX data, checked against the counts in
// ../shared/assets/README.md and against each other (the .hair files are the same points written
// by a different tool in a different format); then malformed files, each with its message; then
// the World loading a groom file onto its mesh.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "scenes/gltf_loader.hpp"
#include "scenes/groom_loader.hpp"
#include "scenes/world.hpp"
#include "groom_test_files.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using testing::cyHair;
using testing::expectError;
using testing::putF32;
using testing::putU32;
using testing::readFile;
using testing::syntheticPoint;
using testing::tfxV3;
using testing::tfxV4;
using testing::ScratchDir;
using testing::sharedResolver;

// --- The shipped data --------------------------------------------------------------------

struct TfxExpectation {
  std::size_t strands;
  std::size_t verticesPerStrand;
};

// ../shared/assets/README.md gives the ponytail as 4,933 × 16 in four groups and the bear as
// 48,113 × 4; the per-group split is the one AMD's ponytail.tfxproj lists (front_top, side,
// back, tail), which must add up to the README's total (checked below).
const std::map<std::string, TfxExpectation> kTfxAssets{
    {"hair/tressfx_ponytail/front_top.tfx", {876, 16}}, {"hair/tressfx_ponytail/side.tfx", {3066, 16}},
    {"hair/tressfx_ponytail/back.tfx", {517, 16}},      {"hair/tressfx_ponytail/tail.tfx", {474, 16}},
    {"hair/tressfx_bear_fur/bear.tfx", {48113, 4}},
};
const std::vector<std::string> kPonytailGroups{"hair/tressfx_ponytail/front_top.tfx", "hair/tressfx_ponytail/side.tfx",
                                               "hair/tressfx_ponytail/back.tfx", "hair/tressfx_ponytail/tail.tfx"};

TEST(GroomLoaderAssets, EveryTfxInTheManifestHasTheReadmeCounts) {
  std::size_t ponytailStrands = 0;
  std::size_t seen = 0;
  const AssetResolver resolver = sharedResolver();  // outlives the loop over its entries
  for (const AssetEntry& entry : resolver.entries()) {
    if (!entry.name.ends_with(".tfx")) continue;
    SCOPED_TRACE(entry.name);
    ++seen;
    const auto expected = kTfxAssets.find(entry.name);
    ASSERT_NE(expected, kTfxAssets.end()) << "a .tfx asset without published counts: add it here";
    MANE_RESOLVE_OR_SKIP(file, entry.name);
    auto groom = loadGroomFile(file);
    ASSERT_TRUE(groom.has_value()) << groom.error().message;
    EXPECT_EQ(groom->strands.size(), expected->second.strands);
    for (const std::vector<glm::vec3>& strand : groom->strands)
      ASSERT_EQ(strand.size(), expected->second.verticesPerStrand);
    EXPECT_EQ(groom->pointCount(), expected->second.strands * expected->second.verticesPerStrand);
    if (entry.name.starts_with("hair/tressfx_ponytail/")) ponytailStrands += groom->strands.size();
  }
  EXPECT_EQ(seen, kTfxAssets.size());
  EXPECT_EQ(ponytailStrands, 4933u);  // README: 4,933 × 16 = 78,928 points
}

TEST(GroomLoaderAssets, CyHairConversionsHoldExactlyTheTfxPoints) {
  // Two formats, two parsers, one data set: the .hair files were written from the .tfx points
  // by another tool, so every float must match bit for bit. The ponytail .hair holds the four
  // groups one after another in ponytail.tfxproj's order.
  MANE_RESOLVE_OR_SKIP(ponytailHair, "hair/converted_to_cyhair/tressfx_ponytail.hair");
  auto hair = loadCyHair(ponytailHair);
  ASSERT_TRUE(hair.has_value()) << hair.error().message;
  std::vector<std::vector<glm::vec3>> groups;
  for (const std::string& name : kPonytailGroups) {
    MANE_RESOLVE_OR_SKIP(file, name);
    auto tfx = loadTfx(file);
    ASSERT_TRUE(tfx.has_value()) << tfx.error().message;
    groups.insert(groups.end(), tfx->strands.begin(), tfx->strands.end());
  }
  EXPECT_EQ(hair->strands.size(), 4933u);
  EXPECT_TRUE(hair->strands == groups) << "ponytail .hair differs from its .tfx groups";

  MANE_RESOLVE_OR_SKIP(bearHair, "hair/converted_to_cyhair/tressfx_bear_fur.hair");
  MANE_RESOLVE_OR_SKIP(bearTfx, "hair/tressfx_bear_fur/bear.tfx");
  auto bear = loadCyHair(bearHair);
  ASSERT_TRUE(bear.has_value()) << bear.error().message;
  auto bearFromTfx = loadTfx(bearTfx);
  ASSERT_TRUE(bearFromTfx.has_value()) << bearFromTfx.error().message;
  EXPECT_EQ(bear->strands.size(), 48113u);
  EXPECT_TRUE(bear->strands == bearFromTfx->strands) << "bear .hair differs from bear.tfx";
}

TEST(GroomLoaderAssets, PonytailLiesOnItsHead) {
  // The README says the strands sit on their own head mesh in the same units. Oracle: the head
  // mesh's bounding box (read by the glTF loader, an independent parser) expanded by the
  // longest strand holds every point, and roots — which grow from the scalp — lie in the box
  // itself, within 1 % of its diagonal.
  MANE_RESOLVE_OR_SKIP(headFile, "hair/tressfx_ponytail/ponytail_head.converted.glb");
  auto head = loadGltf(headFile);
  ASSERT_TRUE(head.has_value()) << head.error().message;
  const Bounds box = head->bounds();
  const float margin = 0.01f * glm::length(box.size());
  for (const std::string& name : kPonytailGroups) {
    SCOPED_TRACE(name);
    MANE_RESOLVE_OR_SKIP(file, name);
    auto groom = loadTfx(file);
    ASSERT_TRUE(groom.has_value()) << groom.error().message;
    float longest = 0.0f;
    for (const std::vector<glm::vec3>& strand : groom->strands) {
      float length = 0.0f;
      for (std::size_t i = 1; i < strand.size(); ++i) length += glm::length(strand[i] - strand[i - 1]);
      longest = std::max(longest, length);
    }
    EXPECT_GT(longest, 0.05f * glm::length(box.size())) << "strands are hair, not stubble, at this scale";
    EXPECT_LT(longest, 2.0f * glm::length(box.size())) << "strands are not in different units from the head";
    for (std::size_t s = 0; s < groom->strands.size(); ++s) {
      const glm::vec3 root = groom->strands[s].front();
      ASSERT_TRUE(glm::all(glm::greaterThanEqual(root, box.min - margin)) &&
                  glm::all(glm::lessThanEqual(root, box.max + margin)))
          << "strand " << s << " root (" << root.x << ", " << root.y << ", " << root.z << ") outside the head box";
      for (const glm::vec3& p : groom->strands[s])
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, box.min - longest)) &&
                    glm::all(glm::lessThanEqual(p, box.max + longest)))
            << "strand " << s;
    }
  }
}

// --- Well-formed synthetic files ---------------------------------------------------------

TEST(GroomLoader, TfxV3AndV4LayoutsGiveTheSamePoints) {
  ScratchDir dir;
  auto v3 = loadTfx(dir.write("v3.tfx", tfxV3(3, 5, 15)));
  ASSERT_TRUE(v3.has_value()) << v3.error().message;
  auto v4 = loadTfx(dir.write("v4.tfx", tfxV4(3, 5)));
  ASSERT_TRUE(v4.has_value()) << v4.error().message;
  ASSERT_EQ(v3->strands.size(), 3u);
  for (std::size_t s = 0; s < 3; ++s)
    for (std::size_t v = 0; v < 5; ++v) EXPECT_EQ(v3->strands[s][v], syntheticPoint(s, v));
  EXPECT_TRUE(v3->strands == v4->strands);
}

TEST(GroomLoader, CyHairSegmentsArrayGivesStrandsOfDifferentLengths) {
  ScratchDir dir;
  auto hair = loadCyHair(dir.write("mixed.hair", cyHair({1, 4, 2}, 3, 0)));
  ASSERT_TRUE(hair.has_value()) << hair.error().message;
  ASSERT_EQ(hair->strands.size(), 3u);
  EXPECT_EQ(hair->strands[0].size(), 2u);
  EXPECT_EQ(hair->strands[1].size(), 5u);
  EXPECT_EQ(hair->strands[2].size(), 3u);
  EXPECT_EQ(hair->strands[1][4], syntheticPoint(1, 4));
}

TEST(GroomLoader, CyHairOptionalArraysAfterThePointsMustBeComplete) {
  // Thickness (4 B/point) and colours (12 B/point) follow the points and must be in the file
  // (their values: groom_repair_tests.cpp).
  ScratchDir dir;
  std::string bytes = cyHair({}, 2, 3, 4u | 16u);
  bytes.append(8 * 16, '\0');
  auto hair = loadCyHair(dir.write("full.hair", bytes));
  ASSERT_TRUE(hair.has_value()) << hair.error().message;
  EXPECT_EQ(hair->pointCount(), 8u);

  bytes.resize(bytes.size() - 1);
  expectError(loadCyHair(dir.write("cut.hair", bytes)), {"cut.hair", "colours array", "truncated"});
}

TEST(GroomLoader, DispatchesByExtensionCaseInsensitively) {
  ScratchDir dir;
  EXPECT_TRUE(loadGroomFile(dir.write("a.TFX", tfxV3(1, 2, 2))).has_value());
  EXPECT_TRUE(loadGroomFile(dir.write("a.Hair", cyHair({}, 1, 1))).has_value());
  expectError(loadGroomFile(dir.write("a.abc", "x")), {"a.abc", "unsupported groom file extension", ".abc"});
  expectError(loadGroomFile(dir.path() / "absent.tfx"), {"absent.tfx", "not found"});
}

// --- Malformed files ---------------------------------------------------------------------

TEST(GroomLoaderMalformed, TfxTruncatedAnywhereIsAnErrorNamingTheFile) {
  // Cut a valid 4 × 16 file inside the version, inside the header, right after it, and in
  // the middle of a vertex.
  const std::string whole = tfxV3(4, 16, 64);
  ScratchDir dir;
  for (std::size_t length : {0u, 3u, 100u, 295u, 296u, 296u + 12u * 20u + 7u, 296u + 12u * 64u - 1u}) {
    SCOPED_TRACE(length);
    expectError(loadTfx(dir.write("cut.tfx", whole.substr(0, length))), {"cut.tfx", "truncated"});
  }
  EXPECT_TRUE(loadTfx(dir.write("whole.tfx", whole)).has_value());
}

TEST(GroomLoaderMalformed, RealTfxTruncatedMidArray) {
  MANE_RESOLVE_OR_SKIP(file, "hair/tressfx_ponytail/tail.tfx");
  const std::string bytes = readFile(file);
  ScratchDir dir;
  for (std::size_t length : {std::size_t{150}, bytes.size() / 2, bytes.size() - 1}) {
    SCOPED_TRACE(length);
    expectError(loadTfx(dir.write("tail.tfx", bytes.substr(0, length))), {"tail.tfx", "truncated"});
  }
}

TEST(GroomLoaderMalformed, TfxWithFewerThanTwoVerticesPerStrand) {
  ScratchDir dir;
  expectError(loadTfx(dir.write("zero.tfx", tfxV3(4, 0, 0))), {"zero.tfx", "0 vertices per strand", "at least 2"});
  expectError(loadTfx(dir.write("one.tfx", tfxV3(4, 1, 4))), {"one.tfx", "1 vertices per strand", "at least 2"});
  expectError(loadTfx(dir.write("none.tfx", tfxV3(0, 4, 0))), {"none.tfx", "0 strands", "empty"});
}

TEST(GroomLoaderMalformed, TfxCountsWhoseProductOverflowsAreRejectedNotAllocated) {
  // 2^32−1 strands × 2^32−1 vertices × 12 bytes overflows 64 bits; 2^31 × 8 overflows 32 bits
  // to 0. Either must be found too large for the file, without allocating.
  ScratchDir dir;
  expectError(loadTfx(dir.write("huge.tfx", tfxV3(0xFFFFFFFFu, 0xFFFFFFFFu, 8))),
              {"huge.tfx", "4294967295 strands", "truncated, or the counts are corrupt"});
  expectError(loadTfx(dir.write("wrap.tfx", tfxV3(0x80000000u, 8, 8))),
              {"wrap.tfx", "2147483648 strands", "truncated, or the counts are corrupt"});
}

TEST(GroomLoaderMalformed, TfxVertexOffsetOutsideTheFile) {
  ScratchDir dir;
  std::string bytes = tfxV3(1, 4, 4);
  putU32(bytes, 144, 0xFFFFFFF0u);
  expectError(loadTfx(dir.write("far.tfx", bytes)), {"far.tfx", "past the end", "byte 144"});
  putU32(bytes, 144, 16);
  expectError(loadTfx(dir.write("inside.tfx", bytes)), {"inside.tfx", "points into", "header"});
}

TEST(GroomLoaderMalformed, TfxWrongVersionIsNotATfxFile) {
  ScratchDir dir;
  std::string bytes = tfxV3(1, 4, 4);
  putF32(bytes, 0, 2.0f);
  expectError(loadTfx(dir.write("old.tfx", bytes)), {"old.tfx", "version 2", "not supported"});
  putF32(bytes, 0, std::numeric_limits<float>::quiet_NaN());
  expectError(loadTfx(dir.write("nan.tfx", bytes)), {"nan.tfx", "version", "not supported"});
  std::string png("\x89PNG\r\n\x1a\n", 8);
  png.append(400, 'x');
  expectError(loadTfx(dir.write("png.tfx", png)), {"png.tfx", "not supported"});
}

// Flaws in single strands are repaired or dropped (groom_repair_tests.cpp); loaded strictly,
// they are errors naming the strand, the point and the byte.
constexpr GroomLoadOptions kStrict{.strict = true};

TEST(GroomLoaderMalformed, StrictNanVertexNamesStrandVertexAndByte) {
  ScratchDir dir;
  std::string bytes = tfxV3(3, 4, 12);
  // Strand 1, vertex 2 = vertex 6 of the array, which starts at byte 296 + 6·12 = 368; its y is NaN.
  putF32(bytes, 296 + 6 * 12 + 4, std::numeric_limits<float>::quiet_NaN());
  expectError(loadTfx(dir.write("nan.tfx", bytes), kStrict), {"nan.tfx", "strand 1, vertex 2", "byte 368", "not finite"});

  std::string hair = cyHair({}, 2, 3);
  putF32(hair, 128 + 5 * 12, std::numeric_limits<float>::infinity());  // hair 1, point 1, x
  expectError(loadCyHair(dir.write("inf.hair", hair), kStrict),
              {"inf.hair", "strand 1, point 1", "byte 188", "not finite"});
}

TEST(GroomLoaderMalformed, StrictZeroLengthSegmentNamesBothVertices) {
  ScratchDir dir;
  std::string bytes = tfxV3(2, 4, 8);
  // Strand 1, vertex 3 := vertex 2.
  std::memmove(bytes.data() + 296 + 7 * 12, bytes.data() + 296 + 6 * 12, 12);
  expectError(loadTfx(dir.write("flat.tfx", bytes), kStrict),
              {"flat.tfx", "strand 1, vertex 3", "vertex 2", "zero-length"});
}

TEST(GroomLoaderMalformed, CyHairHeaderProblems) {
  ScratchDir dir;
  std::string bytes = cyHair({}, 2, 3);
  expectError(loadCyHair(dir.write("short.hair", bytes.substr(0, 127))), {"short.hair", "128-byte", "truncated"});
  expectError(loadCyHair(dir.write("mid.hair", bytes.substr(0, 128 + 12 * 5 + 2))),
              {"mid.hair", "points array", "truncated"});

  std::string magic = bytes;
  magic[3] = 'X';
  expectError(loadCyHair(dir.write("magic.hair", magic)), {"magic.hair", "\"HAIX\"", "not a HAIR file"});

  std::string noPoints = bytes;
  putU32(noPoints, 12, 0);
  expectError(loadCyHair(dir.write("nopoints.hair", noPoints)), {"nopoints.hair", "no point array"});

  std::string mismatch = bytes;
  putU32(mismatch, 8, 7);  // 2 hairs × 4 points = 8
  expectError(loadCyHair(dir.write("count.hair", mismatch)), {"count.hair", "make 8 points", "declares 7"});

  std::string zeroDefault = bytes;
  putU32(zeroDefault, 16, 0);
  expectError(loadCyHair(dir.write("zerodefault.hair", zeroDefault)), {"zerodefault.hair", "default segment count"});

  std::string huge = bytes;
  putU32(huge, 4, 0xFFFFFFFFu);
  putU32(huge, 8, 0xFFFFFFFFu);
  expectError(loadCyHair(dir.write("huge.hair", huge)), {"huge.hair", "points array", "truncated"});

  expectError(loadCyHair(dir.write("zeroseg.hair", cyHair({2, 0, 1}, 3, 0)), kStrict),
              {"zeroseg.hair", "strand 1 has 0 segments", "byte 130"});
}

// --- The World ---------------------------------------------------------------------------

std::string groomScene(const std::string& headSource, float scale, const std::string& groomSource) {
  return R"({"name": "groomed", "camera": {"position": [0, 1, 3], "target": [0, 1, 0]},
      "meshes": [{"name": "head", "source": ")" +
         headSource + R"(", "transform": {"scale": )" + std::to_string(scale) + R"(}}],
      "grooms": [{"name": "hair", "source": ")" +
         groomSource + R"(", "attached_mesh": "head"}]})";
}

TEST(GroomLoaderWorld, LoadsAGroomFileOntoItsMeshAndSimulatesIt) {
  MANE_RESOLVE_OR_SKIP(head, "hair/tressfx_ponytail/ponytail_head.converted.glb");
  auto scene = parseScene(
      groomScene("hair/tressfx_ponytail/ponytail_head.converted.glb", 0.01f, "hair/tressfx_ponytail/tail.tfx"),
      "groomed.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  auto world = World::create(std::move(*scene), sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world.has_value()) << world.error().message;
  EXPECT_EQ(world->guideStrandCount(), 474u);  // tail.tfx, see kTfxAssets
  EXPECT_EQ(world->particleCount(), 474u * 16u);
  const std::uint64_t before = world->stateHash();
  ASSERT_TRUE(world->advance(1.0 / 30.0, 2).has_value());
  EXPECT_NE(world->stateHash(), before) << "the hair falls under gravity";
}

TEST(GroomLoaderWorld, MissingGroomAssetIsANoteAndTheGroomIsSkipped) {
  AssetResolverSettings settings = defaultAssetResolverSettings();
  settings.searchRoots.clear();
  settings.cacheDirectory.clear();
  settings.allowDownload = false;
  auto resolver = AssetResolver::create(settings);
  ASSERT_TRUE(resolver.has_value()) << resolver.error().message;
  auto scene = parseScene(groomScene("procedural:sphere", 0.1f, "hair/tressfx_bear_fur/bear.tfx"), "bear.json");
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  auto world = World::create(std::move(*scene), *resolver, {.loadTextures = false});
  ASSERT_TRUE(world.has_value()) << world.error().message;
  EXPECT_EQ(world->guideStrandCount(), 0u);
  ASSERT_EQ(world->notes().size(), 1u);
  EXPECT_NE(world->notes()[0].find("groom hair"), std::string::npos) << world->notes()[0];
  EXPECT_NE(world->notes()[0].find("bear.tfx missing"), std::string::npos) << world->notes()[0];
  ASSERT_TRUE(world->advance(0.1, 1).has_value());
}

TEST(GroomLoaderWorld, MalformedGroomFileIsAnError) {
  ScratchDir dir;
  dir.write("bad.hair", cyHair({}, 2, 3).substr(0, 150));
  const std::filesystem::path sceneFile =
      dir.write("scene.json", groomScene("procedural:sphere", 0.1f, "bad.hair"));  // relative to the scene
  auto scene = loadScene(sceneFile);
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  auto world = World::create(std::move(*scene), sharedResolver(), {.loadTextures = false});
  expectError(world, {"groom hair", "bad.hair", "truncated"});
}

TEST(GroomLoaderWorld, UserGroomFileIsScaledWithItsMesh) {
  // A user's own .hair next to the scene (a path, not a manifest name), on a mesh scaled by
  // 0.5: found relative to the scene file, loaded, and simulated without a note.
  ScratchDir dir;
  dir.write("user.hair", cyHair({}, 3, 5));
  const std::filesystem::path sceneFile = dir.write("scene.json", groomScene("procedural:sphere", 0.5f, "user.hair"));
  auto scene = loadScene(sceneFile);
  ASSERT_TRUE(scene.has_value()) << scene.error().message;
  auto world = World::create(std::move(*scene), sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(world.has_value()) << world.error().message;
  EXPECT_EQ(world->guideStrandCount(), 3u);
  EXPECT_EQ(world->particleCount(), 18u);
  EXPECT_TRUE(world->notes().empty());
  ASSERT_TRUE(world->advance(0.25, 1).has_value());
}

TEST(GroomLoaderWorld, InvertZNegatesTheFilesZ) {
  // `invert_z` mirrors the file's points in z before they go on the mesh (TressFX's exporter
  // can write z inverted); x and y are untouched. Placed at rest, the mirrored groom is the
  // plain one with z negated, point for point (the synthetic strands have z ≠ 0).
  ScratchDir dir;
  dir.write("user.hair", cyHair({}, 3, 5));
  std::string text = groomScene("procedural:sphere", 0.5f, "user.hair");
  const std::filesystem::path plainFile = dir.write("plain.json", text);
  const std::string attached = R"("attached_mesh": "head")";
  text.replace(text.find(attached), attached.size(), attached + R"(, "invert_z": true)");
  const std::filesystem::path mirroredFile = dir.write("mirrored.json", text);
  auto plain = World::create(*loadScene(plainFile), sharedResolver(), {.loadTextures = false});
  auto mirrored = World::create(*loadScene(mirroredFile), sharedResolver(), {.loadTextures = false});
  ASSERT_TRUE(plain.has_value()) << plain.error().message;
  ASSERT_TRUE(mirrored.has_value()) << mirrored.error().message;
  ASSERT_TRUE(mirrored->scene().grooms[0].invertZ);
  const auto& a = plain->simulatedGroom(0).particles().positions;
  const auto& b = mirrored->simulatedGroom(0).particles().positions;
  ASSERT_EQ(a.size(), b.size());
  float largestZ = 0.0f;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(b[i], glm::vec3(a[i].x, a[i].y, -a[i].z)) << "particle " << i;
    largestZ = std::max(largestZ, std::abs(a[i].z));
  }
  EXPECT_GT(largestZ, 0.0f);
}

}  // namespace
}  // namespace mane::scenes
