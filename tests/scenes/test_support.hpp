#pragma once
// Helpers shared by the scene tests: a scratch directory and the default asset resolver.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scenes/assets.hpp"

namespace mane::scenes::testing {

/// A fresh directory under the system temp folder, removed when the object dies.
class ScratchDir {
public:
  ScratchDir() {
    std::random_device seed;
    path_ =
        std::filesystem::temp_directory_path() / ("mane-scene-test-" + std::to_string(seed()) + std::to_string(seed()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  /// Writes `content` to `relative` (creating folders) and returns the full path.
  std::filesystem::path write(const std::string& relative, const std::string& content) const {
    const std::filesystem::path file = path_ / relative;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << content;
    return file;
  }

private:
  std::filesystem::path path_;
};

inline std::string readFile(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

/// The project's resolver without downloads: tests never touch the network.
/// A scene of one small sphere, "body", wearing one cloth named "cloth" whose fields after its
/// name and body are `clothFields` (JSON members, comma-separated).
inline std::string sceneWithCloth(const std::string& clothFields) {
  return R"({"name": "c", "camera": {"position": [0, 0, 1], "target": [0, 0, 0]},
    "meshes": [{"name": "body", "source": "procedural:sphere", "transform": {"scale": 0.1}}],
    "cloths": [{"name": "cloth", "attached_mesh": "body", )" +
         clothFields + "}]}";
}

inline AssetResolver sharedResolver() {
  AssetResolverSettings settings = defaultAssetResolverSettings();
  settings.allowDownload = false;
  auto resolver = AssetResolver::create(settings);
  if (!resolver) throw std::runtime_error(resolver.error().message);
  return *resolver;
}

/// A resolver that finds nothing and never downloads: a machine without ../shared/assets.
inline AssetResolver resolverWithoutAssets() {
  AssetResolverSettings settings = defaultAssetResolverSettings();
  settings.searchRoots.clear();
  settings.cacheDirectory.clear();
  settings.allowDownload = false;
  auto resolver = AssetResolver::create(settings);
  if (!resolver) throw std::runtime_error(resolver.error().message);
  return *resolver;
}

/// Whether a missing shared asset must fail the test rather than skip it: set
/// MANE_REQUIRE_ASSETS=1 (scripts/test.sh does under CI) so that a run without
/// ../shared/assets cannot pass with the real-data tests silently skipped.
inline bool assetsRequired() {
  const char* value = std::getenv("MANE_REQUIRE_ASSETS");
  return value && std::string_view(value) != "0";
}

/// Skips the test with `reason`, or fails it when assets are required.
#define MANE_SKIP_FOR_MISSING_ASSET(reason)                            \
  do {                                                                 \
    if (::mane::scenes::testing::assetsRequired()) FAIL() << (reason); \
    GTEST_SKIP() << (reason);                                          \
  } while (false)

/// Resolves a shared asset, or skips the test when the assets are not installed.
#define MANE_RESOLVE_OR_SKIP(var, name)                                    \
  std::filesystem::path var;                                               \
  {                                                                        \
    auto found_ = ::mane::scenes::testing::sharedResolver().lookup(name);  \
    ASSERT_TRUE(found_.has_value()) << found_.error().message;             \
    if (!found_->path) MANE_SKIP_FOR_MISSING_ASSET(found_->missingReason); \
    var = *found_->path;                                                   \
  }

}  // namespace mane::scenes::testing
