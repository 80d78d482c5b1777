#pragma once
// Spectacles built from a scene's measurements (scenes/scene.hpp, `Glasses`): two lenses ground
// to its prescription (render/lens.hpp) and the frame that holds them as a mesh — a rim round each
// lens's outline, covering its edge, a bridge between the rims and two temples running back from
// hinges on the rims' outer sides and bending down over the ears. Everything is in the glasses'
// own frame: metres, origin at the middle of the bridge on the lenses' front, +x to the wearer's
// left, +y up, +z forward.

#include <array>

#include "common/error.hpp"
#include "render/lens.hpp"
#include "scenes/mesh.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes {

struct GlassesModel {
  Mesh frame;
  std::array<render::Lens, 2> lenses;  ///< models place them in the glasses' frame: right, then left
};

/// Errors name what the measurements do not allow (a lens too strong for its outline).
[[nodiscard]] Result<GlassesModel> buildGlasses(const Glasses& glasses);

}  // namespace mane::scenes
