// `mane render`: the scene rendered headless to PNG files, with each pass's GPU time; with --mp4,
// the frames also encoded into a video by ffmpeg; with --cache, the frames of a simulation cache
// rendered without simulating (any --frame-range of them: a render farm's share); with --json, a
// machine-readable report of the times.

#include <CLI/CLI.hpp>
#include <charconv>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/mp4_encoding.hpp"
#include "app/scene_loading.hpp"
#include "app/timing_report.hpp"
#include "render/exr.hpp"
#include "render/png.hpp"
#include "render/renderer.hpp"
#include "physics/hash.hpp"
#include "scenes/frame_loop.hpp"
#include "scenes/sim_cache.hpp"

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
  std::string mp4;         ///< empty: PNG frames only
  std::string cache;       ///< empty: simulate; else render the simulation cache in this folder
  std::string frameRange;  ///< "FIRST:LAST", inclusive; empty: every frame
  bool json = false;
  bool strict = false;  ///< every groom strict
  bool exr = false;     ///< also each frame's linear HDR colour as OpenEXR
};

constexpr const char* kFrameNumber = "%04d";

/// SCENE_ffff.png, or with `extension` in place of .png.
std::string frameFileName(const std::string& scene, int frame, const std::string& extension = ".png") {
  char number[16];
  std::snprintf(number, sizeof(number), kFrameNumber, frame);
  return scene + "_" + number + extension;
}

void printProgress(int done, int total, double elapsedSeconds) {
  const int width = 30;
  const int filled = total > 0 ? done * width / total : width;
  const double left = done > 0 ? elapsedSeconds / done * (total - done) : 0.0;
  std::printf("\r[%s%s] %d/%d frames, %.1f s left ", std::string(filled, '#').c_str(),
              std::string(width - filled, '.').c_str(), done, total, left);
  std::fflush(stdout);
}

/// "A:B" (inclusive, 0 ≤ A ≤ B) → {A, B}.
Result<std::pair<int, int>> parseFrameRange(const std::string& text) {
  const auto colon = text.find(':');
  int first = -1, last = -1;
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (colon == std::string::npos || std::from_chars(begin, begin + colon, first).ptr != begin + colon ||
      std::from_chars(begin + colon + 1, end, last).ptr != end || first < 0 || last < first)
    return fail("--frame-range " + text + ": expected FIRST:LAST, frame numbers from 0 with FIRST ≤ LAST, e.g. 0:99");
  return std::pair{first, last};
}

/// One rendered frame, for the JSON report.
struct FrameRecord {
  int frame = 0;
  std::string file;
  std::string exrFile;  ///< empty without --exr
  std::vector<render::PassTiming> passes;
  scenes::FrameStageTimes stages;  ///< the simulation's share (zero for cached frames)
  double loadCacheMs = 0.0;        ///< reading and showing the cached state
  double wallMs = 0.0;             ///< the whole frame on the CPU, PNG included
};

nlohmann::json jsonReport(const RenderOptions& options, const std::string& scene, const std::string& device,
                          std::uint32_t width, std::uint32_t height, double fps, const std::vector<FrameRecord>& frames,
                          double wallSeconds, std::uint64_t stateHash, const std::vector<std::string>& notes) {
  nlohmann::json perFrame = nlohmann::json::array();
  std::vector<std::vector<render::PassTiming>> timings;
  for (const FrameRecord& record : frames) {
    nlohmann::json passes = nlohmann::json::object();
    for (const auto& timing : record.passes) {
      const std::string name(timing.pass.name());
      passes[name] = passes.value(name, 0.0) + timing.milliseconds;  // a pass may run more than once a frame
    }
    perFrame.push_back({{"frame", record.frame},
                        {"file", record.file},
                        {"exr_file", record.exrFile.empty() ? nlohmann::json() : nlohmann::json(record.exrFile)},
                        {"wall_ms", record.wallMs},
                        {"simulate_ms", record.stages.simulateMs},
                        {"upload_ms", record.stages.uploadMs},
                        {"refine_ms", record.stages.refineMs},
                        {"load_cache_ms", record.loadCacheMs},
                        {"gpu_ms", allPassesMilliseconds(record.passes)},
                        {"passes_gpu_ms", passes}});
    timings.push_back(record.passes);
  }
  nlohmann::json passes = nlohmann::json::array();
  for (const PassStatistics& row : passStatistics(timings))
    passes.push_back({{"pass", row.pass}, {"median_ms", row.medianMs}, {"worst_ms", row.worstMs}});
  return {{"command", "render"},
          {"scene", scene},
          {"device", device},
          {"width", width},
          {"height", height},
          {"msaa", options.msaa},
          {"fps", fps},
          {"source", options.cache.empty() ? "simulated" : "cache"},
          {"cache", options.cache.empty() ? nlohmann::json() : nlohmann::json(options.cache)},
          {"first_frame", frames.empty() ? 0 : frames.front().frame},
          {"last_frame", frames.empty() ? 0 : frames.back().frame},
          {"wall_seconds", wallSeconds},
          {"state_hash", physics::hashText(stateHash)},
          {"notes", notes},
          {"passes", passes},
          {"frames", perFrame}};
}

void run(const RenderOptions& options, bool sceneGiven) {
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
  // Which frames: 0 .. --frames − 1, a --frame-range, or the cache's frames.
  std::optional<scenes::SimCacheManifest> cache;
  std::string scenePath = options.scene;
  double fps = options.fps;
  int firstFrame = 0, lastFrame = options.frames - 1;
  if (!options.cache.empty()) {
    auto manifest = scenes::readCacheManifest(options.cache);
    if (!manifest) return failWith(manifest.error().message);
    cache = std::move(*manifest);
    if (!sceneGiven) scenePath = cache->scene;
    fps = cache->fps;
    lastFrame = int(cache->frames) - 1;
  }
  if (!options.frameRange.empty()) {
    auto range = parseFrameRange(options.frameRange);
    if (!range) return failWith(range.error().message);
    std::tie(firstFrame, lastFrame) = *range;
    if (cache && lastFrame >= int(cache->frames))
      return failWith("--frame-range " + options.frameRange + ": the cache " + options.cache + " holds frames 0 to " +
                      std::to_string(cache->frames - 1));
  }
  if (ffmpeg && firstFrame != 0)
    return failWith("--mp4 encodes frames from 0 on; render the ranges, then encode the PNG files with ffmpeg");
  const int frameCount = lastFrame - firstFrame + 1;

  scenes::WorldSettings worldSettings;
  worldSettings.strictGrooms = options.strict;
  auto world = loadWorld(scenePath, worldSettings, !options.json);
  if (!world) return failWith(world.error().message);
  std::uint32_t width = static_cast<std::uint32_t>(world->scene().output.width);
  std::uint32_t height = static_cast<std::uint32_t>(world->scene().output.height);
  if (size) std::tie(width, height) = *size;
  if (cache && world->scene().post.autoGain && firstFrame > 0 && !options.json)
    std::cout << "note: the scene's auto gain adapts from frame to frame; a range that starts mid-sequence starts "
                 "from this frame's own exposure (docs/render-farm.md)\n";

  auto device = render::Device::create(render::deviceSettingsFromEnvironment());
  if (!device) return failWith(device.error().message);
  const std::string deviceName = (*device)->info().name;
  if (!options.json) std::cout << "device: " << deviceName << '\n';
  auto renderer = render::Renderer::create(**device, {.extent = {width, height}, .msaaSamples = options.msaa});
  if (!renderer) return failWith(renderer.error().message);
  auto loop = scenes::FrameLoop::create(*world, **renderer, {.imageSize = {width, height}, .threads = options.threads});
  if (!loop) return failWith(loop.error().message);
  if (auto set = loop->setScene(world->staticScene()); !set) return failWith(set.error().message);

  const std::filesystem::path outDir = options.out;
  const std::string stem =
      world->scene().name.empty() ? std::filesystem::path(scenePath).stem().string() : world->scene().name;
  const bool progress = frameCount > 1 && !options.json && stdoutIsTerminal();
  std::vector<FrameRecord> records;
  std::uint64_t stateHash = world->stateHash();
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  for (int frame = cache ? firstFrame : 0; frame <= lastFrame; ++frame) {
    const auto frameStart = Clock::now();
    FrameRecord record{.frame = frame};
    if (cache) {
      auto state = scenes::readCacheFrame(options.cache, *cache, static_cast<std::uint32_t>(frame), *world);
      if (!state) return failWith(state.error().message);
      if (auto shown = scenes::showSimulatedState(*state, *world, **renderer); !shown)
        return failWith(shown.error().message);
      stateHash = state->stateHash;
      record.loadCacheMs = std::chrono::duration<double, std::milli>(Clock::now() - frameStart).count();
    } else if (frame > 0) {
      if (auto advanced = loop->advance(1.0 / fps); !advanced) return failWith(advanced.error().message);
      stateHash = world->stateHash();
    }
    if (frame < firstFrame) continue;  // simulated up to the range, not rendered
    render::FrameInput frameInput = world->frameInput();
    frameInput.post.frameSeconds = float(1.0 / fps);
    auto frameTimings = loop->renderFrame(frameInput);
    if (!frameTimings) return failWith(frameTimings.error().message);
    record.passes = *frameTimings;
    record.stages = loop->lastStageTimes();
    if (cache) record.stages.simulateMs = record.stages.uploadMs = 0.0;
    auto pixels = (*renderer)->readOutput();
    if (!pixels) return failWith(pixels.error().message);
    const auto path = outDir / frameFileName(stem, frame);
    if (auto written = render::writePng(path, width, height, *pixels); !written)
      return failWith(written.error().message);
    record.file = std::filesystem::absolute(path).lexically_normal().string();
    if (options.exr) {
      auto hdr = (*renderer)->readHdrOutput();
      if (!hdr) return failWith(hdr.error().message);
      const auto exrPath = outDir / frameFileName(stem, frame, ".exr");
      if (auto written = render::writeExr(exrPath, width, height, *hdr); !written)
        return failWith(written.error().message);
      record.exrFile = std::filesystem::absolute(exrPath).lexically_normal().string();
    }
    record.wallMs = std::chrono::duration<double, std::milli>(Clock::now() - frameStart).count();
    records.push_back(std::move(record));
    if (frameCount == 1 && !options.json) {
      std::cout << "wrote " << records.back().file << " (" << width << "x" << height << ")\n";
      if (options.exr) std::cout << "wrote " << records.back().exrFile << " (linear fp16 RGB)\n";
    } else if (progress) {
      printProgress(int(records.size()), frameCount, std::chrono::duration<double>(Clock::now() - start).count());
    }
  }
  const double wallSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (frameCount > 1 && !options.json)
    std::cout << (progress ? "\n" : "") << "wrote " << frameCount << " frames to "
              << std::filesystem::absolute(outDir).lexically_normal().string() << "/" << stem << "_NNNN.png"
              << (options.exr ? " and .exr" : "") << '\n';
  if (ffmpeg) {
    const std::filesystem::path mp4 = std::filesystem::absolute(options.mp4).lexically_normal();
    std::error_code error;
    if (mp4.has_parent_path()) std::filesystem::create_directories(mp4.parent_path(), error);
    std::string pattern;  // ffmpeg reads the file names as a printf pattern: a '%' of the name doubles
    for (char c : stem) pattern += c == '%' ? std::string("%%") : std::string(1, c);
    if (auto encoded = encodeMp4(*ffmpeg, outDir / (pattern + "_" + kFrameNumber + ".png"), frameCount, fps, mp4);
        !encoded)
      return failWith(encoded.error().message);
    if (!options.json)
      std::cout << "wrote " << mp4.string() << " (H.264, " << frameCount << " frames at " << fps << " fps)\n";
  }
  if (options.json) {
    const std::string scene = std::filesystem::absolute(scenePath).lexically_normal().string();
    std::cout << jsonReport(options, scene, deviceName, width, height, fps, records, wallSeconds, stateHash,
                            world->notes())
                     .dump(2)
              << '\n';
  } else {
    std::vector<std::vector<render::PassTiming>> timings;
    for (const FrameRecord& record : records) timings.push_back(record.passes);
    printTimingTable(passStatistics(timings));
    if (frameCount == 1)
      std::cout << "(one frame: its times include first-use shader compilation; --frames N gives steady-state "
                   "medians)\n";
  }
  if (checkValidation(**device)) succeed();
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  auto* command = app.add_subcommand("render", "Render a scene headless to PNG files and report each pass's GPU time");
  auto* scene = command->add_option("scene", options->scene, "Scene file (JSON); with --cache, the cache's scene")
                    ->capture_default_str();
  command->add_option("--out", options->out, "Folder for the PNG files")->capture_default_str();
  command->add_option("--size", options->size, "Image size WIDTHxHEIGHT (default: the scene's)");
  auto* frames = command->add_option("--frames", options->frames, "Number of frames to render")
                     ->check(CLI::Range(1, 100000))
                     ->capture_default_str();
  auto* fps = command->add_option("--fps", options->fps, "Frames per second of the animation")
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
  auto* cache = command
                    ->add_option("--cache", options->cache,
                                 "Render the frames of a simulation cache (`mane sim --cache`) without simulating, at "
                                 "its fps; frame f is written as SCENE_ffff.png")
                    ->type_name("FOLDER");
  auto* range = command
                    ->add_option("--frame-range", options->frameRange,
                                 "Render only frames FIRST to LAST (inclusive, from 0): a farm's share of a sequence. "
                                 "Without --cache the frames before FIRST are simulated, not rendered")
                    ->type_name("FIRST:LAST");
  range->excludes(frames);
  cache->excludes(frames);
  cache->excludes(fps);
  command->add_flag("--exr", options->exr,
                    "Also write each frame's HDR colour as SCENE_ffff.exr beside its PNG: fp16 RGB, linear, before "
                    "exposure, glow and tone mapping");
  command->add_flag("--strict", options->strict, kStrictGroomsHelp);
  command->add_flag("--json", options->json,
                    "Print a JSON report (per-frame and per-pass GPU times, frame times, state hash) instead of text");
  command->callback([options, scene] { run(*options, scene->count() > 0); });
}

}  // namespace mane::app
