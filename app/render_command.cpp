// `mane render`: the scene rendered headless to PNG files, with each pass's GPU time; with --mp4,
// the frames also encoded into a video by ffmpeg.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>

#include "app/commands.hpp"
#include "app/mp4_encoding.hpp"
#include "app/scene_loading.hpp"
#include "render/png.hpp"
#include "render/renderer.hpp"
#include "scenes/frame_loop.hpp"

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
  std::string mp4;  ///< empty: PNG frames only
};

constexpr const char* kFrameNumber = "%04d";

std::string frameFileName(const std::string& scene, int frame) {
  char number[16];
  std::snprintf(number, sizeof(number), kFrameNumber, frame);
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

// Median and worst GPU time of each pass over all frames, in the order the passes ran, then of
// the whole span from the first pass's begin to the last one's end: on lavapipe a render pass's
// draws are rasterized when it ends, and that work can fall between two passes' timers.
void printTimingTable(const std::vector<std::vector<render::PassTiming>>& frames) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> samples;
  const std::string span = "all passes";
  for (const auto& frame : frames) {
    double end = 0.0;
    for (const auto& timing : frame) {
      const std::string pass(timing.pass.name());
      if (!samples.contains(pass)) order.push_back(pass);
      samples[pass].push_back(timing.milliseconds);
      end = std::max(end, timing.startMilliseconds + timing.milliseconds);
    }
    if (!frame.empty()) samples[span].push_back(end);
  }
  if (samples.contains(span)) order.push_back(span);
  std::printf("%-18s %10s %10s\n", "pass", "median ms", "worst ms");
  for (const auto& pass : order) {
    auto& values = samples[pass];
    std::sort(values.begin(), values.end());
    std::printf("%-18s %10.2f %10.2f\n", pass.c_str(), values[values.size() / 2], values.back());
  }
}

void run(const RenderOptions& options) {
  // Before any rendering: a missing encoder found after an hour of frames wastes the hour.
  std::optional<std::filesystem::path> ffmpeg;
  if (!options.mp4.empty()) {
    ffmpeg = findOnPath("ffmpeg");
    if (std::filesystem::is_directory(options.mp4))
      return failWith("--mp4 " + options.mp4 + " is a folder; give the name of the MP4 file to write");
    if (!ffmpeg)
      return failWith(
          "--mp4 needs the program ffmpeg, which is not on PATH (Debian/Ubuntu: sudo apt-get install "
          "ffmpeg)");
  }
  std::optional<std::pair<std::uint32_t, std::uint32_t>> size;
  if (!options.size.empty()) {
    auto parsed = parseSize(options.size);
    if (!parsed) return failWith(parsed.error().message);
    size = *parsed;
  }
  scenes::WorldSettings worldSettings;
  auto world = loadWorld(options.scene, worldSettings);
  if (!world) return failWith(world.error().message);
  std::uint32_t width = static_cast<std::uint32_t>(world->scene().output.width);
  std::uint32_t height = static_cast<std::uint32_t>(world->scene().output.height);
  if (size) std::tie(width, height) = *size;

  auto device = render::Device::create(render::deviceSettingsFromEnvironment());
  if (!device) return failWith(device.error().message);
  std::cout << "device: " << (*device)->info().name << '\n';
  auto renderer = render::Renderer::create(**device, {.extent = {width, height}, .msaaSamples = options.msaa});
  if (!renderer) return failWith(renderer.error().message);
  auto loop = scenes::FrameLoop::create(*world, **renderer, {.imageSize = {width, height}, .threads = options.threads});
  if (!loop) return failWith(loop.error().message);
  if (auto set = loop->setScene(world->staticScene()); !set) return failWith(set.error().message);

  const std::filesystem::path outDir = options.out;
  const std::string stem =
      world->scene().name.empty() ? std::filesystem::path(options.scene).stem().string() : world->scene().name;
  std::vector<std::vector<render::PassTiming>> timings;
  const auto start = std::chrono::steady_clock::now();
  for (int frame = 0; frame < options.frames; ++frame) {
    if (frame > 0)
      if (auto advanced = loop->advance(1.0 / options.fps); !advanced) return failWith(advanced.error().message);
    render::FrameInput frameInput = world->frameInput();
    frameInput.post.frameSeconds = float(1.0 / options.fps);
    auto frameTimings = loop->renderFrame(frameInput);
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
  if (ffmpeg) {
    const std::filesystem::path mp4 = std::filesystem::absolute(options.mp4).lexically_normal();
    std::error_code error;
    if (mp4.has_parent_path()) std::filesystem::create_directories(mp4.parent_path(), error);
    std::string pattern;  // ffmpeg reads the file names as a printf pattern: a '%' of the name doubles
    for (char c : stem) pattern += c == '%' ? std::string("%%") : std::string(1, c);
    if (auto encoded =
            encodeMp4(*ffmpeg, outDir / (pattern + "_" + kFrameNumber + ".png"), options.frames, options.fps, mp4);
        !encoded)
      return failWith(encoded.error().message);
    std::cout << "wrote " << mp4.string() << " (H.264, " << options.frames << " frames at " << options.fps << " fps)\n";
  }
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
  command
      ->add_option("--mp4", options->mp4,
                   "Also encode the frames into this H.264 MP4 file at --fps (needs ffmpeg on PATH: sudo apt-get "
                   "install ffmpeg)")
      ->type_name("FILE");
  command->callback([options] { run(*options); });
}

}  // namespace mane::app
