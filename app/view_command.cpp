// `mane view`: the scene in a window (GLFW + Vulkan swapchain) with an orbit camera.
// Mouse: left drag orbits, right drag turns the key light, wheel zooms. Keys (kKeyHelp): pause and
// step the simulation, turn the key light, switch techniques and post effects, quit. The frame time
// and the toggles' states are drawn in the image's top-left corner
// (render/passes/text_overlay_pass.hpp) and the window title.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/commands.hpp"
#include "app/scene_loading.hpp"
#include "render/passes/text_overlay_pass.hpp"
#include "render/png.hpp"
#include "render/renderer.hpp"
#include "render/window.hpp"
#include "scenes/frame_loop.hpp"

namespace mane::app {
namespace {

struct ViewOptions {
  std::string scene = defaultScenePath().string();
  int frames = 0;  ///< 0: until the window closes
  std::string screenshot;
  unsigned msaa = 1;
  unsigned threads = 2;
  std::string press;  ///< keys pressed one per frame from the second frame on
  bool strict = false;  ///< every groom strict
};

constexpr const char* kKeyHelp =
    "Keys: Space pause/run the simulation, N step one frame while paused, K skin pre-integrated / texture-space "
    "diffusion, H hair shadows opacity / deep opacity maps, T tone map Reinhard / linear, G glow, A auto gain, "
    "R god rays, F fur shells and fins / bare, S the surfaces' soft shadows, O the on-screen text, J / L turn the key "
    "light left / right 15 degrees, "
    "I / M raise / lower it 10 degrees, C a character's next animation clip (cross-faded), E its next expression "
    "(morph target blended in, the last one out), B fire the ship's cannon, W / Q the sea's wind stronger / calmer, "
    "Esc quit. Mouse: left drag orbits, right drag turns the key light, "
    "wheel "
    "zooms.";

// Spherical coordinates around the scene camera's target.
struct OrbitCamera {
  glm::vec3 target{0.0f};
  float distance = 1.0f;
  float yaw = 0.0f;    ///< radians about +Y
  float pitch = 0.0f;  ///< radians above the horizon
  double lastX = 0.0, lastY = 0.0;
  bool dragging = false;

  static OrbitCamera from(const render::Camera& camera) {
    OrbitCamera orbit;
    orbit.target = camera.target;
    const glm::vec3 offset = camera.position - camera.target;
    orbit.distance = glm::length(offset);
    orbit.yaw = std::atan2(offset.x, offset.z);
    orbit.pitch = std::asin(glm::clamp(offset.y / std::max(orbit.distance, 1e-6f), -1.0f, 1.0f));
    return orbit;
  }
  glm::vec3 position() const {
    return target +
           distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  }
};

// The key light (the scene's first, which casts the hair shadows and the god rays) turned about the
// vertical and raised or lowered from where the scene put it. Keys turn it in whole steps and the
// right mouse button continuously; both add to the same angles.
struct LightControl {
  static constexpr float kYawStep = glm::radians(15.0f);
  static constexpr float kPitchStep = glm::radians(10.0f);
  static constexpr float kMaxElevation = glm::radians(85.0f);
  float yaw = 0.0f;    ///< radians about +Y, added to the light's azimuth
  float pitch = 0.0f;  ///< radians added to its elevation
  bool dragging = false;

  /// `towardLight` (a unit vector) with the turn applied; its elevation stays within ±85°. The
  /// same arithmetic with no turn, so that turning back restores the light bit for bit.
  glm::vec3 apply(glm::vec3 towardLight) const {
    const glm::vec3 d = glm::normalize(towardLight);
    const float azimuth = std::atan2(d.x, d.z) + yaw;
    const float elevation = glm::clamp(std::asin(glm::clamp(d.y, -1.0f, 1.0f)) + pitch, -kMaxElevation, kMaxElevation);
    return {std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)};
  }
};

// "LIGHT AZ <degrees> EL <degrees>" of a direction towards the light: azimuth from +Z towards +X.
std::string lightLine(glm::vec3 towardLight) {
  char line[64];
  std::snprintf(line, sizeof(line), "LIGHT AZ %.0f EL %.0f", glm::degrees(std::atan2(towardLight.x, towardLight.z)),
                glm::degrees(std::asin(glm::clamp(towardLight.y, -1.0f, 1.0f))));
  return line;
}

struct InputState {
  OrbitCamera orbit;
  LightControl light;
  bool lightChanged = false;  ///< print the new angles once
  bool paused = false;
  bool stepOnce = false;
  // Post-processing toggles over the scene's own settings: T Reinhard/linear, G glow, A auto gain,
  // R god rays.
  bool flipToneMapping = false;
  bool flipGodRays = false;
  bool flipGlow = false;
  bool flipAutoGain = false;
  // Technique toggles over the scene's static settings (K skin diffusion, H hair shadow maps): they
  // take a new Renderer::setScene, made when `techniquesChanged` is set.
  bool flipSkinDiffusion = false;
  bool flipHairShadows = false;
  bool furShells = true;       // F: fur as shells and fins, or the bare body with its photo
  bool surfaceShadows = true;  // S: the surfaces' soft shadows from the key light
  bool techniquesChanged = false;
  bool announceTechniques = false;  // print the technique line with the next frame (K, H, S)
  bool showOverlay = true;  // O
  // Characters: C plays each one's next clip, E blends in its next expression.
  bool nextClip = false;
  bool nextExpression = false;
  bool fireCannon = false;  // B: the ship's cannon
  float windFactor = 1.0f;  // W / Q: the sea's wind stronger / calmer by kWindStep, applied once
};

constexpr float kWindStep = 1.25f;

// What a key does; the window's key callback and --press both come here.
void press(GLFWwindow* window, InputState& state, int key) {
  switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
    case GLFW_KEY_SPACE: state.paused = !state.paused; break;
    case GLFW_KEY_N: state.stepOnce = true; break;
    case GLFW_KEY_T: state.flipToneMapping = !state.flipToneMapping; break;
    case GLFW_KEY_G: state.flipGlow = !state.flipGlow; break;
    case GLFW_KEY_A: state.flipAutoGain = !state.flipAutoGain; break;
    case GLFW_KEY_R: state.flipGodRays = !state.flipGodRays; break;
    case GLFW_KEY_K:
      state.flipSkinDiffusion = !state.flipSkinDiffusion;
      state.techniquesChanged = state.announceTechniques = true;
      break;
    case GLFW_KEY_H:
      state.flipHairShadows = !state.flipHairShadows;
      state.techniquesChanged = state.announceTechniques = true;
      break;
    case GLFW_KEY_O: state.showOverlay = !state.showOverlay; break;
    case GLFW_KEY_F: state.furShells = !state.furShells; break;
    case GLFW_KEY_S:
      state.surfaceShadows = !state.surfaceShadows;
      state.announceTechniques = true;
      break;
    case GLFW_KEY_C: state.nextClip = true; break;
    case GLFW_KEY_E: state.nextExpression = true; break;
    case GLFW_KEY_B: state.fireCannon = true; break;
    case GLFW_KEY_W: state.windFactor *= kWindStep; break;
    case GLFW_KEY_Q: state.windFactor /= kWindStep; break;
    case GLFW_KEY_J:
    case GLFW_KEY_L:
      state.light.yaw += (key == GLFW_KEY_L ? 1.0f : -1.0f) * LightControl::kYawStep;
      state.lightChanged = true;
      break;
    case GLFW_KEY_I:
    case GLFW_KEY_M:
      state.light.pitch += (key == GLFW_KEY_I ? 1.0f : -1.0f) * LightControl::kPitchStep;
      state.lightChanged = true;
      break;
    default: break;
  }
}

// The GLFW key of a character of --press: letters (either case) and space.
std::optional<int> keyOf(char character) {
  if (character >= 'a' && character <= 'z') return GLFW_KEY_A + (character - 'a');
  if (character >= 'A' && character <= 'Z') return GLFW_KEY_A + (character - 'A');
  if (character == ' ') return GLFW_KEY_SPACE;
  return std::nullopt;
}

// The scene's static settings with the technique toggles applied: every skin material's diffusion
// flipped (K), the hair shadows flipped between opacity shadow maps and deep opacity maps (H; a
// scene without hair shadows gets opacity shadow maps).
render::StaticScene withTechniques(render::StaticScene scene, const InputState& input) {
  if (input.flipSkinDiffusion)
    for (render::MaterialData& material : scene.materials)
      if (material.shading == render::SurfaceShading::kSkin)
        material.skin.diffusion = material.skin.diffusion == render::SkinDiffusion::kTextureSpace
                                      ? render::SkinDiffusion::kPreintegrated
                                      : render::SkinDiffusion::kTextureSpace;
  if (input.flipHairShadows)
    scene.hairShadows.mode = scene.hairShadows.mode == render::HairShadowMode::kOpacityShadowMap
                                 ? render::HairShadowMode::kDeepOpacityMap
                                 : render::HairShadowMode::kOpacityShadowMap;
  return scene;
}

// The overlay's second line: each toggle's key and what it shows now, short.
std::string techniqueLine(const render::StaticScene& scene, const render::FrameInput& frame) {
  const render::PostSettings& post = frame.post;
  std::string skin = "-";
  for (const render::MaterialData& material : scene.materials)
    if (material.shading == render::SurfaceShading::kSkin) {
      skin = material.skin.diffusion == render::SkinDiffusion::kTextureSpace ? "TEXTURE" : "PRE";
      break;
    }
  const char* shadows = scene.grooms.empty()                                                  ? "-"
                        : scene.hairShadows.mode == render::HairShadowMode::kOpacityShadowMap ? "OSM"
                        : scene.hairShadows.mode == render::HairShadowMode::kDeepOpacityMap   ? "DEEP"
                                                                                              : "OFF";
  const auto onOff = [](bool on) { return on ? "ON" : "OFF"; };
  const std::string fur = scene.furs.empty() ? "-" : frame.furShells ? "SHELLS" : "BARE";
  return "K SKIN " + skin + "  H SHADOWS " + shadows + "  S SOFT " + onOff(frame.surfaceShadows) + "  F FUR " + fur +
         "  T " + (post.toneMapping == render::ToneMapping::kReinhard ? "REINHARD" : "LINEAR") + "  G GLOW " +
         onOff(post.glowStrength > 0.0f) + "  A GAIN " + onOff(post.autoGain) + "  R RAYS " +
         onOff(post.godRays > 0.0f);
}

// The scene's post settings with the viewer's toggles applied.
render::PostSettings toggled(render::PostSettings post, const InputState& input) {
  if (input.flipToneMapping)
    post.toneMapping = post.toneMapping == render::ToneMapping::kReinhard ? render::ToneMapping::kLinear
                                                                          : render::ToneMapping::kReinhard;
  // Timbury's glow mixes about half and half; a scene with its own strength toggles to none.
  if (input.flipGlow) post.glowStrength = post.glowStrength > 0.0f ? 0.0f : 0.4f;
  if (input.flipAutoGain) post.autoGain = !post.autoGain;
  if (input.flipGodRays) post.godRays = post.godRays > 0.0f ? 0.0f : 1.0f;
  return post;
}

void installCallbacks(GLFWwindow* window, InputState& input) {
  glfwSetWindowUserPointer(window, &input);
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    auto& state = *static_cast<InputState*>(glfwGetWindowUserPointer(w));
    if (button == GLFW_MOUSE_BUTTON_LEFT) state.orbit.dragging = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_RIGHT) state.light.dragging = action == GLFW_PRESS;
    glfwGetCursorPos(w, &state.orbit.lastX, &state.orbit.lastY);
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    auto& state = *static_cast<InputState*>(glfwGetWindowUserPointer(w));
    OrbitCamera& orbit = state.orbit;
    if (orbit.dragging) {
      orbit.yaw -= float(x - orbit.lastX) * 0.01f;
      orbit.pitch = glm::clamp(orbit.pitch + float(y - orbit.lastY) * 0.01f, -1.5f, 1.5f);
    }
    if (state.light.dragging) {
      state.light.yaw += float(x - orbit.lastX) * 0.01f;
      state.light.pitch -= float(y - orbit.lastY) * 0.01f;
      state.lightChanged = true;
    }
    orbit.lastX = x;
    orbit.lastY = y;
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    auto& orbit = static_cast<InputState*>(glfwGetWindowUserPointer(w))->orbit;
    orbit.distance = std::max(orbit.distance * std::pow(0.9f, float(dy)), 0.01f);
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_PRESS) press(w, *static_cast<InputState*>(glfwGetWindowUserPointer(w)), key);
  });
}

void run(const ViewOptions& options) {
  std::vector<int> scripted;
  for (char character : options.press) {
    const auto key = keyOf(character);
    if (!key) return failWith(std::string("--press: no key for '") + character + "' (letters and space only)");
    scripted.push_back(*key);
  }
  auto world = loadWorld(options.scene, {.strictGrooms = options.strict});
  if (!world) return failWith(world.error().message);
  const auto width = static_cast<std::uint32_t>(world->scene().output.width);
  const auto height = static_cast<std::uint32_t>(world->scene().output.height);

  auto window = render::Window::open("mane — " + world->scene().name, width, height);
  if (!window) return failWith(window.error().message);
  render::DeviceSettings deviceSettings = render::deviceSettingsFromEnvironment();
  deviceSettings.instanceExtensions = (*window)->requiredInstanceExtensions();
  deviceSettings.presentation = true;
  auto device = render::Device::create(deviceSettings);
  if (!device) return failWith(device.error().message);
  auto swapchain = render::Swapchain::create(**device, **window);
  if (!swapchain) return failWith(swapchain.error().message);
  auto renderer = render::Renderer::create(**device, {.extent = {width, height}, .msaaSamples = options.msaa});
  if (!renderer) return failWith(renderer.error().message);
  auto loop = scenes::FrameLoop::create(*world, **renderer, {.imageSize = {width, height}, .threads = options.threads});
  if (!loop) return failWith(loop.error().message);
  render::StaticScene drawn = world->staticScene();
  if (auto set = loop->setScene(drawn); !set) return failWith(set.error().message);
  std::cout << kKeyHelp << '\n';

  InputState input;
  input.orbit = OrbitCamera::from(world->frameInput().camera);
  installCallbacks((*window)->handle(), input);

  auto last = std::chrono::steady_clock::now();
  double smoothedMs = 0.0;
  const render::TextOverlaySettings overlay{.scale = width >= 960 ? 2u : 1u};
  for (int frame = 0; !(*window)->shouldClose() && (options.frames == 0 || frame < options.frames); ++frame) {
    glfwPollEvents();
    if (frame >= 1 && std::size_t(frame - 1) < scripted.size())
      press((*window)->handle(), input, scripted[std::size_t(frame - 1)]);
    if (input.windFactor != 1.0f) {
      if (const scenes::SceneOcean* ocean = world->ocean()) {
        const float speed = std::clamp(ocean->windSpeed() * input.windFactor, 2.0f, 30.0f);
        if (auto set = world->setWindSpeed(speed); !set) return failWith(set.error().message);
        std::cout << "wind " << speed << " m/s\n";
        input.techniquesChanged = true;  // the renderer takes the new waves below
      } else {
        std::cout << "the scene has no sea\n";
      }
      input.windFactor = 1.0f;
    }
    if (input.techniquesChanged) {
      // New passes and maps for the switched techniques; the frame in flight must not use the old
      // ones.
      input.techniquesChanged = false;
      (*device)->device().waitIdle();
      drawn = withTechniques(world->staticScene(), input);
      if (auto set = loop->setScene(drawn); !set) return failWith(set.error().message);
    }
    // Over half a second: quick enough to follow the key, slow enough to see the blend.
    constexpr float kCharacterBlendSeconds = 0.5f;
    if (input.nextClip) std::cout << "clips: " << world->playNextClips(kCharacterBlendSeconds) << '\n';
    if (input.nextExpression) std::cout << "expressions: " << world->nextExpression(kCharacterBlendSeconds) << '\n';
    if (input.fireCannon) std::cout << (world->fireCannon() ? "cannon fired\n" : "the scene has no cannon\n");
    input.nextClip = input.nextExpression = input.fireCannon = false;
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    smoothedMs = frame == 0 ? dt * 1e3 : 0.9 * smoothedMs + 0.1 * dt * 1e3;
    if (!input.paused || input.stepOnce) {
      // Real time, capped so a slow frame (lavapipe) plays in slow motion rather than jumping.
      if (auto advanced = loop->advance(std::min(dt, 1.0 / 30.0)); !advanced) return failWith(advanced.error().message);
      input.stepOnce = false;
    }
    render::FrameInput frameInput = world->frameInput();
    frameInput.camera.position = input.orbit.position();
    frameInput.camera.target = input.orbit.target;
    frameInput.post = toggled(frameInput.post, input);
    frameInput.post.frameSeconds = float(dt);
    frameInput.furShells = input.furShells;
    frameInput.surfaceShadows = input.surfaceShadows;
    if (input.announceTechniques) std::cout << techniqueLine(drawn, frameInput) << '\n';
    input.announceTechniques = false;
    if (!frameInput.lights.empty()) {
      frameInput.lights[0].direction = input.light.apply(frameInput.lights[0].direction);
      if (input.lightChanged) std::cout << lightLine(frameInput.lights[0].direction) << '\n';
    }
    input.lightChanged = false;
    // Subdivided meshes follow the camera (and their own motion), but not while the orbit is being
    // dragged: a re-tessellation can rebuild a voxel translucency table (seconds).
    auto rendered = loop->renderFrame(
        frameInput, input.orbit.dragging ? scenes::Refinement::kKeep : scenes::Refinement::kForCamera);
    if (!rendered) return failWith(rendered.error().message);
    if (input.showOverlay) {
      // From the first pass's begin to the last one's end (render::PassTiming).
      double gpuMs = 0.0;
      for (const render::PassTiming& t : *rendered) gpuMs = std::max(gpuMs, t.startMilliseconds + t.milliseconds);
      const std::string light = frameInput.lights.empty() ? "" : "  " + lightLine(frameInput.lights[0].direction);
      char timing[128];
      std::snprintf(timing, sizeof(timing), "%.1f MS/FRAME  GPU %.1f MS%s%s", smoothedMs, gpuMs, light.c_str(),
                    input.paused ? "  PAUSED" : "");
      const std::vector<std::string> lines{timing, techniqueLine(drawn, frameInput)};
      const render::TextLayout layout = render::layoutText(lines, overlay, {width, height});
      (*device)->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
        render::recordTextOverlay(commands, (*renderer)->target().output(), layout, overlay);
      });
    }
    if (auto presented = (*swapchain)->present((*renderer)->target().output()); !presented)
      return failWith(presented.error().message);
    char title[160];
    std::snprintf(title, sizeof(title), "mane — %s — %.1f ms/frame%s", world->scene().name.c_str(), smoothedMs,
                  input.paused ? " (paused)" : "");
    glfwSetWindowTitle((*window)->handle(), title);
  }
  (*device)->device().waitIdle();
  if (!options.screenshot.empty()) {
    auto pixels = (*renderer)->readOutput();
    if (!pixels) return failWith(pixels.error().message);
    if (auto written = render::writePng(options.screenshot, width, height, *pixels); !written)
      return failWith(written.error().message);
    std::cout << "wrote " << options.screenshot << '\n';
  }
  if (checkValidation(**device)) succeed();
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto options = std::make_shared<ViewOptions>();
  auto* command =
      app.add_subcommand("view", "Open the scene in a window: drag to orbit, wheel to zoom, Space to pause");
  command->add_option("scene", options->scene, "Scene file (JSON)")->capture_default_str();
  command->add_option("--frames", options->frames, "Close after this many frames (0: when the window closes)")
      ->check(CLI::Range(0, 10000000));
  command->add_option("--screenshot", options->screenshot, "Write the last frame to this PNG file before closing");
  command->add_option("--msaa", options->msaa, "Samples per pixel (1 or 4)")
      ->check(CLI::IsMember({1u, 4u}))
      ->capture_default_str();
  command->add_flag("--strict", options->strict, kStrictGroomsHelp);
  command->add_option("--threads", options->threads, "Simulation threads")
      ->check(CLI::Range(1u, 64u))
      ->capture_default_str();
  command->add_option("--press", options->press,
                      "Keys pressed one per frame from the second frame on, as if typed (e.g. KH: texture-space "
                      "skin, then deep opacity maps); for scripted runs");
  command->footer(kKeyHelp);
  command->callback([options] { run(*options); });
}

}  // namespace mane::app
