#include "scenes/assets.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "scenes/detail/download.hpp"
#include "scenes/detail/sha256.hpp"

#ifndef MANE_SOURCE_DIR
#error "MANE_SOURCE_DIR must name the source tree (set by scenes/CMakeLists.txt)"
#endif

namespace mane::scenes {
namespace {

std::string environment(const char* variable) {
  const char* value = std::getenv(variable);
  return value ? std::string(value) : std::string();
}

bool isHexSha256(const std::string& text) {
  return text.size() == 64 &&
         std::all_of(text.begin(), text.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

/// Names are relative paths that stay inside a root: no absolute paths, no "..".
bool isSafeName(const std::string& name) {
  if (name.empty() || name.front() == '/' || name.find('\\') != std::string::npos) return false;
  for (const auto& part : std::filesystem::path(name)) {
    if (part == ".." || part == ".") return false;
  }
  return true;
}

Result<std::vector<AssetEntry>> readManifest(const std::filesystem::path& manifest) {
  const std::string file = manifest.string();
  std::ifstream stream(manifest);
  if (!stream) return fail(file + ": cannot open the asset manifest");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(stream);
  } catch (const nlohmann::json::exception& e) {
    return fail(file + ": the asset manifest is not valid JSON: " + e.what());
  }
  if (!json.is_object() || !json.contains("assets") || !json["assets"].is_array()) {
    return fail(file + ": the asset manifest must be an object with an \"assets\" array");
  }
  std::vector<AssetEntry> entries;
  std::set<std::string> seen;
  const auto& assets = json["assets"];
  for (std::size_t i = 0; i < assets.size(); ++i) {
    const std::string where = file + ": assets[" + std::to_string(i) + "]";
    const auto& item = assets[i];
    auto text = [&](const char* key, bool required) -> Result<std::string> {
      if (!item.is_object()) return fail(where + ": expected an object");
      if (!item.contains(key) || item[key].is_null()) {
        if (required) return fail(where + "." + key + ": required field is missing");
        return std::string();
      }
      if (!item[key].is_string()) return fail(where + "." + key + ": expected a string");
      return item[key].get<std::string>();
    };
    AssetEntry entry;
    auto name = text("name", true);
    auto upstream = text("upstream", false);
    auto origin = text("origin", false);
    auto sha = text("sha256", true);
    auto licence = text("licence", true);
    for (const auto* field : {&name, &upstream, &origin, &sha, &licence}) {
      if (!*field) return std::unexpected(field->error());
    }
    entry.name = *name;
    entry.upstream = *upstream;
    entry.origin = *origin;
    entry.sha256 = *sha;
    entry.licence = *licence;
    if (!isSafeName(entry.name)) {
      return fail(where + ".name: '" + entry.name + "' must be a relative path without '.' or '..' parts");
    }
    if (!isHexSha256(entry.sha256)) {
      return fail(where + ".sha256: expected 64 lower-case hex digits for '" + entry.name + "'");
    }
    if (item.contains("companions")) {
      if (!item["companions"].is_array()) return fail(where + ".companions: expected an array");
      for (const auto& companion : item["companions"]) {
        if (!companion.is_string()) return fail(where + ".companions: expected strings");
        entry.companions.push_back(companion.get<std::string>());
      }
    }
    if (!seen.insert(entry.name).second) {
      return fail(where + ".name: '" + entry.name + "' is listed twice");
    }
    entries.push_back(std::move(entry));
  }
  for (const AssetEntry& entry : entries) {
    for (const std::string& companion : entry.companions) {
      if (!seen.contains(companion)) {
        return fail(file + ": companion '" + companion + "' of '" + entry.name + "' is not in the manifest");
      }
    }
  }
  return entries;
}

}  // namespace

AssetResolverSettings defaultAssetResolverSettings() {
  AssetResolverSettings settings;
  const std::filesystem::path source(MANE_SOURCE_DIR);
  settings.manifest = source / "scenes" / "assets.json";
  if (const std::string assets = environment("MANE_ASSETS"); !assets.empty()) {
    settings.searchRoots.emplace_back(assets);
  }
  settings.searchRoots.push_back((source / ".." / "shared" / "assets").lexically_normal());
  std::error_code ec;
  const std::filesystem::path here = std::filesystem::current_path(ec);
  if (!ec) settings.searchRoots.push_back((here / ".." / "shared" / "assets").lexically_normal());

  if (const std::string xdg = environment("XDG_CACHE_HOME"); !xdg.empty()) {
    settings.cacheDirectory = std::filesystem::path(xdg) / "mane" / "assets";
  } else if (const std::string home = environment("HOME"); !home.empty()) {
    settings.cacheDirectory = std::filesystem::path(home) / ".cache" / "mane" / "assets";
  }
  const std::string offline = environment("MANE_OFFLINE");
  settings.allowDownload = offline.empty() || offline == "0";
  return settings;
}

Result<AssetResolver> AssetResolver::create(AssetResolverSettings settings) {
  auto entries = readManifest(settings.manifest);
  if (!entries) return std::unexpected(entries.error());
  AssetResolver resolver;
  resolver.settings_ = std::move(settings);
  resolver.entries_ = std::move(*entries);
  return resolver;
}

Result<AssetResolver> AssetResolver::createDefault() {
  return create(defaultAssetResolverSettings());
}

const AssetEntry* AssetResolver::find(std::string_view name) const {
  const auto it =
      std::find_if(entries_.begin(), entries_.end(), [&](const AssetEntry& entry) { return entry.name == name; });
  return it == entries_.end() ? nullptr : &*it;
}

Result<void> AssetResolver::verify(const AssetEntry& entry, const std::filesystem::path& file) const {
  auto actual = detail::sha256OfFile(file);
  if (!actual) return std::unexpected(actual.error());
  if (*actual != entry.sha256) {
    return fail(file.string() + ": sha256 mismatch for asset '" + entry.name + "': expected " + entry.sha256 +
                ", actual " + *actual + " (a damaged or different file; delete it or fix the manifest)");
  }
  return {};
}

Result<AssetLookup> AssetResolver::lookupForScene(std::string_view name,
                                                  const std::filesystem::path& sceneDirectory) const {
  if (find(name)) return lookup(name);
  const std::filesystem::path file = sceneDirectory / std::filesystem::path(name);
  std::error_code ec;
  if (std::filesystem::is_regular_file(file, ec)) return AssetLookup{file, {}};
  std::string message = "'";  // built in steps: g++ 12 gives a false -Wrestrict on one long "+" chain
  message.append(name);
  message += "' is neither an asset of " + settings_.manifest.string() + " nor a file (";
  message += std::filesystem::absolute(file, ec).lexically_normal().string() + " does not exist)";
  return fail(std::move(message));
}

Result<AssetLookup> AssetResolver::lookup(std::string_view name) const {
  const AssetEntry* entry = find(name);
  if (!entry) {
    return fail("asset '" + std::string(name) + "' is not in the manifest " + settings_.manifest.string());
  }
  std::vector<std::filesystem::path> places = settings_.searchRoots;
  if (!settings_.cacheDirectory.empty()) places.push_back(settings_.cacheDirectory);
  std::string looked;
  for (const auto& root : places) {
    const std::filesystem::path candidate = root / entry->name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec)) {
      if (settings_.verifyLocalFiles) {
        if (auto ok = verify(*entry, candidate); !ok) return std::unexpected(ok.error());
      }
      return AssetLookup{candidate, {}};
    }
    looked += (looked.empty() ? "" : ", ") + candidate.string();
  }
  std::string reason = "asset '" + entry->name + "' not found (looked in " +
                       (looked.empty() ? std::string("no directories") : looked) + ")";
  if (entry->upstream.empty()) {
    return AssetLookup{std::nullopt, reason + "; it is derived data with no upstream copy to download"};
  }
  if (!settings_.allowDownload || settings_.cacheDirectory.empty()) {
    return AssetLookup{std::nullopt, reason + "; downloading is disabled"};
  }
  auto downloaded = download(*entry);
  if (!downloaded) return std::unexpected(downloaded.error());
  if (!downloaded->path) downloaded->missingReason = reason + "; " + downloaded->missingReason;
  return downloaded;
}

Result<AssetLookup> AssetResolver::download(const AssetEntry& entry) const {
  const std::filesystem::path target = settings_.cacheDirectory / entry.name;
  std::error_code ec;
  std::filesystem::create_directories(target.parent_path(), ec);
  if (ec) {
    return AssetLookup{std::nullopt,
                       "cannot create the cache directory " + target.parent_path().string() + ": " + ec.message()};
  }
  // Download beside the target and rename, so a partial file never looks complete.
  const std::filesystem::path partial = target.string() + ".part-" + std::to_string(static_cast<long>(::getpid()));
  const detail::DownloadLimits limits{settings_.connectTimeoutSeconds, 10, settings_.totalTimeoutSeconds};
  if (auto ok = detail::downloadFile(entry.upstream, partial, limits); !ok) {
    return AssetLookup{std::nullopt, ok.error().message};
  }
  auto actual = detail::sha256OfFile(partial);
  if (!actual) {
    std::filesystem::remove(partial, ec);
    return std::unexpected(actual.error());
  }
  if (*actual != entry.sha256) {
    std::filesystem::remove(partial, ec);
    return fail(entry.upstream + ": sha256 mismatch for downloaded asset '" + entry.name + "': expected " +
                entry.sha256 + ", actual " + *actual +
                " (upstream changed or the manifest is wrong); nothing was cached");
  }
  std::filesystem::rename(partial, target, ec);
  if (ec) {
    std::filesystem::remove(partial, ec);
    return AssetLookup{std::nullopt, "cannot move the download into " + target.string()};
  }
  // Companions must sit beside the file in the cache (a .gltf names its .bin relatively),
  // whatever the search roots hold.
  for (const std::string& name : entry.companions) {
    const AssetEntry& companion = *find(name);  // readManifest checked it is listed
    const std::filesystem::path cached = settings_.cacheDirectory / companion.name;
    if (std::filesystem::is_regular_file(cached, ec) && verify(companion, cached)) continue;
    auto found = companion.upstream.empty() ? Result<AssetLookup>(AssetLookup{std::nullopt, "it has no upstream copy"})
                                            : download(companion);
    if (!found) return std::unexpected(found.error());
    if (!found->path) {
      return AssetLookup{std::nullopt, "companion of '" + entry.name + "' missing: " + found->missingReason};
    }
  }
  return AssetLookup{target, {}};
}

Result<std::filesystem::path> AssetResolver::resolve(std::string_view name) const {
  auto found = lookup(name);
  if (!found) return std::unexpected(found.error());
  if (!found->path) return fail(found->missingReason);
  return *found->path;
}

}  // namespace mane::scenes
