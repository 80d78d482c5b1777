// A program outside the mane source tree that uses mane's physics, as another project would:
// grow a small groom, bob the head it hangs from for one second, print the state hash.
// Built three ways by the test suite (tests/packaging/): against an installed mane through
// find_package, with mane's sources through add_subdirectory, and through pkg-config. All three
// print the same hash.

#include <cstdio>
#include <cstdlib>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <mane/physics/groom_generator.hpp>
#include <mane/physics/hair.hpp>

int main() {
  using namespace mane::physics;

  GroomSettings groom;
  groom.seed = 11;
  groom.strandCount = 16;
  groom.particlesPerStrand = 10;
  groom.strandLength = 0.2f;  // metres
  auto strands = generateGroom(groom);
  if (!strands) {
    std::fprintf(stderr, "embed_physics: groom: %s\n", strands.error().message.c_str());
    return EXIT_FAILURE;
  }

  HairSettings settings;  // default solver: 1/120 s steps, gravity along −Y; the built-in pool
  settings.strands = std::move(*strands);
  auto hair = HairSystem::create(settings);
  if (!hair) {
    std::fprintf(stderr, "embed_physics: hair: %s\n", hair.error().message.c_str());
    return EXIT_FAILURE;
  }

  // The head rises 5 cm and comes back down over the second. Plain arithmetic, no libm, so the
  // hash is the same wherever the program is built.
  constexpr int kFrames = 60;
  constexpr double kFrameDt = 1.0 / 60.0;  // seconds
  for (int frame = 1; frame <= kFrames; ++frame) {
    const float phase = static_cast<float>(frame) / kFrames;             // 0..1
    const float height = 0.1f * (phase < 0.5f ? phase : 1.0f - phase);  // metres
    const glm::mat4 head = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, height, 0.0f));
    if (auto ok = hair->setHeadTransform(head); !ok) {
      std::fprintf(stderr, "embed_physics: head: %s\n", ok.error().message.c_str());
      return EXIT_FAILURE;
    }
    if (auto ok = hair->advance(kFrameDt); !ok) {
      std::fprintf(stderr, "embed_physics: advance: %s\n", ok.error().message.c_str());
      return EXIT_FAILURE;
    }
  }

  std::printf("%zu strands, %llu steps\n", hair->strandCount(), static_cast<unsigned long long>(hair->stepCount()));
  std::printf("state hash: %016llx\n", static_cast<unsigned long long>(hair->stateHash()));
  return EXIT_SUCCESS;
}
