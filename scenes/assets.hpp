#pragma once
// The asset manifest (scenes/assets.json) and the resolver that turns an asset name into a
// verified file on disk: $MANE_ASSETS, ../shared/assets, the user cache, then a download.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/error.hpp"

namespace mane::scenes {

/// One file of third-party data, as listed in the manifest.
struct AssetEntry {
  /// Path relative to an assets root, with '/' separators, e.g.
  /// "head/LeePerrySmith/LeePerrySmith.glb". Never absolute, never contains "..".
  std::string name;
  /// Raw-download URL of the identical bytes; empty for DERIVED files, which have no
  /// upstream copy and must be found locally.
  std::string upstream;
  /// Where the file comes from, for people (repository, commit, path; or how it was derived).
  std::string origin;
  /// Lower-case hex SHA-256 of the file's bytes.
  std::string sha256;
  /// Licence name, e.g. "CC BY 3.0".
  std::string licence;
  /// Other assets the file needs beside it (a .gltf's .bin buffers and textures); a download
  /// fetches them too, into the same cache.
  std::vector<std::string> companions;
};

/// Where a resolver looks, and whether it may download. Build with
/// `defaultAssetResolverSettings()` and adjust, or fill in completely (tests do).
struct AssetResolverSettings {
  /// The manifest file (JSON, see scenes/README.md).
  std::filesystem::path manifest;
  /// Directories searched in order; each holds files at `root / name`.
  std::vector<std::filesystem::path> searchRoots;
  /// The download cache, searched after `searchRoots`; empty: no cache and no download.
  std::filesystem::path cacheDirectory;
  /// When false, a file found nowhere is reported missing without touching the network.
  bool allowDownload = true;
  /// Check each local file's SHA-256 against the manifest on every resolve (reads every byte).
  bool verifyLocalFiles = true;
  /// Seconds allowed to connect to the upstream host; keeps an offline run from hanging.
  long connectTimeoutSeconds = 5;
  /// Seconds allowed for a whole download.
  long totalTimeoutSeconds = 120;
};

/// The settings the program and the tests use:
/// - manifest: `<source dir>/scenes/assets.json`;
/// - roots: `$MANE_ASSETS` (when set and non-empty), `<source dir>/../shared/assets`,
///   `./../shared/assets` (relative to the current directory);
/// - cache: `$XDG_CACHE_HOME/mane/assets`, else `$HOME/.cache/mane/assets`;
/// - downloads allowed unless `$MANE_OFFLINE` is set to anything but "0".
[[nodiscard]] AssetResolverSettings defaultAssetResolverSettings();

/// The result of a lookup that may legitimately find nothing (offline, asset not shipped).
struct AssetLookup {
  std::optional<std::filesystem::path> path;  ///< the verified file, when found
  std::string missingReason;                  ///< where it looked and why it failed, else
};

/// Resolves manifest names to verified files. Cheap to copy; thread-compatible (concurrent
/// resolves of the same missing name may download it twice, harmlessly).
class AssetResolver {
public:
  /// Reads and validates the manifest. Errors name the manifest and the bad entry.
  [[nodiscard]] static Result<AssetResolver> create(AssetResolverSettings settings);
  /// `create(defaultAssetResolverSettings())`.
  [[nodiscard]] static Result<AssetResolver> createDefault();

  /// The manifest entry of `name`, or nullptr.
  [[nodiscard]] const AssetEntry* find(std::string_view name) const;
  [[nodiscard]] const std::vector<AssetEntry>& entries() const { return entries_; }
  [[nodiscard]] const AssetResolverSettings& settings() const { return settings_; }

  /// Finds `name`: first root holding the file, then the cache, then a download into the
  /// cache (with its companions). A found or downloaded file whose SHA-256 differs from the
  /// manifest is an error naming the file, the expected and the actual hash; a name the
  /// manifest does not list is an error. A file found nowhere is not an error here:
  /// `path` is empty and `missingReason` says where it looked.
  [[nodiscard]] Result<AssetLookup> lookup(std::string_view name) const;

  /// For names written in scene files: a name the manifest lists is looked up as by `lookup`;
  /// any other name is the user's own file, absolute or relative to `sceneDirectory`, used as
  /// it is (no checksum). A user file that does not exist is an error naming both readings.
  [[nodiscard]] Result<AssetLookup> lookupForScene(std::string_view name,
                                                   const std::filesystem::path& sceneDirectory) const;

  /// `lookup`, with a missing file turned into an error too.
  [[nodiscard]] Result<std::filesystem::path> resolve(std::string_view name) const;

private:
  AssetResolver() = default;
  Result<void> verify(const AssetEntry& entry, const std::filesystem::path& file) const;
  Result<AssetLookup> download(const AssetEntry& entry) const;

  AssetResolverSettings settings_;
  std::vector<AssetEntry> entries_;
};

}  // namespace mane::scenes
