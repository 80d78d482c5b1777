// libFuzzer harness: bytes → a scratch manifest → AssetResolver::create, then a lookup of
// every entry. No search roots, no cache, no downloads: lookups touch neither the disk nor
// the network, so only the manifest parsing and validation are under test.

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "scenes/assets.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mane::fuzz::InputFile manifest("assets.json");
  mane::scenes::AssetResolverSettings settings;
  settings.manifest = manifest.write(data, size);
  settings.allowDownload = false;
  auto resolver = mane::scenes::AssetResolver::create(settings);
  if (!resolver) return 0;
  for (const auto& entry : resolver->entries()) {
    if (resolver->find(entry.name) != &entry) std::abort();
    auto found = resolver->lookup(entry.name);
    if (!found || found->path) std::abort();  // nowhere to look: always "missing"
  }
  (void)resolver->lookup("not/in/the/manifest");
  return 0;
}
