// The task interface (task_runner.hpp) and the built-in pool (thread_pool.hpp): every task of a
// batch runs exactly once whoever runs it, and a runner that fails is reported by the call that
// used it while the state stays the one a working runner gives.

#include <atomic>
#include <thread>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/cloth.hpp"
#include "physics/groom_generator.hpp"
#include "physics/hair.hpp"
#include "physics/interpolation.hpp"
#include "physics/thread_pool.hpp"
#include "tests/support/host_task_runner.hpp"

namespace mane::physics {
namespace {

using ::testing::HasSubstr;

// Runs a batch of `count` tasks on `runner`, counting each task's calls.
std::vector<int> callsPerTask(const TaskRunner& runner, std::uint32_t count) {
  std::vector<std::atomic<int>> calls(count);
  const TaskFunction task = [&](std::uint32_t t) { calls[t].fetch_add(1); };
  auto group = runner.enqueue(count, task);
  EXPECT_TRUE(group);
  EXPECT_TRUE(runner.wait(*group));
  std::vector<int> result;
  for (const auto& c : calls) result.push_back(c.load());
  return result;
}

TEST(ThreadPool, RunsEveryTaskOnceForOneTwoAndFourWorkers) {
  for (unsigned workers : {1u, 2u, 4u}) {
    ThreadPool pool(workers);
    EXPECT_EQ(pool.workerCount(), workers);
    const TaskRunner runner = pool.runner();
    EXPECT_EQ(runner.concurrency, workers);
    if (workers == 1) {
      EXPECT_FALSE(runner.hasCallbacks());  // the calling thread runs everything
      continue;
    }
    for (int batch = 0; batch < 200; ++batch)
      EXPECT_EQ(callsPerTask(runner, 37), std::vector<int>(37, 1)) << workers << " workers, batch " << batch;
  }
}

TEST(ThreadPool, BatchesFromSeveralThreadsShareOnePool) {
  ThreadPool pool(3);
  const TaskRunner runner = pool.runner();
  std::atomic<int> wrong{0};
  {
    std::vector<std::jthread> callers;
    for (int c = 0; c < 4; ++c)
      callers.emplace_back([&] {
        for (int batch = 0; batch < 100; ++batch)
          if (callsPerTask(runner, 16) != std::vector<int>(16, 1)) wrong.fetch_add(1);
      });
  }
  EXPECT_EQ(wrong.load(), 0);
}

std::vector<std::vector<glm::vec3>> groom(std::size_t strands) {
  GroomSettings settings;
  settings.seed = 33;
  settings.strandCount = strands;
  settings.particlesPerStrand = 12;
  return *generateGroom(settings);
}

// Three frames of a swaying head on `runner`; the state hash, and the first error if any.
std::pair<std::uint64_t, std::string> runHair(const TaskRunner& runner) {
  HairSettings settings;
  settings.strands = groom(200);
  settings.tasks = runner;
  auto hair = HairSystem::create(settings);
  EXPECT_TRUE(hair);
  std::string firstError;
  for (int frame = 1; frame <= 3; ++frame) {
    EXPECT_TRUE(hair->setHeadTransform(glm::translate(glm::mat4(1.0f), glm::vec3(0.01f * frame, 0.0f, 0.0f))));
    if (auto advanced = hair->advance(1.0 / 60.0); !advanced && firstError.empty())
      firstError = advanced.error().message;
  }
  return {hair->stateHash(), firstError};
}

TEST(TaskRunnerFailure, ARefusingRunnerIsAnErrorAndTheHairStateStaysRight) {
  const auto [reference, none] = runHair(builtInTaskRunner(1));
  EXPECT_EQ(none, "");
  const auto [hash, error] = runHair(test::refusingRunner());
  EXPECT_THAT(error, HasSubstr("Hair system: the task runner could not start 4 tasks: the host's job queue is full"));
  EXPECT_EQ(hash, reference);
}

TEST(TaskRunnerFailure, ARunnerThatDropsTasksIsAnErrorAndTheHairStateStaysRight) {
  const auto [reference, none] = runHair(builtInTaskRunner(1));
  const auto [hash, error] = runHair(test::droppingRunner());
  EXPECT_THAT(error, HasSubstr("returned from wait with 3 of 4 tasks not run"));
  EXPECT_EQ(hash, reference);
}

TEST(TaskRunnerFailure, ClothAndInterpolationReportAFailingRunnerToo) {
  // Cloth splits its loops only above 4,096 particles per task: a 91 × 91 grid gets 2.
  ClothSettings cloth;
  constexpr int kSide = 91;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) cloth.positions.push_back({0.01f * float(i), -0.01f * float(j), 0.0f});
  for (int j = 0; j + 1 < kSide; ++j)
    for (int i = 0; i + 1 < kSide; ++i) {
      const auto a = static_cast<std::uint32_t>(j * kSide + i), b = a + 1, c = a + kSide, d = c + 1;
      cloth.triangles.insert(cloth.triangles.end(), {a, c, b, b, c, d});
    }
  cloth.pinnedVertices = {0, kSide - 1};
  cloth.tasks = builtInTaskRunner(1);
  auto reference = Cloth::create(cloth);
  ASSERT_TRUE(reference);
  ASSERT_TRUE(reference->advance(1.0 / 60.0));
  cloth.tasks = test::droppingRunner();
  auto dropped = Cloth::create(cloth);
  ASSERT_TRUE(dropped);
  auto advanced = dropped->advance(1.0 / 60.0);
  ASSERT_FALSE(advanced);
  EXPECT_THAT(advanced.error().message, HasSubstr("cloth: the task runner returned from wait with 1 of 2 tasks"));
  EXPECT_EQ(dropped->stateHash(), reference->stateHash());

  InterpolationSettings dense;
  dense.restGuides = groom(20);
  dense.groom.strandCount = 100;
  dense.tasks = test::refusingRunner();
  auto interpolator = DenseStrandInterpolator::create(dense);
  ASSERT_TRUE(interpolator);
  std::vector<glm::vec3> guides;
  for (const auto& strand : dense.restGuides) guides.insert(guides.end(), strand.begin(), strand.end());
  std::vector<glm::vec3> expected(interpolator->layout().vertexTotal()), got(expected.size());
  ASSERT_TRUE(interpolateDenseStrands(guides, interpolator->layout(), expected, {}, 1u));
  auto filled = interpolator->interpolate(guides, got);
  ASSERT_FALSE(filled);
  EXPECT_THAT(filled.error().message, HasSubstr("Dense groom: the task runner could not start"));
  EXPECT_EQ(got, expected);
}

}  // namespace
}  // namespace mane::physics
