// `mane render`: the scene rendered headless to PNG files, with each pass's GPU time.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>

#include "app/commands.hpp"
#include "app/scene_loading.hpp"
#include "render/png.hpp"
#include "render/renderer.hpp"

namespace mane::app {
namespace {

struct RenderOptions {
  std::string scene = defaultScenePath().string();
  std::string out = "out";
  std::string size;
  int frames = 1;
  double fps = 30.0;
  unsigned msaa = 4;
  unsigned threads = 2;
};

std::string frameFileName(const std::string& scene, int frame) {
  char number[16];
  std::snprintf(number, sizeof(number), "%04d", frame);
  return scene + "_" + number + ".png";
}

void printProgress(int done, int total, double elapsedSeconds) {
  const int width = 30;
  const int filled = total > 0 ? done * width / total : width;
  const double left = done > 0 ? elapsedSeconds / done * (total - done) : 0.0;
  std::printf("\r[%s%s] %d/%d frames, %.1f s left ", std::string(filled, '#').c_str(),
              std::string(width - filled, '.').c_str(), done, total, left);
  std::fflush(stdout);
}

// Median and worst GPU time of each pass over all frames, in the order the passes ran.
void printTimingTable(const std::vector<std::vector<render::PassTiming>>& frames) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> samples;
  for (const auto& frame : frames)
    for (const auto& timing : frame) {
      if (!samples.contains(timing.pass)) order.push_back(timing.pass);
      samples[timing.pass].push_back(timing.milliseconds);
    }
  std::printf("%-12s %10s %10s\n", "pass", "median ms", "worst ms");
  for (const auto& pass : order) {
    auto& values = samples[pass];
    std::sort(values.begin(), values.end());
    std::printf("%-12s %10.2f %10.2f\n", pass.c_str(), values[values.size() / 2], values.back());
  }
}

void run(const RenderOptions& options) {
  scenes::WorldSettings worldSettings;
  auto world = loadWorld(options.scene, worldSettings);
  if (!world) return failWith(world.error().message);
  std::uint32_t width = static_cast<std::uint32_t>(world->scene().output.width);
  std::uint32_t height = static_cast<std::uint32_t>(world->scene().output.height);
  if (!options.size.empty()) {
    auto size = parseSize(options.size);
    if (!size) return failWith(size.error().message);
    std::tie(width, height) = *size;
  }

  auto device = render::Device::create(render::deviceSettingsFromEnvironment());
  if (!device) return failWith(device.error().message);
  std::cout << "device: " << (*device)->info().name << '\n';
  auto renderer = render::Renderer::create(**device, {.extent = {width, height}, .msaaSamples = options.msaa});
  if (!renderer) return failWith(renderer.error().message);
  if (auto uploaded = (*renderer)->setScene(world->staticScene()); !uploaded) return failWith(uploaded.error().message);

  const std::filesystem::path outDir = options.out;
  const std::string stem =
      world->scene().name.empty() ? std::filesystem::path(options.scene).stem().string() : world->scene().name;
  std::vector<std::vector<render::PassTiming>> timings;
  const auto start = std::chrono::steady_clock::now();
  for (int frame = 0; frame < options.frames; ++frame) {
    if (frame > 0)
      if (auto advanced = world->advance(1.0 / options.fps, options.threads); !advanced)
        return failWith(advanced.error().message);
    if (auto uploaded = uploadDynamicMeshes(*world, **renderer); !uploaded) return failWith(uploaded.error().message);
    render::FrameInput frameInput = world->frameInput();
    frameInput.post.frameSeconds = float(1.0 / options.fps);
    auto frameTimings = (*renderer)->render(frameInput);
    if (!frameTimings) return failWith(frameTimings.error().message);
    timings.push_back(*frameTimings);
    auto pixels = (*renderer)->readOutput();
    if (!pixels) return failWith(pixels.error().message);
    const auto path = outDir / frameFileName(stem, frame);
    if (auto written = render::writePng(path, width, height, *pixels); !written)
      return failWith(written.error().message);
    if (options.frames == 1) {
      std::cout << "wrote " << std::filesystem::absolute(path).lexically_normal().string() << " (" << width << "x"
                << height << ")\n";
    } else {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      printProgress(frame + 1, options.frames, elapsed);
    }
  }
  if (options.frames > 1)
    std::cout << "\nwrote " << options.frames << " frames to "
              << std::filesystem::absolute(outDir).lexically_normal().string() << "/" << stem << "_NNNN.png\n";
  printTimingTable(timings);
  if (options.frames == 1)
    std::cout << "(one frame: its times include first-use shader compilation; --frames N gives steady-state "
                 "medians)\n";
  if (checkValidation(**device)) succeed();
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  auto* command = app.add_subcommand("render", "Render a scene headless to PNG files and report each pass's GPU time");
  command->add_option("scene", options->scene, "Scene file (JSON)")->capture_default_str();
  command->add_option("--out", options->out, "Folder for the PNG files")->capture_default_str();
  command->add_option("--size", options->size, "Image size WIDTHxHEIGHT (default: the scene's)");
  command->add_option("--frames", options->frames, "Number of frames to render")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--fps", options->fps, "Frames per second of the animation")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  command->add_option("--msaa", options->msaa, "Samples per pixel (1 or 4)")
      ->check(CLI::IsMember({1u, 4u}))
      ->capture_default_str();
  command->add_option("--threads", options->threads, "Simulation threads (results do not depend on it)")
      ->check(CLI::Range(1u, 64u))
      ->capture_default_str();
  command->callback([options] { run(*options); });
}

}  // namespace mane::app
