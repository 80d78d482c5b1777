#pragma once
// Helpers shared by the scene tests: a scratch directory and the default asset resolver.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "scenes/assets.hpp"

namespace mane::scenes::testing {

/// A fresh directory under the system temp folder, removed when the object dies.
class ScratchDir {
 public:
  ScratchDir() {
    std::random_device seed;
    path_ = std::filesystem::temp_directory_path() /
            ("mane-scene-test-" + std::to_string(seed()) + std::to_string(seed()));
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
inline AssetResolver sharedResolver() {
  AssetResolverSettings settings = defaultAssetResolverSettings();
  settings.allowDownload = false;
  auto resolver = AssetResolver::create(settings);
  if (!resolver) throw std::runtime_error(resolver.error().message);
  return *resolver;
}

/// Resolves a shared asset, or skips the test when the assets are not on this machine.
#define MANE_RESOLVE_OR_SKIP(var, name)                                      \
  std::filesystem::path var;                                                 \
  {                                                                          \
    auto found_ = ::mane::scenes::testing::sharedResolver().lookup(name);    \
    ASSERT_TRUE(found_.has_value()) << found_.error().message;               \
    if (!found_->path) GTEST_SKIP() << found_->missingReason;                \
    var = *found_->path;                                                     \
  }

}  // namespace mane::scenes::testing
