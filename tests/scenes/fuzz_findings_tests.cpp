// Inputs the loader fuzzers (tests/fuzz/) found, fed back to their loaders: each must give its
// result, keeping the promises its header makes, or an error naming the file and the problem.
// Where a finding had relatives the fuzzer had not reached yet, they are here too.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "groom_test_files.hpp"
#include "scenes/groom_loader.hpp"
#include "scenes/groom_repair.hpp"
#include "scenes/image.hpp"
#include "scenes/obj_loader.hpp"
#include "scenes/sim_state.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using namespace std::string_literals;
using testing::putF32;
using testing::ScratchDir;
using testing::tfxV3;

/// A TressFX 3.x file holding exactly these strands (all of one point count).
std::string tfxWith(const std::vector<std::vector<glm::vec3>>& strands) {
  const auto verts = static_cast<std::uint32_t>(strands.front().size());
  std::string bytes = tfxV3(static_cast<std::uint32_t>(strands.size()), verts, 0);
  for (const auto& strand : strands)
    for (const glm::vec3& p : strand)
      for (int c = 0; c < 3; ++c) putF32(bytes, bytes.size(), p[c]);
  return bytes;
}

/// StrandSet's promise (groom_loader.hpp): every strand has ≥ 2 finite points, no two
/// consecutive ones equal, and the groom's flaws are all accounted for.
void expectStrandSetPromises(const StrandSet& groom) {
  EXPECT_EQ(groom.strands.size() + groom.repairs.droppedCount(), groom.repairs.strandsRead);
  for (std::size_t s = 0; s < groom.strands.size(); ++s) {
    const auto& strand = groom.strands[s];
    EXPECT_GE(strand.size(), 2u) << "strand " << s;
    for (std::size_t i = 0; i < strand.size(); ++i) {
      EXPECT_TRUE(std::isfinite(strand[i].x) && std::isfinite(strand[i].y) && std::isfinite(strand[i].z))
          << "strand " << s << ", point " << i;
      if (i > 0) {
        EXPECT_NE(strand[i], strand[i - 1]) << "strand " << s << ", point " << i;
      }
    }
  }
}

// --- Groom repair ------------------------------------------------------------------------

// Found by tests/fuzz/fuzz_groom: a strand with a repeated point, all of whose coordinates are
// subnormal, was merged and then split back to its count at the midpoint of its longest
// segment; that midpoint rounded to one of the segment's ends, a repeated point again. Strand 0
// still splits (its midpoint 1.5 × 2^-140 is representable) and is kept; strand 1's cannot
// (half of 2^-149 rounds to 0) and it is dropped.
TEST(FuzzFindings, GroomStrandWithSubnormalPointsNeverKeepsARepeatedPoint) {
  ScratchDir dir;
  const float a = std::ldexp(1.0f, -139);
  const float b = std::ldexp(1.0f, -140);
  const float tiny = std::ldexp(1.0f, -149);  // the smallest positive float
  const std::string bytes =
      tfxWith({{{0, 0, a}, {0, 0, a}, {0, 0, b}, {0, 0, 0}}, {{0, 0, 0}, {0, 0, 0}, {0, 0, tiny}, {0, 0, 0}}});
  auto groom = loadTfx(dir.write("subnormal.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  expectStrandSetPromises(*groom);
  ASSERT_EQ(groom->strands.size(), 1u);
  EXPECT_EQ(groom->strands[0].size(), 4u);
  EXPECT_EQ(groom->repairs.summary(),
            "2 strands read: 1 repaired (1 with a repeated point: 0), 1 dropped (1 with fewer than two distinct points: 1)");
}

// The same at ordinary magnitudes: at x = 16384 one float step is about 2 mm, the size of this
// groom's segments (so rule 2 keeps them), and a strand whose points are one step apart has no
// point between them to split at.
TEST(FuzzFindings, GroomStrandAtFloatResolutionIsDroppedRatherThanSplit) {
  ScratchDir dir;
  const float x0 = 16384.0f;
  const float x1 = std::nextafter(x0, 1e9f);
  const float x2 = std::nextafter(x1, 1e9f);
  const std::string bytes = tfxWith({{{0, 0, 0}, {0, -2e-3f, 0}, {0, -4e-3f, 0}, {0, -6e-3f, 0}},
                                     {{1, 0, 0}, {1, -2e-3f, 0}, {1, -4e-3f, 0}, {1, -6e-3f, 0}},
                                     {{x0, 0, 0}, {x0, 0, 0}, {x1, 0, 0}, {x2, 0, 0}}});
  auto groom = loadTfx(dir.write("resolution.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  expectStrandSetPromises(*groom);
  ASSERT_EQ(groom->strands.size(), 2u);
  ASSERT_EQ(groom->repairs.repairs.size(), 1u);
  EXPECT_EQ(groom->repairs.repairs[0].strand, 2u);
  EXPECT_EQ(groom->repairs.repairs[0].point, 1u);
  EXPECT_EQ(groom->repairs.repairs[0].flaw, StrandFlaw::kTooFewPoints);
}

// Splitting must not make zero-length segments either: with 1 m segments the bound is 1 µm, and
// a strand of 1.5 µm segments (kept by rule 2) has none that halves into two over it.
TEST(FuzzFindings, GroomStrandTooShortToSplitOverTheZeroLengthBoundIsDropped) {
  ScratchDir dir;
  const float step = 1.5f * kZeroLengthFraction;
  const std::string bytes = tfxWith({{{0, 0, 0}, {0, -1, 0}, {0, -2, 0}, {0, -3, 0}},
                                     {{1, 0, 0}, {1, -1, 0}, {1, -2, 0}, {1, -3, 0}},
                                     {{2, 0, 0}, {2, -1, 0}, {2, -2, 0}, {2, -3, 0}},
                                     {{0.5f, 0, 0}, {0.5f, 0, 0}, {0.5f + step, 0, 0}, {0.5f + 2 * step, 0, 0}}});
  auto groom = loadTfx(dir.write("short.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  expectStrandSetPromises(*groom);
  EXPECT_EQ(groom->strands.size(), 3u);
  ASSERT_EQ(groom->repairs.repairs.size(), 1u);
  EXPECT_EQ(groom->repairs.repairs[0].strand, 3u);
  EXPECT_EQ(groom->repairs.repairs[0].flaw, StrandFlaw::kTooFewPoints);
}

// Found while fixing the above: the midpoint was (a + b) / 2, which overflows to infinity for
// finite points past half the float range; a groom at that scale (its median segment already
// infinite in length, so nothing is absurd) got a non-finite point from its repair.
TEST(FuzzFindings, GroomRepairNearTheFloatLimitKeepsItsPointsFinite) {
  ScratchDir dir;
  const std::string bytes = tfxWith({{{3e38f, 0, 0}, {2e38f, 0, 0}, {1e38f, 0, 0}, {0, 0, 0}},
                                     {{3e38f, 1, 0}, {2e38f, 1, 0}, {1e38f, 1, 0}, {0, 1, 0}},
                                     {{3e38f, 2, 0}, {3e38f, 2, 0}, {2e38f, 2, 0}, {1e38f, 2, 0}}});
  auto groom = loadTfx(dir.write("huge.tfx", bytes));
  ASSERT_TRUE(groom.has_value()) << groom.error().message;
  expectStrandSetPromises(*groom);
  ASSERT_EQ(groom->strands.size(), 3u);
  ASSERT_EQ(groom->strands[2].size(), 4u);
  EXPECT_GT(groom->strands[2][1].x, 2e38f);  // between the ends of the split segment
  EXPECT_LT(groom->strands[2][1].x, 3e38f);
}

// --- Images -------------------------------------------------------------------------------

// Found by tests/fuzz/fuzz_image: stb_image 2.27 reads a PPM/PGM header's numbers into an int
// unchecked, and a ten-digit height overflowed it (undefined behaviour). Refused, naming the
// number; comments and leading zeros are read past as stb_image reads them.
TEST(FuzzFindings, PnmHeaderBeyondIntOrBeyondTheFileIsRefusedNamingIt) {
  ScratchDir dir;
  testing::expectError(loadImage(dir.write("tall.ppm", "P6\n2\t\n5555222552\x02\0\n\x01=\x02\x0b"s)),
                       {"tall.ppm", "PNM header", "height 5555222552", "too large"});
  testing::expectError(loadImage(dir.write("deep.pgm", "P5 # a comment\n 1 1\n#\n99999999999999999999999 x")),
                       {"deep.pgm", "maximum value 99999999999999999999"});
  // The timeout the fuzzer found next: 4014 x 4014 pixels declared by a 95-byte file, which
  // stb_image 2.27 decodes into whatever its allocation held. A file short of its pixels is
  // refused, saying what the header declares.
  testing::expectError(loadImage(dir.write("short.ppm", "P6\n\t\t\n 4014\t\n 4014\n 255\n\x01\x02\x03"s)),
                       {"short.ppm", "truncated PNM", "4014 x 4014 pixels of 3 bytes from byte 24",
                        "need 48336612 bytes", "the file has 27"});
  auto image = loadImage(dir.write("zeros.pgm", "P5 0000000000001 01 0000000000255\n\x80"s));
  ASSERT_TRUE(image.has_value()) << image.error().message;
  EXPECT_EQ(image->width, 1);
  EXPECT_EQ(image->rgba[0], 0x80);
}

// Found by tests/fuzz/fuzz_image (a timeout): a 21-byte TGA declaring 3855 x 3855 pixels,
// which stb_image decoded, reading zeros past the end of the file, into a black image; seconds
// under the sanitizers. A TGA shorter than its header says is refused; uncompressed data must be
// all there, run-length-encoded data at least a packet byte and a pixel per 128 pixels.
TEST(FuzzFindings, TruncatedTgaIsRefusedSayingWhatItDeclares) {
  ScratchDir dir;
  const std::string found = "\xcd\x00\x02\x64\x64\x64\x64\x02\x0f\x05\x0f\x0f\x0f\x0f\x0f\x0f\x0f\xa9\x81\x0a\x04"s;
  testing::expectError(loadImage(dir.write("found.tga", found)),
                       {"found.tga", "truncated TGA", "3855 x 3855 pixels of 2 bytes", "the file has 21"});

  // 2 x 1 pixels, 24-bit BGR, uncompressed: complete, then one byte short.
  const std::string header = "\0\0\x02\0\0\0\0\0\0\0\0\0\x02\0\x01\0\x18\0"s;
  const std::string complete = header + "\x01\x02\x03\x04\x05\x06"s;
  auto image = loadImage(dir.write("complete.tga", complete));
  ASSERT_TRUE(image.has_value()) << image.error().message;
  EXPECT_EQ(image->width, 2);
  EXPECT_EQ(image->rgba[0], 0x03);  // BGR stored, RGB read
  testing::expectError(loadImage(dir.write("short.tga", complete.substr(0, complete.size() - 1))),
                       {"short.tga", "2 x 1 pixels of 3 bytes", "at least 24 bytes", "the file has 23"});

  // 256 x 256 grey, run-length encoded (type 11): 512 packets of 128 at the least, 2 bytes each.
  const std::string rle = "\0\0\x0b\0\0\0\0\0\0\0\0\0\0\x01\0\x01\x08\0\xff\x80"s;
  testing::expectError(loadImage(dir.write("rle.tga", rle)),
                       {"rle.tga", "256 x 256 pixels of 1 byte run-length encoded", "at least 1042 bytes"});
}

// Found by tests/fuzz/fuzz_image: a PNG whose first IDAT chunk is empty made stb_image 2.27
// memcpy zero bytes into its not yet allocated buffer, a null pointer (undefined behaviour).
// Empty IDAT chunks carry nothing and are dropped first: the image reads as without them, and a
// PNG with no data at all is still refused.
TEST(FuzzFindings, PngEmptyDataChunksAreDroppedAndOverlongChunksRefused) {
  ScratchDir dir;
  // 1 x 1 pixel, 8-bit grey 0x80; chunks with their CRCs, as an encoder would write them.
  const std::string signature = "\x89PNG\r\n\x1a\n"s;
  const std::string header =
      "\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x01\x00\x00\x00\x01\x08\x00\x00\x00\x00\x3a\x7e\x9b\x55"s;
  const std::string emptyData = "\x00\x00\x00\x00\x49\x44\x41\x54\x35\xaf\x06\x1e"s;
  const std::string data = "\x00\x00\x00\x0a\x49\x44\x41\x54\x78\x9c\x63\x68\x00\x00\x00\x82\x00\x81\x77\xcd\x72\xb6"s;
  const std::string end = "\x00\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82"s;
  auto image = loadImage(dir.write("empty_first.png", signature + header + emptyData + data + emptyData + end));
  ASSERT_TRUE(image.has_value()) << image.error().message;
  EXPECT_EQ(image->width, 1);
  EXPECT_EQ(image->height, 1);
  EXPECT_EQ(image->rgba[0], 0x80);
  testing::expectError(loadImage(dir.write("no_data.png", signature + header + emptyData + end)),
                       {"no_data.png", "cannot decode image"});
  // The second finding: the empty chunk last, its CRC cut off (stb_image reads it all the same).
  testing::expectError(loadImage(dir.write("cut.png", signature + header + emptyData.substr(0, 9))),
                       {"cut.png", "cannot decode image"});
  // The third (out of memory): a chunk declaring 1 GiB, for which stb_image 2.27 allocated 2 GiB
  // before finding the file ends. Refused, naming the chunk; chunks after IEND are not read.
  const std::string huge = "\x40\x00\x00\x00IDAT\x78\x9c"s;
  testing::expectError(
      loadImage(dir.write("huge.png", signature + header + data + huge + end)),
      {"huge.png", "truncated PNG", "\"IDAT\" chunk at byte 55", "declares 1073741824 bytes", "only 14 follow"});
  image = loadImage(dir.write("trailing.png", signature + header + data + end + huge));
  ASSERT_TRUE(image.has_value()) << image.error().message;
  EXPECT_EQ(image->rgba[0], 0x80);
}

// --- OBJ ----------------------------------------------------------------------------------

// Found by tests/fuzz/fuzz_obj: a `vw` line (tinyobjloader's skin-weight extension) with a joint
// id past int's range made tinyobjloader convert that float to int, undefined behaviour. No skin
// weights are read from OBJ, so those lines are skipped before parsing, however they are
// indented and whatever ends the line before them.
TEST(FuzzFindings, ObjSkinWeightLinesAreIgnored) {
  ScratchDir dir;
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "vw 1 2147483648 0.5\n"
      " \tvw 2 1e30 1\r"
      "vw 3 -1 1\r\n"
      "f 1 2 3\n";
  auto mesh = loadObj(dir.write("weights.obj", text));
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  EXPECT_EQ(mesh->positions.size(), 3u);
  EXPECT_EQ(mesh->indices.size(), 3u);
}

// Found by tests/fuzz/fuzz_obj: tinyobjloader sums a number's exponent digits in an int, and
// "2147483648" overflows it (undefined behaviour). Such a file is refused, naming the line;
// leading zeros do not count, so a long but small exponent still reads.
TEST(FuzzFindings, ObjNumberWithATenDigitExponentIsRefusedNamingTheLine) {
  ScratchDir dir;
  const auto refused = loadObj(dir.write("exponent.obj", "v 0 0 0\r\nv 1 0 0\rv 0 1e+2147483648 0\nf 1 2 3\n"));
  testing::expectError(refused, {"exponent.obj", "line 3", "exponent", "ten digits"});
  auto mesh = loadObj(dir.write("zeros.obj", "v 0 0 0\nv 1e-00000000000 0 0\nv 0 1E+0000000000001 0\nf 1 2 3\n"));
  ASSERT_TRUE(mesh.has_value()) << mesh.error().message;
  EXPECT_EQ(mesh->positions[2].y, 10.0f);
}

// --- Saved simulation states ------------------------------------------------------------

// Found by tests/fuzz/fuzz_sim_state: a cloth of 0 particles (so also a fur of 0 vertices) read
// its empty position arrays with memcpy from an empty vector's data(), a null pointer memcpy may
// not be given even for 0 bytes (UBSan reports it; an optimiser may assume it never happens).
// Such records are well-formed and read back as written.
TEST(FuzzFindings, SimulatedStateWithEmptyRecordsReadsBack) {
  SimulatedState state{.step = 3, .time = 0.125, .stateHash = 1};
  state.cloths.push_back({.name = "empty", .positions = {}, .previousPositions = {}});
  state.furs.push_back({.fur = 0, .leans = {}});
  const std::vector<unsigned char> bytes = encodeSimulatedState(state);
  auto decoded = decodeSimulatedState(bytes, "empty.msim");
  ASSERT_TRUE(decoded.has_value()) << decoded.error().message;
  ASSERT_EQ(decoded->cloths.size(), 1u);
  EXPECT_EQ(decoded->cloths[0].name, "empty");
  EXPECT_TRUE(decoded->cloths[0].positions.empty());
  ASSERT_EQ(decoded->furs.size(), 1u);
  EXPECT_TRUE(decoded->furs[0].leans.empty());
  EXPECT_EQ(encodeSimulatedState(*decoded), bytes);
}

}  // namespace
}  // namespace mane::scenes
