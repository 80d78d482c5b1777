#pragma once
// A scene's environment made ready for the renderer: the panorama read and turned into a cube map,
// or the procedural sky built with the first light as its sun.

#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "render/frame.hpp"
#include "scenes/assets.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {

struct SceneEnvironment {
  render::EnvironmentData data;
  /// The panorama's sun, cut out of `data` where the scene asks (Environment::sunLight) and the
  /// panorama has one.
  std::optional<render::DirectionalLight> sun;
};

/// The cube map of `scene.environment` (nothing when it has none), and its sun where the scene
/// asks for it (a note says where it lies, or that the panorama has none). A panorama that is
/// missing is replaced by the sky, with a line in `notes`; one that cannot be read is an error
/// naming it.
[[nodiscard]] Result<std::optional<SceneEnvironment>> loadSceneEnvironment(const Scene& scene,
                                                                           const AssetResolver& resolver,
                                                                           std::vector<std::string>& notes);

}  // namespace mane::scenes
