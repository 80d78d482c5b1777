// The asset manifest and resolver: the shipped manifest against ../shared/assets/SHA256SUMS,
// the search order, the cache, downloads (file:// URLs, so no network), checksum failures.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scenes/scene_meshes.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

using testing::readFile;
using testing::ScratchDir;

// sha256("hello\n"), from `printf 'hello\n' | sha256sum`.
constexpr const char* kHelloSha = "5891b5b522d5df086d0ff0b110fbd9d21bb4fc7163af34d08286a2e846f6be03";
constexpr const char* kWrongSha = "0000000000000000000000000000000000000000000000000000000000000000";

/// A manifest with one entry per (name, upstream, sha) in `dir/manifest.json`.
std::filesystem::path writeManifest(const ScratchDir& dir,
                                    std::vector<std::tuple<std::string, std::string, std::string>> entries) {
  nlohmann::json assets = nlohmann::json::array();
  for (const auto& [name, upstream, sha] : entries) {
    assets.push_back({{"name", name},
                      {"upstream", upstream.empty() ? nlohmann::json() : nlohmann::json(upstream)},
                      {"sha256", sha},
                      {"licence", "CC0"}});
  }
  return dir.write("manifest.json", nlohmann::json{{"assets", assets}}.dump(2));
}

AssetResolver makeResolver(const std::filesystem::path& manifest, std::vector<std::filesystem::path> roots,
                           const std::filesystem::path& cache, bool download) {
  AssetResolverSettings settings;
  settings.manifest = manifest;
  settings.searchRoots = std::move(roots);
  settings.cacheDirectory = cache;
  settings.allowDownload = download;
  settings.connectTimeoutSeconds = 2;
  auto resolver = AssetResolver::create(settings);
  EXPECT_TRUE(resolver.has_value()) << resolver.error().message;
  return *resolver;
}

TEST(AssetManifest, ListsEveryFileOfTheSharedAssetsWithItsChecksum) {
  const AssetResolver resolver = testing::sharedResolver();
  MANE_RESOLVE_OR_SKIP(readme, "meshes/teapot.obj");
  const std::filesystem::path root = readme.parent_path().parent_path();
  std::istringstream sums(readFile(root / "SHA256SUMS"));
  std::size_t lines = 0;
  for (std::string sha, name; sums >> sha >> name;) {
    ++lines;
    name = name.substr(2);  // "./fur/x.png" → "fur/x.png"
    const AssetEntry* entry = resolver.find(name);
    ASSERT_NE(entry, nullptr) << name << " is missing from scenes/assets.json";
    EXPECT_EQ(entry->sha256, sha) << name;
    EXPECT_FALSE(entry->licence.empty()) << name;
    EXPECT_TRUE(entry->upstream.empty() || entry->upstream.starts_with("https://")) << name;
  }
  EXPECT_EQ(lines, resolver.entries().size());
}

TEST(AssetManifest, EverySharedFileVerifies) {
  // The resolver hashes each file it returns; 15 MB in all.
  const AssetResolver resolver = testing::sharedResolver();
  for (const AssetEntry& entry : resolver.entries()) {
    auto path = resolver.resolve(entry.name);
    EXPECT_TRUE(path.has_value()) << path.error().message;
  }
}

TEST(AssetManifest, MalformedManifestNamesTheEntry) {
  ScratchDir dir;
  const auto manifest =
      dir.write("manifest.json", R"({"assets": [{"name": "../escape.txt", "sha256": "x", "licence": "CC0"}]})");
  AssetResolverSettings settings;
  settings.manifest = manifest;
  auto resolver = AssetResolver::create(settings);
  ASSERT_FALSE(resolver.has_value());
  EXPECT_NE(resolver.error().message.find("manifest.json: assets[0].name"), std::string::npos)
      << resolver.error().message;
}

TEST(AssetResolver, EnvironmentRootBeatsTheSharedFolder) {
  MANE_RESOLVE_OR_SKIP(shared, "meshes/teapot.obj");
  ScratchDir mine;
  mine.write("meshes/teapot.obj", readFile(shared));
  ::setenv("MANE_ASSETS", mine.path().c_str(), 1);
  AssetResolverSettings settings = defaultAssetResolverSettings();
  ::unsetenv("MANE_ASSETS");
  settings.allowDownload = false;
  auto resolver = AssetResolver::create(settings);
  ASSERT_TRUE(resolver.has_value()) << resolver.error().message;
  auto path = resolver->resolve("meshes/teapot.obj");
  ASSERT_TRUE(path.has_value()) << path.error().message;
  EXPECT_EQ(*path, mine.path() / "meshes/teapot.obj");
  // Without the variable the shared copy is found again.
  EXPECT_EQ(*testing::sharedResolver().resolve("meshes/teapot.obj"), shared);
}

TEST(AssetResolver, DefaultCacheFollowsXdgCacheHome) {
  ::setenv("XDG_CACHE_HOME", "/tmp/mane-xdg-test", 1);
  const AssetResolverSettings settings = defaultAssetResolverSettings();
  ::unsetenv("XDG_CACHE_HOME");
  EXPECT_EQ(settings.cacheDirectory, std::filesystem::path("/tmp/mane-xdg-test/mane/assets"));
}

TEST(AssetResolver, FirstRootHoldingTheFileWins) {
  ScratchDir dir;
  const auto manifest = writeManifest(dir, {{"a/hello.txt", "", kHelloSha}});
  dir.write("second/a/hello.txt", "hello\n");
  const AssetResolver resolver = makeResolver(manifest, {dir.path() / "first", dir.path() / "second"}, {}, false);
  EXPECT_EQ(*resolver.resolve("a/hello.txt"), dir.path() / "second/a/hello.txt");
  dir.write("first/a/hello.txt", "hello\n");
  EXPECT_EQ(*resolver.resolve("a/hello.txt"), dir.path() / "first/a/hello.txt");
}

TEST(AssetResolver, UsesTheCacheAfterTheRoots) {
  ScratchDir dir;
  const auto manifest = writeManifest(dir, {{"a/hello.txt", "", kHelloSha}});
  dir.write("cache/a/hello.txt", "hello\n");
  const AssetResolver resolver = makeResolver(manifest, {dir.path() / "empty"}, dir.path() / "cache", false);
  EXPECT_EQ(*resolver.resolve("a/hello.txt"), dir.path() / "cache/a/hello.txt");
}

TEST(AssetResolver, LocalFileWithWrongChecksumIsRejectedWithBothHashes) {
  ScratchDir dir;
  const auto manifest = writeManifest(dir, {{"a/hello.txt", "", kWrongSha}});
  dir.write("root/a/hello.txt", "hello\n");
  const AssetResolver resolver = makeResolver(manifest, {dir.path() / "root"}, {}, false);
  auto path = resolver.resolve("a/hello.txt");
  ASSERT_FALSE(path.has_value());
  const std::string& message = path.error().message;
  EXPECT_NE(message.find((dir.path() / "root/a/hello.txt").string()), std::string::npos) << message;
  EXPECT_NE(message.find(std::string("expected ") + kWrongSha), std::string::npos) << message;
  EXPECT_NE(message.find(std::string("actual ") + kHelloSha), std::string::npos) << message;
}

TEST(AssetResolver, DownloadsIntoTheCacheAndVerifies) {
  ScratchDir dir;
  const auto upstream = dir.write("upstream/hello.txt", "hello\n");
  const auto manifest = writeManifest(dir, {{"a/hello.txt", "file://" + upstream.string(), kHelloSha}});
  const AssetResolver resolver = makeResolver(manifest, {dir.path() / "empty"}, dir.path() / "cache", true);
  auto path = resolver.resolve("a/hello.txt");
  ASSERT_TRUE(path.has_value()) << path.error().message;
  EXPECT_EQ(*path, dir.path() / "cache/a/hello.txt");
  EXPECT_EQ(readFile(*path), "hello\n");
}

TEST(AssetResolver, DownloadWithWrongChecksumIsRejectedAndNotCached) {
  ScratchDir dir;
  const auto upstream = dir.write("upstream/hello.txt", "hello\n");
  const auto manifest = writeManifest(dir, {{"a/hello.txt", "file://" + upstream.string(), kWrongSha}});
  const AssetResolver resolver = makeResolver(manifest, {}, dir.path() / "cache", true);
  auto path = resolver.resolve("a/hello.txt");
  ASSERT_FALSE(path.has_value());
  const std::string& message = path.error().message;
  EXPECT_NE(message.find("a/hello.txt"), std::string::npos) << message;
  EXPECT_NE(message.find(std::string("expected ") + kWrongSha), std::string::npos) << message;
  EXPECT_NE(message.find(std::string("actual ") + kHelloSha), std::string::npos) << message;
  EXPECT_TRUE(std::filesystem::is_empty(dir.path() / "cache/a"));
}

TEST(AssetResolver, UnreachableUpstreamFailsFastAsMissing) {
  ScratchDir dir;
  // Port 9 (discard) on the loopback: refused at once, like an offline machine's DNS error.
  const auto manifest = writeManifest(dir, {{"a/hello.txt", "http://127.0.0.1:9/hello.txt", kHelloSha}});
  const AssetResolver resolver = makeResolver(manifest, {}, dir.path() / "cache", true);
  const auto start = std::chrono::steady_clock::now();
  auto found = resolver.lookup("a/hello.txt");
  const auto seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(found.has_value()) << found.error().message;
  EXPECT_FALSE(found->path.has_value());
  EXPECT_NE(found->missingReason.find("cannot download http://127.0.0.1:9/hello.txt"), std::string::npos)
      << found->missingReason;
  EXPECT_LT(seconds, 5.0);
}

TEST(AssetResolver, MissingAssetIsAnErrorNotACrash) {
  ScratchDir dir;
  const auto manifest = writeManifest(dir, {{"a/hello.txt", "", kHelloSha}});
  const AssetResolver resolver = makeResolver(manifest, {dir.path() / "empty"}, {}, true);
  auto path = resolver.resolve("a/hello.txt");
  ASSERT_FALSE(path.has_value());
  EXPECT_NE(path.error().message.find("asset 'a/hello.txt' not found"), std::string::npos) << path.error().message;
  EXPECT_NE(path.error().message.find((dir.path() / "empty/a/hello.txt").string()), std::string::npos);
  auto unknown = resolver.resolve("b/nothing.txt");
  ASSERT_FALSE(unknown.has_value());
  EXPECT_NE(unknown.error().message.find("'b/nothing.txt' is not in the manifest"), std::string::npos)
      << unknown.error().message;
}

TEST(SceneMeshes, MissingAssetFallsBackToASphereWithANote) {
  ScratchDir dir;
  const auto manifest = writeManifest(dir, {{"head/head.glb", "", kHelloSha}});
  const AssetResolver resolver = makeResolver(manifest, {dir.path() / "empty"}, {}, false);
  MeshInstance instance{"head", "head/head.glb", "", {}};
  instance.transform.scale = 0.5f;
  auto loaded = loadSceneMesh(instance, resolver);
  ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
  EXPECT_TRUE(loaded->procedural);
  EXPECT_TRUE(loaded->note.starts_with("asset head/head.glb missing: using a procedural sphere")) << loaded->note;
  // Placed with the instance's scale, the stand-in has the documented world radius.
  EXPECT_NEAR(loaded->mesh.bounds().max.y * instance.transform.scale, kFallbackSphereRadius, 1e-6f);
}

TEST(SceneMeshes, ChecksumMismatchIsNotHiddenByTheFallback) {
  ScratchDir dir;
  const auto manifest = writeManifest(dir, {{"m/tri.obj", "", kWrongSha}});
  dir.write("root/m/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const AssetResolver resolver = makeResolver(manifest, {dir.path() / "root"}, {}, false);
  auto loaded = loadSceneMesh(MeshInstance{"tri", "m/tri.obj", "", {}}, resolver);
  ASSERT_FALSE(loaded.has_value());
  EXPECT_NE(loaded.error().message.find("sha256 mismatch"), std::string::npos);
}

TEST(SceneMeshes, ASourceOutsideTheManifestIsAFileBesideTheScene) {
  ScratchDir dir;
  const auto manifest = writeManifest(dir, {{"m/tri.obj", "", kHelloSha}});
  dir.write("scenes/my/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const AssetResolver resolver = makeResolver(manifest, {dir.path() / "empty"}, {}, false);
  auto loaded = loadSceneMesh(MeshInstance{"tri", "my/tri.obj", "", {}}, resolver, dir.path() / "scenes");
  ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
  EXPECT_FALSE(loaded->procedural);
  EXPECT_EQ(loaded->mesh.triangleCount(), 1u);

  auto typo = loadSceneMesh(MeshInstance{"tri", "my/tir.obj", "", {}}, resolver, dir.path() / "scenes");
  ASSERT_FALSE(typo.has_value());
  EXPECT_NE(typo.error().message.find("'my/tir.obj' is neither an asset of"), std::string::npos)
      << typo.error().message;
  EXPECT_NE(typo.error().message.find("tir.obj does not exist"), std::string::npos) << typo.error().message;
}

TEST(SceneMeshes, LoadsAnAssetThroughTheResolver) {
  auto loaded = loadSceneMesh(MeshInstance{"teapot", "meshes/teapot.obj", "", {}}, testing::sharedResolver());
  ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
  if (loaded->procedural) MANE_SKIP_FOR_MISSING_ASSET(loaded->note);
  EXPECT_EQ(loaded->mesh.triangleCount(), 6320u);
  EXPECT_TRUE(loaded->note.empty());
}

}  // namespace
}  // namespace mane::scenes
