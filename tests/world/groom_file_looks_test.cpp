// Groom files' own looks (scenes/groom_looks.hpp) reach the renderer and the picture: a `.hair`
// file's thickness, transparency and colour (its arrays, or its header's defaults) and a `.tfx`
// file's per-strand thickness become the dense strands' looks, where the scene's `render` block
// does not give them itself; then rendered, a set of strands twice as thick covers about twice
// the pixels, a red file draws red hair and a transparent one draws less of it.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <utility>
#include <cstring>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "render/png.hpp"
#include "render/renderer.hpp"
#include "scenes/world.hpp"
#include "tests/scenes/test_support.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::scenes {
namespace {

using testing::resolverWithoutAssets;
using testing::ScratchDir;

/// One strand of a test HAIR file: its root's x (cm: the file's units), and what the file's
/// arrays say of it (the same at every point, except a thickness tapering to `tipThickness`).
struct FileStrand {
  float x = 0.0f;
  float thickness = 0.0f;  ///< cm, at the root
  float transparency = 0.0f;
  glm::vec3 colour{1.0f};
  float tipThickness = -1.0f;  ///< cm; < 0: the root's
};

void put(std::string& bytes, const void* value, std::size_t size) {
  bytes.append(static_cast<const char*>(value), size);
}
void putFloat(std::string& bytes, float value) {
  put(bytes, &value, 4);
}

/// A HAIR file (cyHairFile.h: a 128-byte header, then the arrays its flags announce) of strands
/// hanging 8 cm straight down −Y in 3 segments from roots at y = 4 cm, z = 0. With `arrays` the
/// file carries thickness, transparency and colour arrays; without, only `defaults` in the header
/// speak for them.
std::string hairFile(const std::vector<FileStrand>& strands, bool arrays, const FileStrand& defaults = {}) {
  constexpr std::uint32_t kPoints = 4;
  std::string bytes = "HAIR";
  const std::uint32_t header[] = {static_cast<std::uint32_t>(strands.size()),
                                  kPoints * static_cast<std::uint32_t>(strands.size()),
                                  2u /* points */ | (arrays ? 4u | 8u | 16u : 0u), kPoints - 1};
  put(bytes, header, sizeof header);
  putFloat(bytes, defaults.thickness);
  putFloat(bytes, defaults.transparency);
  for (int c = 0; c < 3; ++c) putFloat(bytes, defaults.colour[c]);
  bytes.resize(128, '\0');
  for (const FileStrand& strand : strands)
    for (std::uint32_t v = 0; v < kPoints; ++v) {
      const float point[3] = {strand.x, 4.0f - 8.0f * static_cast<float>(v) / (kPoints - 1), 0.0f};
      put(bytes, point, sizeof point);
    }
  if (!arrays) return bytes;
  for (const FileStrand& strand : strands)
    for (std::uint32_t v = 0; v < kPoints; ++v) {
      const float tip = strand.tipThickness < 0.0f ? strand.thickness : strand.tipThickness;
      putFloat(bytes, strand.thickness + (tip - strand.thickness) * static_cast<float>(v) / (kPoints - 1));
    }
  for (const FileStrand& strand : strands)
    for (std::uint32_t v = 0; v < kPoints; ++v) putFloat(bytes, strand.transparency);
  for (const FileStrand& strand : strands)
    for (std::uint32_t v = 0; v < kPoints; ++v)
      for (int c = 0; c < 3; ++c) putFloat(bytes, strand.colour[c]);
  return bytes;
}

/// Ten strands 3 cm apart: five thin ones (2 mm) at x = −3 … −15 cm, five twice as thick (4 mm)
/// at x = 3 … 15 cm, all opaque and red.
std::vector<FileStrand> thinAndThick() {
  std::vector<FileStrand> strands;
  for (int k = 0; k < 5; ++k) strands.push_back({.x = -3.0f - 3.0f * k, .thickness = 0.2f, .colour = {1, 0, 0}});
  for (int k = 0; k < 5; ++k) strands.push_back({.x = 3.0f + 3.0f * k, .thickness = 0.4f, .colour = {1, 0, 0}});
  return strands;
}

/// Behind the strands (the light through the fibres, TT, shows) and in front of them.
const std::string kBackAndFrontLights = R"([{"kind": "directional", "direction": [0.1, 0.05, 1], "intensity": 3.0},
    {"kind": "directional", "direction": [0.3, 0.1, -1], "intensity": 1.5}])";
/// In front, dimly: hair that stays far from white after tone mapping, so that less of it shows
/// as a smaller change.
const std::string kDimFrontLight = R"([{"kind": "directional", "direction": [0, -0.3, -1], "intensity": 1.0}])";

/// A scene holding `file`'s strands on a 1 cm sphere scaled 0.01 (file centimetres → metres),
/// one dense strand per guide, seen head-on from 0.5 m over 40 × 12 cm in 1200 × 360 pixels
/// (3,000 pixels per metre), under `lights`, hair shadows off (the sphere stays the same with
/// and without hair), not simulated before the first frame. `render` adds to the groom's
/// `render` block.
std::filesystem::path looksScene(const ScratchDir& dir, const std::string& file, std::size_t strands,
                                 const std::string& render = "", const std::string& lights = kBackAndFrontLights) {
  return dir.write("scene.json", R"({"name": "looks", "output": {"width": 1200, "height": 360},
      "camera": {"position": [0, 0, 0.5], "target": [0, 0, 0], "fov_degrees": 13.686},
      "lights": )" + lights + R"(,
      "meshes": [{"name": "head", "source": "procedural:sphere", "transform": {"scale": 0.01}}],
      "grooms": [{"name": "hair", "source": ")" + file + R"(", "attached_mesh": "head",
                  "render": {"strands": )" + std::to_string(strands) + render + R"(}}],
      "hair_shadows": {"mode": "off"},
      "simulation": {"settle_seconds": 0}})");
}

Result<World> worldOf(const std::filesystem::path& scene) {
  auto parsed = loadScene(scene);
  if (!parsed) return std::unexpected(parsed.error());
  return World::create(std::move(*parsed), resolverWithoutAssets(), {.loadTextures = false});
}

// --- From the file to the renderer (CPU) -------------------------------------------------

TEST(GroomFileLooks, AHairFilesThicknessTransparencyAndColourBecomeItsStrandsLooks) {
  // Width: root thickness × the mesh's scale 0.01, over the groom's width (0.4 mm by default):
  // 2 mm → 5, 4 mm → 10; taper tip / root; opacity 1 − transparency; colour as stored. One
  // dense strand per guide, each its own guide's look.
  ScratchDir dir;
  std::vector<FileStrand> strands = thinAndThick();
  strands[1].tipThickness = 0.05f;
  strands[2].transparency = 0.25f;
  strands[3].colour = {0.2f, 0.4f, 0.6f};
  dir.write("strands.hair", hairFile(strands, true));
  auto world = worldOf(looksScene(dir, "strands.hair", strands.size()));
  ASSERT_TRUE(world.has_value()) << world.error().message;
  EXPECT_TRUE(world->notes().empty()) << ::testing::PrintToString(world->notes());
  const render::StaticScene statics = world->staticScene();
  ASSERT_EQ(statics.grooms.size(), 1u);
  const render::HairGroomData& groom = statics.grooms[0];
  EXPECT_EQ(groom.settings.width, 4e-4f) << "the groom's own width stays the scale";
  ASSERT_EQ(groom.strandLooks.size(), strands.size());
  for (std::size_t s = 0; s < strands.size(); ++s) {
    SCOPED_TRACE("strand " + std::to_string(s));
    const render::HairStrandLook& look = groom.strandLooks[s];
    EXPECT_NEAR(look.widthScale * groom.settings.width, strands[s].thickness * 0.01f, 1e-8f);
    EXPECT_FLOAT_EQ(look.tipWidthScale, s == 1 ? 0.25f : 1.0f);
    EXPECT_FLOAT_EQ(look.opacityScale, s == 2 ? 0.75f : 1.0f);
    EXPECT_EQ(look.colour, strands[s].colour);
  }
  EXPECT_FLOAT_EQ(groom.strandLooks[5].widthScale, 2.0f * groom.strandLooks[0].widthScale);
}

TEST(GroomFileLooks, WithoutArraysTheHeadersDefaultsHoldForEveryStrand) {
  ScratchDir dir;
  std::vector<FileStrand> strands = thinAndThick();
  dir.write("defaults.hair",
            hairFile(strands, false, {.thickness = 0.3f, .transparency = 0.5f, .colour = {0.9f, 0.5f, 0.1f}}));
  auto world = worldOf(looksScene(dir, "defaults.hair", strands.size()));
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const render::HairGroomData groom = world->staticScene().grooms.at(0);
  ASSERT_EQ(groom.strandLooks.size(), strands.size());
  for (const render::HairStrandLook& look : groom.strandLooks) {
    EXPECT_NEAR(look.widthScale * groom.settings.width, 0.003f, 1e-8f);
    EXPECT_EQ(look.tipWidthScale, 1.0f);
    EXPECT_EQ(look.opacityScale, 0.5f);
    EXPECT_EQ(look.colour, glm::vec3(0.9f, 0.5f, 0.1f));
  }
}

TEST(GroomFileLooks, TheScenesRenderFieldsWinOverTheFiles) {
  // The scene gives width, opacity and colour: every strand has them; the file's taper, which
  // the scene leaves open, still holds.
  ScratchDir dir;
  std::vector<FileStrand> strands = thinAndThick();
  for (FileStrand& strand : strands) strand.tipThickness = 0.5f * strand.thickness, strand.transparency = 0.5f;
  dir.write("strands.hair", hairFile(strands, true));
  auto world = worldOf(looksScene(dir, "strands.hair", strands.size(),
                                  R"(, "width": 1e-4, "opacity": 0.8, "colour": [0.1, 0.2, 0.3])"));
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const render::HairGroomData groom = world->staticScene().grooms.at(0);
  EXPECT_EQ(groom.settings.width, 1e-4f);
  EXPECT_EQ(groom.settings.opacity, 0.8f);
  ASSERT_EQ(groom.strandLooks.size(), strands.size());
  for (const render::HairStrandLook& look : groom.strandLooks) {
    EXPECT_EQ(look.widthScale, 1.0f);
    EXPECT_EQ(look.opacityScale, 1.0f);
    EXPECT_EQ(look.colour, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_FLOAT_EQ(look.tipWidthScale, 0.5f);
  }
}

TEST(GroomFileLooks, AFileWidthThatIsNoStrandWidthFallsBackToTheGroomsWithANote) {
  // 5 cm at the root (a file in other units than its points?) is no strand width: the groom's
  // width stands in and a note says so. A thickness of 0 says nothing (no note).
  ScratchDir dir;
  std::vector<FileStrand> strands = thinAndThick();
  strands[0].thickness = 5.0f;
  strands[1].thickness = 0.0f;
  dir.write("strands.hair", hairFile(strands, true));
  auto world = worldOf(looksScene(dir, "strands.hair", strands.size()));
  ASSERT_TRUE(world.has_value()) << world.error().message;
  ASSERT_EQ(world->notes().size(), 1u) << ::testing::PrintToString(world->notes());
  for (const char* part : {"groom hair", "1 strand", "0.05 m", "(0, 0.01] m", "\"width\""})
    EXPECT_NE(world->notes()[0].find(part), std::string::npos) << "missing \"" << part << "\" in " << world->notes()[0];
  const render::HairGroomData groom = world->staticScene().grooms.at(0);
  EXPECT_EQ(groom.strandLooks.at(0).widthScale, 1.0f);
  EXPECT_EQ(groom.strandLooks.at(1).widthScale, 1.0f);
  EXPECT_FLOAT_EQ(groom.strandLooks.at(2).widthScale, 5.0f);
}

TEST(GroomFileLooks, GroomsNoFileOrSceneDescribesHandTheRendererNoLooks) {
  // A file whose header says white, opaque and no width (0), and a procedural groom: no looks,
  // so the renderer draws them exactly as before looks existed. A scene colour on a procedural
  // groom gives every strand that colour.
  ScratchDir dir;
  dir.write("plain.hair", hairFile(thinAndThick(), false, {.colour = glm::vec3(1.0f)}));
  auto world = worldOf(looksScene(dir, "plain.hair", 10));
  ASSERT_TRUE(world.has_value()) << world.error().message;
  EXPECT_TRUE(world->staticScene().grooms.at(0).strandLooks.empty());

  for (const std::string colour : {"", R"(, "colour": [1, 0.5, 0])"}) {
    auto scene = parseScene(R"({"name": "p", "camera": {"position": [0, 0, 3], "target": [0, 0, 0]},
        "meshes": [{"name": "head", "source": "procedural:sphere"}],
        "grooms": [{"name": "hair", "source": "procedural", "attached_mesh": "head", "strands": 40,
                    "render": {"strands": 300)" + colour + "}}]}",
                            "p.json");
    ASSERT_TRUE(scene.has_value()) << scene.error().message;
    auto procedural = World::create(std::move(*scene), resolverWithoutAssets(), {.loadTextures = false});
    ASSERT_TRUE(procedural.has_value()) << procedural.error().message;
    const render::HairGroomData groom = procedural->staticScene().grooms.at(0);
    if (colour.empty()) {
      EXPECT_TRUE(groom.strandLooks.empty());
    } else {
      ASSERT_EQ(groom.strandLooks.size(), 300u);
      for (const render::HairStrandLook& look : groom.strandLooks) EXPECT_EQ(look.colour, glm::vec3(1.0f, 0.5f, 0.0f));
    }
  }
}

TEST(GroomFileLooks, ATfxFilesPerStrandThicknessScalesTheGroomsWidth) {
  // TressFX's per-strand thickness is a factor of the groom's width (here the scene's 0.2 mm is
  // the scene's and holds for all: the file's factors are for a groom without one).
  ScratchDir dir;
  std::string bytes(296, '\0');
  const float version = 3.0f;
  const std::uint32_t counts[] = {2, 4};
  std::memcpy(bytes.data(), &version, 4);
  std::memcpy(bytes.data() + 4, counts, sizeof counts);
  const std::uint32_t vertices = 296, thickness = 296 + 2 * 4 * 12;
  std::memcpy(bytes.data() + 144, &vertices, 4);
  std::memcpy(bytes.data() + 156, &thickness, 4);
  for (int s = 0; s < 2; ++s)
    for (int v = 0; v < 4; ++v) {
      const float point[3] = {5.0f * s, -2.0f * v, 0.0f};
      put(bytes, point, sizeof point);
    }
  putFloat(bytes, 0.5f);
  putFloat(bytes, 2.0f);
  dir.write("two.tfx", bytes);
  auto world = worldOf(looksScene(dir, "two.tfx", 2));
  ASSERT_TRUE(world.has_value()) << world.error().message;
  const render::HairGroomData groom = world->staticScene().grooms.at(0);
  ASSERT_EQ(groom.strandLooks.size(), 2u);
  EXPECT_EQ(groom.strandLooks[0].widthScale, 0.5f);
  EXPECT_EQ(groom.strandLooks[1].widthScale, 2.0f);
  EXPECT_EQ(groom.strandLooks[1].colour, glm::vec3(1.0f));

  auto given = worldOf(looksScene(dir, "two.tfx", 2, R"(, "width": 2e-4)"));
  ASSERT_TRUE(given.has_value()) << given.error().message;
  EXPECT_TRUE(given->staticScene().grooms.at(0).strandLooks.empty());
}

// --- In the picture (lavapipe) ------------------------------------------------------------

class GroomFileLooksRender : public mane::testing::VulkanTest {
protected:
  /// The scene's frame with its hair, and without (the guides never uploaded), RGBA8.
  std::pair<std::vector<std::uint8_t>, std::vector<std::uint8_t>> frames(const std::filesystem::path& scene) {
    auto world = worldOf(scene);
    EXPECT_TRUE(world.has_value()) << world.error().message;
    const auto frame = [&](bool hair) {
      auto renderer = render::Renderer::create(device(), {.extent = {kWidth, kHeight}});
      EXPECT_TRUE(renderer.has_value()) << renderer.error().message;
      const auto set = (*renderer)->setScene(world->staticScene());
      EXPECT_TRUE(set.has_value()) << set.error().message;
      if (hair) {
        for (const auto& guides : world->hairGuides())
          EXPECT_TRUE((*renderer)->updateHair(guides.groom, guides.positions).has_value());
      }
      EXPECT_TRUE((*renderer)->render(world->frameInput()).has_value());
      return *(*renderer)->readOutput();
    };
    return {frame(true), frame(false)};
  }

  /// Keeps a frame for a person to look at (MANE_KEEP_FRAMES names a folder), as PNG.
  static void keep(const std::string& name, const std::vector<std::uint8_t>& rgba) {
    if (const char* folder = std::getenv("MANE_KEEP_FRAMES"))
      (void)render::writePng(std::filesystem::path(folder) / (name + ".png"), kWidth, kHeight, rgba);
  }

  static constexpr std::uint32_t kWidth = 1200, kHeight = 360;
};

/// Hair pixels of a frame: those that differ from the bare frame by more than `threshold` in some
/// channel, counted left and right of the centre, with their mean colour.
struct HairPixels {
  std::size_t left = 0, right = 0;
  glm::dvec3 meanColour{0.0};
  double difference = 0.0;  ///< Σ over pixels of the largest channel difference
};

HairPixels hairPixels(const std::vector<std::uint8_t>& hair, const std::vector<std::uint8_t>& bare, int threshold,
                      std::uint32_t width) {
  HairPixels result;
  for (std::size_t p = 0; p + 3 < hair.size(); p += 4) {
    int largest = 0;
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(hair[p + c]) - int(bare[p + c])));
    result.difference += largest;
    if (largest <= threshold) continue;
    ((p / 4) % width < width / 2 ? result.left : result.right) += 1;
    result.meanColour += glm::dvec3(hair[p], hair[p + 1], hair[p + 2]);
  }
  if (result.left + result.right > 0) result.meanColour /= double(result.left + result.right);
  return result;
}

TEST_F(GroomFileLooksRender, StrandsTwiceAsThickCoverAboutTwiceThePixelsInTheFilesColour) {
  // At 3,000 pixels per metre the thin strands are 6 pixels wide and the thick ones 12: the thick
  // set must cover twice the thin set's pixels within 15 %. Why that much: a pixel counts as hair
  // when the hair changes it by more than 24 of 255, so each edge of a strand gains or loses up
  // to half a pixel per row (±8 % of a 6-pixel strand, averaged over the strands' sub-pixel
  // positions); and the dense strands differ in length by up to 10 % and are offset sideways at
  // random (the layout's length variation and root spread), which moves each set's total a few
  // per cent. The file's red reaches the picture: the hair pixels are red-dominant.
  ScratchDir dir;
  dir.write("strands.hair", hairFile(thinAndThick(), true));
  const auto [hair, bare] = frames(looksScene(dir, "strands.hair", 10));
  keep("thin_and_thick_red", hair);
  const HairPixels pixels = hairPixels(hair, bare, 24, kWidth);
  ASSERT_GT(pixels.left, 500u) << "the thin strands show";
  const double ratio = double(pixels.right) / double(pixels.left);
  EXPECT_NEAR(ratio, 2.0, 0.3) << pixels.right << " thick-strand pixels vs " << pixels.left << " thin";
  EXPECT_GT(pixels.meanColour.r, 2.0 * pixels.meanColour.g);
  EXPECT_GT(pixels.meanColour.r, 2.0 * pixels.meanColour.b);
  std::printf("file looks: thin %zu px, thick %zu px (ratio %.3f), mean hair colour (%.1f %.1f %.1f)\n", pixels.left,
              pixels.right, ratio, pixels.meanColour.r, pixels.meanColour.g, pixels.meanColour.b);

  // The same strands white: their pixels are not red-dominant (what made them red is the file).
  std::vector<FileStrand> white = thinAndThick();
  for (FileStrand& strand : white) strand.colour = glm::vec3(1.0f);
  dir.write("white.hair", hairFile(white, true));
  const auto [whiteHair, whiteBare] = frames(looksScene(dir, "white.hair", 10));
  keep("thin_and_thick_white", whiteHair);
  const HairPixels whitePixels = hairPixels(whiteHair, whiteBare, 24, kWidth);
  EXPECT_GT(whitePixels.meanColour.g, 0.5 * whitePixels.meanColour.r);
  std::printf("file looks: white strands' mean colour (%.1f %.1f %.1f)\n", whitePixels.meanColour.r,
              whitePixels.meanColour.g, whitePixels.meanColour.b);
}

TEST_F(GroomFileLooksRender, TransparentStrandsChangeLessOfThePicture) {
  // The same strands half transparent (the file's transparency array), dimly lit: each changes
  // the pixels under it less, in all by well under the opaque strands' difference (the tone
  // mapping is not linear, so no exact half is expected), and still by something.
  ScratchDir dir;
  std::vector<FileStrand> strands = thinAndThick();
  dir.write("opaque.hair", hairFile(strands, true));
  for (FileStrand& strand : strands) strand.transparency = 0.5f;
  dir.write("transparent.hair", hairFile(strands, true));
  const auto [opaque, opaqueBare] = frames(looksScene(dir, "opaque.hair", 10, "", kDimFrontLight));
  const auto [transparent, transparentBare] = frames(looksScene(dir, "transparent.hair", 10, "", kDimFrontLight));
  keep("thin_and_thick_transparent", transparent);
  const double opaqueDifference = hairPixels(opaque, opaqueBare, 24, kWidth).difference;
  const double transparentDifference = hairPixels(transparent, transparentBare, 24, kWidth).difference;
  EXPECT_LT(transparentDifference, 0.8 * opaqueDifference);
  EXPECT_GT(transparentDifference, 0.2 * opaqueDifference);
  std::printf("file looks: summed difference opaque %.0f, half transparent %.0f\n", opaqueDifference,
              transparentDifference);
}

}  // namespace
}  // namespace mane::scenes
