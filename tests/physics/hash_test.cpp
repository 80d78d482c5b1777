// The state hash is 64-bit FNV-1a; its published test vectors are the oracle
// (http://www.isthe.com/chongo/src/fnv/test_fnv.c: "" → cbf29ce484222325,
// "a" → af63dc4c8601ec8c, "foobar" → 85944171f73967e8).

#include <cmath>
#include <string_view>

#include <gtest/gtest.h>

#include "physics/hash.hpp"

namespace mane::physics {
namespace {

std::uint64_t hashText(std::string_view text) {
  return fnv1a(std::as_bytes(std::span<const char>(text.data(), text.size())));
}

TEST(StateHash, Fnv1aMatchesPublishedVectors) {
  EXPECT_EQ(hashText(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(hashText("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(hashText("foobar"), 0x85944171f73967e8ull);
}

TEST(StateHash, CoversPositionsAndPreviousPositionsBitForBit) {
  Particles particles;
  particles.add({1.0f, 2.0f, 3.0f}, 1.0f);
  particles.add({4.0f, 5.0f, 6.0f}, 0.0f);
  const std::uint64_t base = stateHash(particles);
  EXPECT_EQ(stateHash(particles), base);

  Particles moved = particles;
  moved.positions[1].z = std::nextafter(6.0f, 7.0f);  // one ulp
  EXPECT_NE(stateHash(moved), base);

  Particles previous = particles;
  previous.previousPositions[0].x = std::nextafter(1.0f, 0.0f);
  EXPECT_NE(stateHash(previous), base);
}

}  // namespace
}  // namespace mane::physics
