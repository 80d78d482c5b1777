// Embedding mane_physics: generate a small groom, attach it to a nodding head, simulate one
// second at 60 frames per second on two threads, and print the tip positions and the state hash.
// Uses nothing but mane_physics (GLM and the standard library).

#include <cstdio>
#include <cstdlib>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"

int main() {
  using namespace mane::physics;

  GroomSettings groom;
  groom.seed = 7;
  groom.strandCount = 8;
  groom.particlesPerStrand = 12;
  groom.strandLength = 0.3f;  // metres
  auto strands = generateGroom(groom);
  if (!strands) {
    std::fprintf(stderr, "groom: %s\n", strands.error().message.c_str());
    return EXIT_FAILURE;
  }

  HairSettings settings;  // solver: 1/120 s steps, gravity −9.81 m/s² along Y, 4 iterations
  settings.strands = std::move(*strands);
  settings.tasks = builtInTaskRunner(2);  // or a TaskRunner over the host engine's own workers
  auto hair = HairSystem::create(settings);
  if (!hair) {
    std::fprintf(stderr, "hair: %s\n", hair.error().message.c_str());
    return EXIT_FAILURE;
  }

  // The head slides sideways and back once over the second: a triangle wave built from exact
  // arithmetic (no libm), so the printed hash is the same on every platform.
  constexpr int kFrames = 60;
  constexpr double kFrameDt = 1.0 / 60.0;
  for (int frame = 1; frame <= kFrames; ++frame) {
    const float phase = static_cast<float>(frame) / kFrames;            // 0..1
    const float offset = 0.1f * (phase < 0.5f ? phase : 1.0f - phase);  // metres
    const glm::mat4 head = glm::translate(glm::mat4(1.0f), glm::vec3(offset, 0.0f, 0.0f));
    if (auto ok = hair->setHeadTransform(head); !ok) {
      std::fprintf(stderr, "head: %s\n", ok.error().message.c_str());
      return EXIT_FAILURE;
    }
    if (auto ok = hair->advance(kFrameDt); !ok) {
      std::fprintf(stderr, "advance: %s\n", ok.error().message.c_str());
      return EXIT_FAILURE;
    }
  }

  std::printf("simulated %.4f s in %llu fixed steps\n", hair->simulatedTime(),
              static_cast<unsigned long long>(hair->stepCount()));
  for (std::size_t s = 0; s < hair->strandCount(); ++s) {
    const glm::vec3 tip = hair->strandPositions(s).back();
    std::printf("strand %zu tip: (%+.6f, %+.6f, %+.6f) m\n", s, static_cast<double>(tip.x), static_cast<double>(tip.y),
                static_cast<double>(tip.z));
  }
  std::printf("state hash: %016llx\n", static_cast<unsigned long long>(hair->stateHash()));
  return EXIT_SUCCESS;
}
