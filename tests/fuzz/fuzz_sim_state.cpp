// libFuzzer harness: bytes → decodeSimulatedState (a `.msim` saved state or cache frame, from
// memory) and the same bytes → readCacheManifest (a simulation cache's `cache.json`). Each must
// return its result or an error, never crash, hang or leak. A state the decoder accepts must
// encode back to the very same bytes (the format has one encoding per state), and a manifest it
// accepts must hold one state hash per frame at a positive frame rate.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "scenes/sim_cache.hpp"
#include "scenes/sim_state.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const unsigned char> bytes(data, size);
  auto state = mane::scenes::decodeSimulatedState(bytes, "fuzz.msim");
  if (state) {
    const std::vector<unsigned char> again = mane::scenes::encodeSimulatedState(*state);
    if (!std::equal(again.begin(), again.end(), bytes.begin(), bytes.end())) std::abort();
  } else if (state.error().message.find("fuzz.msim") == std::string::npos) {
    std::abort();
  }

  static const mane::fuzz::InputFile manifestFile("cache.json");
  const std::filesystem::path folder = manifestFile.write(data, size).parent_path();
  auto manifest = mane::scenes::readCacheManifest(folder);
  if (manifest && (!(manifest->fps > 0.0) || manifest->stateHashes.size() != manifest->frames)) std::abort();
  return 0;
}
