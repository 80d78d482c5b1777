// The simulation state file (`.msim`, docs/sim-state-format.md), the HAIR writer and the
// simulation cache's manifest: what is written reads back bit for bit, and broken files are
// refused with a message that says where.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "scenes/groom_loader.hpp"
#include "scenes/groom_writer.hpp"
#include "scenes/sim_cache.hpp"
#include "scenes/sim_state.hpp"

namespace mane::scenes {
namespace {

class Scratch {
public:
  Scratch() {
    std::random_device seed;
    path_ = std::filesystem::temp_directory_path() / ("mane-sim-state-test-" + std::to_string(seed()));
    std::filesystem::create_directories(path_);
  }
  ~Scratch() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

private:
  std::filesystem::path path_;
};

SimulatedState sampleState() {
  SimulatedState state{.step = 42, .time = 0.35, .stateHash = 0x0123456789abcdefull};
  state.grooms.push_back(
      {.name = "scalp",
       .pointsPerStrand = {2, 3},
       .positions = {{0, 0, 0}, {0, -0.01f, 0}, {1, 0, 0}, {1, -0.01f, 0}, {1, -0.02f, 0.001f}},
       .previousPositions = {{0, 0, 0}, {0, -0.011f, 0}, {1, 0, 0}, {1, -0.011f, 0}, {1, -0.02f, 0}}});
  state.cloths.push_back(
      {.name = "cape", .positions = {{0.5f, 1, 2}, {3, 4, 5}}, .previousPositions = {{0.5f, 1, 2}, {3, 4, 4.9f}}});
  state.furs.push_back({.fur = 1, .leans = {{0.1f, 0, 0}, {0, 0.2f, 0}, {0, 0, -0.3f}}});
  return state;
}

bool sameBits(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0;
}

TEST(SimulatedStateFile, ReadsBackEveryFieldBitForBit) {
  const SimulatedState written = sampleState();
  auto read = decodeSimulatedState(encodeSimulatedState(written), "state.msim");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->step, 42u);
  EXPECT_EQ(read->time, 0.35);
  EXPECT_EQ(read->stateHash, written.stateHash);
  ASSERT_EQ(read->grooms.size(), 1u);
  EXPECT_EQ(read->grooms[0].name, "scalp");
  EXPECT_EQ(read->grooms[0].pointsPerStrand, written.grooms[0].pointsPerStrand);
  EXPECT_TRUE(sameBits(read->grooms[0].positions, written.grooms[0].positions));
  EXPECT_TRUE(sameBits(read->grooms[0].previousPositions, written.grooms[0].previousPositions));
  ASSERT_EQ(read->cloths.size(), 1u);
  EXPECT_EQ(read->cloths[0].name, "cape");
  EXPECT_TRUE(sameBits(read->cloths[0].positions, written.cloths[0].positions));
  EXPECT_TRUE(sameBits(read->cloths[0].previousPositions, written.cloths[0].previousPositions));
  ASSERT_EQ(read->furs.size(), 1u);
  EXPECT_EQ(read->furs[0].fur, 1u);
  EXPECT_TRUE(sameBits(read->furs[0].leans, written.furs[0].leans));
}

TEST(SimulatedStateFile, HeaderIsTheDocumentedLayout) {
  // docs/sim-state-format.md: signature, version 1, counts, then step, time, hash (little-endian).
  const auto bytes = encodeSimulatedState(sampleState());
  ASSERT_GE(bytes.size(), 48u);
  EXPECT_EQ(std::memcmp(bytes.data(), "MANESIM\0", 8), 0);
  auto u32 = [&](std::size_t at) {
    return std::uint32_t(bytes[at] | bytes[at + 1] << 8 | bytes[at + 2] << 16 | bytes[at + 3] << 24);
  };
  EXPECT_EQ(u32(8), 1u);
  EXPECT_EQ(u32(12), 1u);  // grooms
  EXPECT_EQ(u32(16), 1u);  // cloths
  EXPECT_EQ(u32(20), 1u);  // furs
  EXPECT_EQ(u32(24), 42u);
  double time = 0.0;
  std::memcpy(&time, bytes.data() + 32, 8);
  EXPECT_EQ(time, 0.35);
}

TEST(SimulatedStateFile, RefusesBrokenFilesSayingWhere) {
  auto bytes = encodeSimulatedState(sampleState());
  auto truncated = decodeSimulatedState(std::span(bytes).first(bytes.size() - 4), "t.msim");
  ASSERT_FALSE(truncated);
  EXPECT_NE(truncated.error().message.find("t.msim: a fur's leans needs 36 bytes at byte"), std::string::npos)
      << truncated.error().message;

  auto longer = bytes;
  longer.push_back(0);
  auto leftover = decodeSimulatedState(longer, "l.msim");
  ASSERT_FALSE(leftover);
  EXPECT_NE(leftover.error().message.find("1 bytes left over"), std::string::npos) << leftover.error().message;

  auto wrongVersion = bytes;
  wrongVersion[8] = 7;
  auto version = decodeSimulatedState(wrongVersion, "v.msim");
  ASSERT_FALSE(version);
  EXPECT_NE(version.error().message.find("version 7 at byte 8"), std::string::npos) << version.error().message;

  auto notOurs = bytes;
  notOurs[0] = 'X';
  EXPECT_FALSE(decodeSimulatedState(notOurs, "x.msim"));

  SimulatedState shortStrand = sampleState();
  shortStrand.grooms[0].pointsPerStrand = {1, 4};
  auto strand = decodeSimulatedState(encodeSimulatedState(shortStrand), "s.msim");
  ASSERT_FALSE(strand);
  EXPECT_NE(strand.error().message.find("strand 0 has 1 points"), std::string::npos) << strand.error().message;
}

TEST(HairWriter, TheHairReaderReadsBackWhatWasWritten) {
  Scratch scratch;
  const SimulatedState state = sampleState();
  const GroomState& groom = state.grooms[0];
  const auto file = scratch.path() / "groom.hair";
  ASSERT_TRUE(writeCyHair(file, groom.pointsPerStrand, groom.positions, "test groom"));
  EXPECT_EQ(std::filesystem::file_size(file), 128u + 2 * 2 + 12 * 5);
  auto read = loadCyHair(file);
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->strands.size(), 2u);
  EXPECT_EQ(read->strands[0], (std::vector<glm::vec3>(groom.positions.begin(), groom.positions.begin() + 2)));
  EXPECT_EQ(read->strands[1], (std::vector<glm::vec3>(groom.positions.begin() + 2, groom.positions.end())));
}

TEST(HairWriter, RefusesWhatTheFormatCannotHold) {
  const std::vector<glm::vec3> points(3, glm::vec3(0.0f));
  EXPECT_FALSE(encodeCyHair(std::vector<std::uint32_t>{}, {}));
  EXPECT_FALSE(encodeCyHair(std::vector<std::uint32_t>{1, 2}, points));  // a hair needs a segment
  EXPECT_FALSE(encodeCyHair(std::vector<std::uint32_t>{2, 2}, points));  // 4 points announced, 3 given
  EXPECT_FALSE(encodeCyHair(std::vector<std::uint32_t>{70000}, std::vector<glm::vec3>(70000)));  // > uint16 segments
}

TEST(SimCacheManifest, ReadsBackAndRefusesAFolderWithoutOne) {
  Scratch scratch;
  const SimCacheManifest written{
      .scene = "/scenes/cape.json", .fps = 24.0, .frames = 2, .stateHashes = {0xffffffffffffffffull, 1}};
  ASSERT_TRUE(writeCacheManifest(scratch.path(), written));
  auto read = readCacheManifest(scratch.path());
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->scene, written.scene);
  EXPECT_EQ(read->fps, 24.0);
  EXPECT_EQ(read->frames, 2u);
  EXPECT_EQ(read->stateHashes, written.stateHashes);
  EXPECT_EQ(cacheFramePath(scratch.path(), 7).filename(), "frame_000007.msim");

  auto missing = readCacheManifest(scratch.path() / "elsewhere");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("did not finish"), std::string::npos) << missing.error().message;
}

}  // namespace
}  // namespace mane::scenes
