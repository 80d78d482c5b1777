// The `mane` Python module: a scene loaded into a World, stepped, its guide particles read and
// written as NumPy arrays, and rendered headless into a NumPy image. A thin layer over
// scenes::World and scenes::FrameLoop, so a script sees what `mane sim` and `mane render` see:
// the same loading, the same steps, the same state hash.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "render/device.hpp"
#include "render/renderer.hpp"
#include "scenes/assets.hpp"
#include "scenes/frame_loop.hpp"
#include "scenes/scene.hpp"
#include "scenes/world.hpp"

namespace py = pybind11;

namespace mane::python {
namespace {

// Raised as mane.Error (a RuntimeError) with the engine's message.
struct ScriptError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void raise(const Error& error) {
  throw ScriptError(error.message);
}

template <class T>
T take(Result<T> result) {
  if (!result) raise(result.error());
  return std::move(*result);
}

void check(const Result<void>& result) {
  if (!result) raise(result.error());
}

// NumPy float32 rows of three are read as glm::vec3 without a copy.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float));

using FloatRows = py::array_t<float, py::array::c_style | py::array::forcecast>;

py::array_t<float> rowsOf(std::span<const glm::vec3> points) {
  py::array_t<float> array({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  std::memcpy(array.mutable_data(), points.data(), points.size_bytes());
  return array;
}

std::span<const glm::vec3> pointsOf(const FloatRows& array, const char* what, std::size_t expected) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error(std::string(what) + ": expected an array of shape (" + std::to_string(expected) +
                          ", 3), got " + std::to_string(array.ndim()) + " dimensions");
  if (static_cast<std::size_t>(array.shape(0)) != expected)
    throw py::value_error(std::string(what) + ": expected " + std::to_string(expected) + " rows, got " +
                          std::to_string(array.shape(0)));
  return {reinterpret_cast<const glm::vec3*>(array.data()), expected};
}

// A World the script owns; the class exists so that pybind11 holds it through a unique_ptr
// (World is movable but has no public constructor).
struct ScriptedWorld {
  scenes::World world;

  physics::HairSystem& groom(std::size_t index) {
    if (index >= world.simulatedGroomCount())
      throw py::index_error("groom " + std::to_string(index) + ": the world simulates " +
                            std::to_string(world.simulatedGroomCount()) + " grooms");
    return world.simulatedGroomMutable(index);
  }
};

std::unique_ptr<ScriptedWorld> loadWorld(const std::filesystem::path& scenePath, bool loadTextures) {
  auto scene = take(scenes::loadScene(scenePath));
  auto resolver = take(scenes::AssetResolver::createDefault());
  py::gil_scoped_release unlocked;
  auto world = take(scenes::World::create(std::move(scene), resolver, {.loadTextures = loadTextures}));
  return std::make_unique<ScriptedWorld>(ScriptedWorld{std::move(world)});
}

// What `mane render` holds for a run: the Vulkan device and a renderer of one image size.
struct ScriptedRenderer {
  std::unique_ptr<render::Device> device;
  std::unique_ptr<render::Renderer> renderer;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

std::unique_ptr<ScriptedRenderer> createRenderer(std::uint32_t width, std::uint32_t height, std::uint32_t msaa) {
  auto result = std::make_unique<ScriptedRenderer>();
  result->width = width;
  result->height = height;
  py::gil_scoped_release unlocked;
  result->device = take(render::Device::create(render::deviceSettingsFromEnvironment()));
  result->renderer = take(render::Renderer::create(*result->device, {.extent = {width, height}, .msaaSamples = msaa}));
  return result;
}

// The world's frame as it is now. The renderer is handed the world's whole scene each call: a
// script may step the world, write its particles or render another world in between, and
// setScene then uploads what moved (FrameLoop keeps no state of its own across frames).
py::array_t<std::uint8_t> renderFrame(ScriptedRenderer& self, ScriptedWorld& scripted, double frameSeconds,
                                      unsigned threads) {
  std::vector<std::uint8_t> pixels;
  {
    py::gil_scoped_release unlocked;
    auto loop = take(scenes::FrameLoop::create(scripted.world, *self.renderer,
                                               {.imageSize = {self.width, self.height}, .threads = threads}));
    check(loop.setScene(scripted.world.staticScene()));
    render::FrameInput frame = scripted.world.frameInput();
    frame.post.frameSeconds = static_cast<float>(frameSeconds);
    take(loop.renderFrame(frame));
    pixels = take(self.renderer->readOutput());
  }
  py::array_t<std::uint8_t> image({py::ssize_t(self.height), py::ssize_t(self.width), py::ssize_t{4}});
  if (pixels.size() != static_cast<std::size_t>(image.size()))
    throw ScriptError("renderer returned " + std::to_string(pixels.size()) + " bytes for a " +
                      std::to_string(self.width) + "x" + std::to_string(self.height) + " RGBA image");
  std::memcpy(image.mutable_data(), pixels.data(), pixels.size());
  return image;
}

}  // namespace
}  // namespace mane::python

PYBIND11_MODULE(mane, module) {
  using namespace mane;
  using namespace mane::python;
  module.doc() = "mane: hair, fur and cloth simulated deterministically on the CPU, rendered headless with Vulkan.";
  module.attr("__version__") = MANE_VERSION;
  py::register_exception<ScriptError>(module, "Error", PyExc_RuntimeError);

  py::class_<ScriptedWorld>(module, "World",
                            "A scene loaded with its meshes, grooms and cloths (as `mane sim` and `mane render` "
                            "load it). Lengths in metres, times in seconds, positions in world space.")
      .def(py::init(&loadWorld), py::arg("scene"), py::arg("load_textures") = true,
           "Loads the scene file (JSON) and its assets. load_textures=False skips decoding the materials' "
           "images (what `mane sim` does; render() then draws without them). Raises mane.Error.")
      .def_property_readonly("name", [](const ScriptedWorld& self) { return self.world.scene().name; })
      .def_property_readonly(
          "notes", [](const ScriptedWorld& self) { return self.world.notes(); },
          "What differs from what the scene asked for (fallbacks, skipped content).")
      .def_property_readonly(
          "time", [](const ScriptedWorld& self) { return self.world.time(); }, "Seconds of animation played so far.")
      .def_property_readonly(
          "step_seconds", [](const ScriptedWorld& self) { return double(self.world.scene().simulation.stepSeconds); },
          "The scene's fixed simulation step, seconds.")
      .def(
          "advance",
          [](ScriptedWorld& self, double seconds, unsigned threads) {
            py::gil_scoped_release unlocked;
            check(self.world.advance(seconds, threads));
          },
          py::arg("seconds"), py::arg("threads") = 1,
          "Animates and simulates `seconds` more (whole fixed steps; the remainder carries over). "
          "The result does not depend on threads.")
      .def(
          "step",
          [](ScriptedWorld& self, int steps, unsigned threads) {
            py::gil_scoped_release unlocked;
            const double step = self.world.scene().simulation.stepSeconds;
            for (int i = 0; i < steps; ++i) check(self.world.advance(step, threads));
          },
          py::arg("steps") = 1, py::arg("threads") = 1,
          "Advances by `steps` fixed steps, one advance() each, as `mane sim --steps` does.")
      .def_property_readonly(
          "state_hash", [](const ScriptedWorld& self) { return self.world.stateHash(); },
          "64-bit hash of every simulated state and the clock (`mane sim` prints it in hex).")
      .def_property_readonly(
          "groom_count", [](const ScriptedWorld& self) { return self.world.simulatedGroomCount(); },
          "Simulated grooms, in scene order.")
      .def_property_readonly(
          "groom_names",
          [](const ScriptedWorld& self) {
            std::vector<std::string> names;
            for (std::size_t g = 0; g < self.world.simulatedGroomCount(); ++g)
              names.push_back(self.world.simulatedGroomName(g));
            return names;
          },
          "The simulated grooms' names, in the order the groom index counts them.")
      .def_property_readonly("particle_count", [](const ScriptedWorld& self) { return self.world.particleCount(); })
      .def(
          "strand_offsets",
          [](ScriptedWorld& self, std::size_t groom) {
            const auto strands = self.groom(groom).strands();
            py::array_t<std::uint32_t> offsets(py::ssize_t(strands.size() + 1));
            auto out = offsets.mutable_unchecked<1>();
            for (std::size_t s = 0; s < strands.size(); ++s) out(py::ssize_t(s)) = strands[s].firstParticle;
            out(py::ssize_t(strands.size())) = std::uint32_t(self.groom(groom).particles().size());
            return offsets;
          },
          py::arg("groom"), "Strand s's particles are rows offsets[s] to offsets[s+1] of positions(), root first.")
      .def(
          "positions",
          [](ScriptedWorld& self, std::size_t groom) { return rowsOf(self.groom(groom).particles().positions); },
          py::arg("groom"), "A copy of the groom's guide particle positions, (N, 3) float32, metres.")
      .def(
          "previous_positions",
          [](ScriptedWorld& self, std::size_t groom) {
            return rowsOf(self.groom(groom).particles().previousPositions);
          },
          py::arg("groom"), "The positions one fixed step earlier, (N, 3) float32 (Verlet keeps no velocity).")
      .def(
          "set_positions",
          [](ScriptedWorld& self, std::size_t groom, const FloatRows& positions, std::optional<FloatRows> previous) {
            physics::HairSystem& hair = self.groom(groom);
            const std::size_t count = hair.particles().size();
            const auto current = pointsOf(positions, "positions", count);
            const auto before = previous ? pointsOf(*previous, "previous", count) : current;
            check(hair.setParticleState(current, before));
          },
          py::arg("groom"), py::arg("positions"), py::arg("previous") = py::none(),
          "Writes the groom's particle state. Without `previous` the particles are left at rest (the previous "
          "positions are set to the same values); with it, positions - previous is the displacement the next "
          "step carries on. Roots are placed on their head or targets again by the next step.")
      .def(
          "root_rest_normals",
          [](ScriptedWorld& self, std::size_t groom) { return rowsOf(self.groom(groom).rootRestNormals()); },
          py::arg("groom"), "Per strand, its root's normal at rest in the head's local frame, (S, 3).")
      .def(
          "set_root_targets",
          [](ScriptedWorld& self, std::size_t groom, const FloatRows& positions, const FloatRows& normals) {
            physics::HairSystem& hair = self.groom(groom);
            const std::size_t count = hair.strandCount();
            check(hair.setRootTargets(pointsOf(positions, "positions", count), pointsOf(normals, "normals", count)));
          },
          py::arg("groom"), py::arg("positions"), py::arg("normals"),
          "Where each root is at the end of the next advance (world space, one row per strand) and the skin's "
          "normal there; from then on roots follow the last targets given instead of their mesh. A groom on a "
          "character part gets targets from the character every advance, over these.");

  py::class_<ScriptedRenderer>(module, "Renderer",
                               "A headless Vulkan renderer (as `mane render` makes it) of one image size.")
      .def(py::init(&createRenderer), py::arg("width"), py::arg("height"), py::arg("msaa") = 4,
           "Creates the device (MANE_DEVICE and the other environment settings `mane render` reads apply) and "
           "a renderer of width x height pixels with msaa samples per pixel (1 or 4). Raises mane.Error.")
      .def_property_readonly("device_name", [](const ScriptedRenderer& self) { return self.device->info().name; })
      .def_property_readonly("size",
                             [](const ScriptedRenderer& self) { return py::make_tuple(self.width, self.height); })
      .def("render", &renderFrame, py::arg("world"), py::arg("frame_seconds") = 1.0 / 30.0, py::arg("threads") = 1,
           "Renders the world as it is now and returns the image, (height, width, 4) uint8 sRGB RGBA, rows top "
           "to bottom. frame_seconds paces the exposure adaptation, as `mane render --fps` does.");
}
