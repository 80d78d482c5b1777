#include "app/scene_loading.hpp"

#include <charconv>
#include <iostream>
#include <unistd.h>

namespace mane::app {

std::filesystem::path defaultScenePath() {
  return std::filesystem::path(MANE_SOURCE_DIR) / "scenes" / "nalu.json";
}

Result<scenes::World> loadWorld(const std::filesystem::path& scenePath, const scenes::WorldSettings& settings,
                                bool printNotes) {
  auto scene = scenes::loadScene(scenePath);
  if (!scene) return std::unexpected(scene.error());
  if (settings.strictGrooms)
    for (scenes::Groom& groom : scene->grooms) groom.strict = !groom.isProcedural();
  auto resolver = scenes::AssetResolver::createDefault();
  if (!resolver) return std::unexpected(resolver.error());
  auto world = scenes::World::create(std::move(*scene), *resolver, settings);
  if (!world) return std::unexpected(world.error());
  if (printNotes)
    for (const std::string& note : world->notes()) std::cout << "note: " << note << '\n';
  return world;
}

bool stdoutIsTerminal() {
  return isatty(STDOUT_FILENO) != 0;
}

Result<std::pair<std::uint32_t, std::uint32_t>> parseSize(const std::string& text) {
  const auto x = text.find('x');
  std::uint32_t width = 0, height = 0;
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (x == std::string::npos || std::from_chars(begin, begin + x, width).ptr != begin + x ||
      std::from_chars(begin + x + 1, end, height).ptr != end || width == 0 || height == 0 || width > 16384 ||
      height > 16384)
    return fail("--size " + text + ": expected WIDTHxHEIGHT with each between 1 and 16384, e.g. 1280x720");
  return std::pair{width, height};
}

}  // namespace mane::app
