// The frame graph's barriers (render/frame_graph.hpp), on the CPU: passes declared over made-up
// buffer and image handles, no device. The expected barriers come from Vulkan's synchronization
// rules stated case by case, and, for random sequences of uses, from an independent checker of
// those rules: every hazard between two uses (read after write, write after write, write after
// read, a layout change) is ordered by a chain of the derived barriers, every use finds the
// image in its layout, and no derived barrier can be left out without breaking one of these.

#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "render/frame_graph.hpp"

namespace mane::render {
namespace {

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

constexpr PassName kPass("pass");

GraphResource fakeBuffer(std::uintptr_t handle) {
  return GraphResource(vk::Buffer(reinterpret_cast<VkBuffer>(handle)));
}

GraphResource fakeImage(std::uintptr_t handle, vk::ImageAspectFlags aspect = vk::ImageAspectFlagBits::eColor) {
  return GraphResource(vk::Image(reinterpret_cast<VkImage>(handle)), {aspect, 0, 1, 0, 1});
}

const PassCommands kNothing = [](const vk::raii::CommandBuffer&) {};

// Passes that use one resource one way, added after the others.
void reads(FrameGraph& graph, const GraphResource& resource, const ResourceUse& use) {
  graph.addPass(
      kPass, [&](FrameGraph::Builder& pass) { pass.read(resource, use); }, kNothing);
}

void writes(FrameGraph& graph, const GraphResource& resource, const ResourceUse& use,
            Contents contents = Contents::kKeep) {
  graph.addPass(
      kPass, [&](FrameGraph::Builder& pass) { pass.write(resource, use, contents); }, kNothing);
}

void produces(FrameGraph& graph, const GraphResource& resource, const ResourceUse& readyFor) {
  graph.addPass(
      kPass, [&](FrameGraph::Builder& pass) { pass.produce(resource, readyFor); }, kNothing);
}

// The barrier every resource's first use gets: anything before the frame may have used it.
constexpr vk::PipelineStageFlags2 kEarlier = Stage::eAllCommands;

TEST(FrameGraph, FirstUseWaitsForEveryEarlierCommand) {
  FrameGraph graph;
  const GraphResource buffer = fakeBuffer(1);
  reads(graph, buffer, ResourceUse::vertexInput());
  graph.compile();
  ASSERT_EQ(graph.barriersBefore(0).size(), 1u);
  const GraphBarrier& barrier = graph.barriersBefore(0)[0];
  EXPECT_EQ(barrier.resource, buffer);
  EXPECT_EQ(barrier.srcStages, kEarlier);
  EXPECT_EQ(barrier.srcAccess, vk::AccessFlags2(Access::eMemoryWrite));
  EXPECT_EQ(barrier.dstStages, vk::PipelineStageFlags2(Stage::eVertexAttributeInput));
  EXPECT_EQ(barrier.dstAccess, vk::AccessFlags2(Access::eVertexAttributeRead));
}

TEST(FrameGraph, ReadAfterWriteWaitsForTheWriteAndMakesItVisibleToTheRead) {
  FrameGraph graph;
  const GraphResource positions = fakeBuffer(1);
  writes(graph, positions, ResourceUse::storageWrite(Stage::eComputeShader));
  reads(graph, positions, ResourceUse::storageRead(Stage::eVertexShader));
  graph.compile();
  ASSERT_EQ(graph.barriersBefore(1).size(), 1u);
  const GraphBarrier& barrier = graph.barriersBefore(1)[0];
  EXPECT_EQ(barrier.srcStages, vk::PipelineStageFlags2(Stage::eComputeShader));
  EXPECT_EQ(barrier.srcAccess, vk::AccessFlags2(Access::eShaderStorageWrite));  // the write alone, not its reads
  EXPECT_EQ(barrier.dstStages, vk::PipelineStageFlags2(Stage::eVertexShader));
  EXPECT_EQ(barrier.dstAccess, vk::AccessFlags2(Access::eShaderStorageRead));
}

TEST(FrameGraph, ReadsOfAWriteAlreadyMadeVisibleToThemNeedNoBarrier) {
  FrameGraph graph;
  const GraphResource positions = fakeBuffer(1);
  writes(graph, positions, ResourceUse::storageWrite(Stage::eComputeShader));
  reads(graph, positions, ResourceUse::storageRead(Stage::eVertexShader | Stage::eComputeShader));
  reads(graph, positions, ResourceUse::storageRead(Stage::eComputeShader));
  // Another stage: the write has not been made visible there yet.
  reads(graph, positions, ResourceUse::storageRead(Stage::eFragmentShader));
  graph.compile();
  EXPECT_EQ(graph.barriersBefore(1).size(), 1u);
  EXPECT_TRUE(graph.barriersBefore(2).empty());
  ASSERT_EQ(graph.barriersBefore(3).size(), 1u);
  const GraphBarrier& barrier = graph.barriersBefore(3)[0];
  // From the write, and from the reads after the barrier that the later barriers chain on.
  EXPECT_TRUE(barrier.srcStages & Stage::eComputeShader);
  EXPECT_EQ(barrier.srcAccess, vk::AccessFlags2(Access::eShaderStorageWrite));
  EXPECT_EQ(barrier.dstStages, vk::PipelineStageFlags2(Stage::eFragmentShader));
}

TEST(FrameGraph, WriteAfterReadsWaitsForTheReadsWithoutMakingAnythingAvailable) {
  FrameGraph graph;
  const GraphResource radiance = fakeBuffer(1);
  writes(graph, radiance, ResourceUse::storageWrite(Stage::eComputeShader));
  reads(graph, radiance, ResourceUse::vertexInput());
  writes(graph, radiance, ResourceUse::storageWrite(Stage::eComputeShader));
  graph.compile();
  ASSERT_EQ(graph.barriersBefore(2).size(), 1u);
  const GraphBarrier& barrier = graph.barriersBefore(2)[0];
  EXPECT_EQ(barrier.srcStages, vk::PipelineStageFlags2(Stage::eVertexAttributeInput));
  EXPECT_EQ(barrier.srcAccess, vk::AccessFlags2());  // an execution dependency: reads leave nothing to flush
  EXPECT_EQ(barrier.dstStages, vk::PipelineStageFlags2(Stage::eComputeShader));
}

TEST(FrameGraph, AnImageUsedInAnotherLayoutIsTransitioned) {
  FrameGraph graph;
  const GraphResource colour = fakeImage(1);
  writes(graph, colour, ResourceUse::colorAttachment(), Contents::kDiscard);
  reads(graph, colour, ResourceUse::sampled(Stage::eComputeShader));
  reads(graph, colour, ResourceUse::sampled(Stage::eFragmentShader));
  graph.leaveAs(colour, ResourceUse::transferSource());
  graph.compile();
  // Discarded: from UNDEFINED, after every earlier command.
  ASSERT_EQ(graph.barriersBefore(0).size(), 1u);
  EXPECT_EQ(graph.barriersBefore(0)[0].oldLayout, Layout::eUndefined);
  EXPECT_EQ(graph.barriersBefore(0)[0].newLayout, Layout::eColorAttachmentOptimal);
  EXPECT_EQ(graph.barriersBefore(0)[0].srcStages, kEarlier);
  ASSERT_EQ(graph.barriersBefore(1).size(), 1u);
  const GraphBarrier& toSampled = graph.barriersBefore(1)[0];
  EXPECT_EQ(toSampled.oldLayout, Layout::eColorAttachmentOptimal);
  EXPECT_EQ(toSampled.newLayout, Layout::eShaderReadOnlyOptimal);
  EXPECT_EQ(toSampled.srcStages, vk::PipelineStageFlags2(Stage::eColorAttachmentOutput));
  EXPECT_EQ(toSampled.srcAccess, vk::AccessFlags2(Access::eColorAttachmentWrite));
  EXPECT_EQ(toSampled.dstStages, vk::PipelineStageFlags2(Stage::eComputeShader));
  EXPECT_EQ(toSampled.dstAccess, vk::AccessFlags2(Access::eShaderSampledRead));
  // Same layout, but the write is not visible to fragment shaders yet: a barrier, no transition.
  ASSERT_EQ(graph.barriersBefore(2).size(), 1u);
  EXPECT_EQ(graph.barriersBefore(2)[0].oldLayout, Layout::eShaderReadOnlyOptimal);
  EXPECT_EQ(graph.barriersBefore(2)[0].newLayout, Layout::eShaderReadOnlyOptimal);
  EXPECT_EQ(graph.barriersBefore(2)[0].dstStages, vk::PipelineStageFlags2(Stage::eFragmentShader));
  // After the last pass, for the copy: it waits for the fragment shaders, and through the
  // barrier before them (which waited for the compute shaders) for the compute shaders.
  ASSERT_EQ(graph.barriersAfter().size(), 1u);
  const GraphBarrier& toCopy = graph.barriersAfter()[0];
  EXPECT_EQ(toCopy.oldLayout, Layout::eShaderReadOnlyOptimal);
  EXPECT_EQ(toCopy.newLayout, Layout::eTransferSrcOptimal);
  EXPECT_TRUE(toCopy.srcStages & Stage::eFragmentShader);
  EXPECT_TRUE(graph.barriersBefore(2)[0].srcStages & Stage::eComputeShader);
  EXPECT_EQ(toCopy.dstStages, vk::PipelineStageFlags2(Stage::eTransfer));
}

TEST(FrameGraph, AnImageFirstReadIsTakenToRestInThatLayout) {
  FrameGraph graph;
  const GraphResource map = fakeImage(1, vk::ImageAspectFlagBits::eDepth);
  reads(graph, map, ResourceUse::sampled(Stage::eFragmentShader));
  graph.compile();
  ASSERT_EQ(graph.barriersBefore(0).size(), 1u);
  EXPECT_EQ(graph.barriersBefore(0)[0].oldLayout, Layout::eShaderReadOnlyOptimal);
  EXPECT_EQ(graph.barriersBefore(0)[0].newLayout, Layout::eShaderReadOnlyOptimal);
  EXPECT_EQ(graph.barriersBefore(0)[0].resource.range().aspectMask,
            vk::ImageAspectFlags(vk::ImageAspectFlagBits::eDepth));
}

TEST(FrameGraph, AProducedResourceNeedsNoBarrierForTheUsesItWasLeftReadyFor) {
  FrameGraph graph;
  const GraphResource map = fakeImage(1);
  produces(graph, map, ResourceUse::sampled(Stage::eFragmentShader | Stage::eComputeShader));
  reads(graph, map, ResourceUse::sampled(Stage::eComputeShader));
  reads(graph, map, ResourceUse::sampled(Stage::eVertexShader));
  graph.compile();
  EXPECT_TRUE(graph.barriersBefore(0).empty()) << "the pass synchronises it itself";
  EXPECT_TRUE(graph.barriersBefore(1).empty());
  ASSERT_EQ(graph.barriersBefore(2).size(), 1u) << "a stage the pass did not make it visible to";
  EXPECT_EQ(graph.barriersBefore(2)[0].dstStages, vk::PipelineStageFlags2(Stage::eVertexShader));
}

TEST(FrameGraph, APassUsingAResourceTwiceGetsOneBarrierForBothUses) {
  FrameGraph graph;
  const GraphResource positions = fakeBuffer(1);
  const GraphResource depth = fakeImage(2, vk::ImageAspectFlagBits::eDepth);
  graph.addPass(
      kPass,
      [&](FrameGraph::Builder& pass) {
        pass.write(positions, ResourceUse::storageWrite(Stage::eComputeShader));
        pass.write(depth, ResourceUse::depthAttachment(), Contents::kDiscard);
      },
      kNothing);
  graph.addPass(
      kPass,
      [&](FrameGraph::Builder& pass) {
        pass.read(positions, ResourceUse::storageRead(Stage::eVertexShader));
        pass.read(positions, ResourceUse::vertexInput());
        pass.write(depth, ResourceUse::depthAttachment());
      },
      kNothing);
  graph.compile();
  ASSERT_EQ(graph.barriersBefore(1).size(), 2u);
  const GraphBarrier& both = graph.barriersBefore(1)[0];
  EXPECT_EQ(both.resource, positions);
  EXPECT_EQ(both.dstStages, Stage::eVertexShader | Stage::eVertexAttributeInput);
  EXPECT_EQ(both.dstAccess, Access::eShaderStorageRead | Access::eVertexAttributeRead);
  const GraphBarrier& kept = graph.barriersBefore(1)[1];
  EXPECT_EQ(kept.resource, depth);
  EXPECT_EQ(kept.oldLayout, Layout::eDepthAttachmentOptimal) << "kept, not discarded";
  EXPECT_EQ(kept.srcAccess, vk::AccessFlags2(Access::eDepthStencilAttachmentWrite));
}

TEST(FrameGraph, ProgrammingErrorsThrow) {
  FrameGraph graph;
  const GraphResource image = fakeImage(1);
  EXPECT_THROW(graph.addPass(
                   kPass,
                   [&](FrameGraph::Builder& pass) {
                     pass.read(image, ResourceUse::colorAttachment());  // a write declared as a read
                   },
                   kNothing),
               std::logic_error);
  graph.reset();
  EXPECT_THROW(graph.addPass(
                   kPass,
                   [&](FrameGraph::Builder& pass) {
                     pass.read(image, ResourceUse::sampled(Stage::eFragmentShader));
                     pass.write(image, ResourceUse::colorAttachment());  // two layouts in one pass
                   },
                   kNothing),
               std::logic_error);
  graph.reset();
  graph.leaveAs(image, ResourceUse::transferSource());
  EXPECT_THROW(graph.addPass(
                   kPass, [](FrameGraph::Builder&) {}, kNothing),
               std::logic_error);
}

// ---- Random sequences against an independent checker of Vulkan's rules ----

struct Access1 {  // one use of one resource by one pass
  std::size_t pass;
  ResourceUse use;
  bool write;
  bool discard;
};

struct Placed {  // a derived barrier, and where: before pass `pass` (passCount: after the last)
  std::size_t pass;
  GraphBarrier barrier;
};

// One end of an ordering: a use (its position, stages and what it needs made available or
// visible), or one of the barriers itself (a layout transition).
struct End {
  double position;
  vk::PipelineStageFlags2 stages;
  vk::AccessFlags2 access;
  std::optional<std::size_t> barrier;
};

// Whether a chain of `barriers` orders `from` before `to`: its first barrier comes after `from`
// and covers its stage (making its writes available), each next one comes later and waits for
// a stage the previous one waited with, and the last comes no later than `to` and covers its
// stage and accesses. Barriers of one place do not chain with each other.
bool chained(const std::vector<Placed>& barriers, const End& from, const End& to) {
  std::vector<bool> reached(barriers.size(), false);
  for (std::size_t i = 0; i < barriers.size(); ++i) {
    const Placed& b = barriers[i];
    if (double(b.pass) <= from.position && from.barrier != i) continue;
    if (double(b.pass) > to.position) break;
    if (from.barrier)
      reached[i] = i == *from.barrier;
    else
      reached[i] =
          (b.barrier.srcStages & from.stages) == from.stages && (b.barrier.srcAccess & from.access) == from.access;
    for (std::size_t j = 0; j < i && !reached[i]; ++j)
      reached[i] = reached[j] && barriers[j].pass < b.pass && bool(barriers[j].barrier.dstStages & b.barrier.srcStages);
    if (!reached[i]) continue;
    if (to.barrier ? i == *to.barrier
                   : (b.barrier.dstStages & to.stages) == to.stages && (b.barrier.dstAccess & to.access) == to.access)
      return true;
  }
  return false;
}

// `chained` for every stage of `from` and every stage of `to`: each pair may take its own chain.
bool ordered(const std::vector<Placed>& barriers, const End& from, const End& to) {
  const auto bits = [](vk::PipelineStageFlags2 stages) {
    std::vector<vk::PipelineStageFlags2> single;
    for (int bit = 0; bit < 64; ++bit)
      if (const auto one = vk::PipelineStageFlags2(VkPipelineStageFlags2(1) << bit); stages & one)
        single.push_back(one);
    if (single.empty()) single.push_back({});
    return single;
  };
  for (const auto first : bits(from.stages))
    for (const auto last : bits(to.stages)) {
      End a = from, b = to;
      a.stages = first;
      b.stages = last;
      if (!chained(barriers, a, b)) return false;
    }
  return true;
}

constexpr vk::AccessFlags2 kWriteBits = Access::eShaderStorageWrite | Access::eColorAttachmentWrite |
                                        Access::eDepthStencilAttachmentWrite | Access::eMemoryWrite;

// Checks `barriers` for the uses of one resource; says what is wrong, or nothing.
std::optional<std::string> violation(const std::vector<Access1>& uses, const std::vector<Placed>& barriers,
                                     bool image) {
  // Before the first pass (position -1): a write by any stage.
  std::vector<Access1> all{{.pass = 0, .use = {Stage::eAllCommands, Access::eMemoryWrite}, .write = true}};
  all.insert(all.end(), uses.begin(), uses.end());
  const auto at = [&](std::size_t i, bool later) {
    const Access1& use = all[i];
    const vk::AccessFlags2 access = later ? use.use.access : use.use.access & kWriteBits;
    return End{.position = i == 0 ? -1.0 : double(use.pass), .stages = use.use.stages, .access = access};
  };
  for (std::size_t j = 1; j < all.size(); ++j)
    for (std::size_t i = 0; i < j; ++i) {
      if (!all[i].write && !all[j].write) continue;
      End before = at(i, false), after = at(j, true);
      if (!all[i].write) after.access = {};  // after a read: execution order alone
      if (!ordered(barriers, before, after))
        return "use " + std::to_string(j) + " is not ordered after use " + std::to_string(i);
    }
  if (!image) return std::nullopt;
  // Layouts: a barrier transitions from the current layout (or from UNDEFINED, dropping the
  // contents, before a use that discards them); a use finds its own layout. A transition writes
  // the image: the uses before it are ordered before it, those after it after it.
  std::optional<Layout> layout;
  std::size_t next = 0;
  for (std::size_t u = 1; u < all.size(); ++u) {
    for (; next < barriers.size() && barriers[next].pass <= all[u].pass; ++next) {
      const GraphBarrier& b = barriers[next].barrier;
      const bool drops = b.oldLayout == Layout::eUndefined;
      if (drops && !all[u].discard) return std::string("contents dropped before a use that keeps them");
      if (!drops && layout && b.oldLayout != *layout) return std::string("a transition from the wrong layout");
      if (drops || b.oldLayout != b.newLayout) {
        const End transition{.position = double(barriers[next].pass), .barrier = next};
        for (std::size_t i = 0; i < all.size(); ++i) {
          const bool before = i == 0 || all[i].pass < barriers[next].pass;
          if (before ? !ordered(barriers, at(i, false), transition) : !ordered(barriers, transition, at(i, true)))
            return "use " + std::to_string(i) + " is not ordered with a layout transition";
        }
      }
      layout = b.newLayout;
    }
    if (!layout) layout = all[u].use.layout;
    if (*layout != all[u].use.layout) return "use " + std::to_string(u) + " finds the image in another layout";
  }
  return std::nullopt;
}

std::string describe(const std::vector<Access1>& uses, const std::vector<Placed>& barriers) {
  std::string text;
  std::size_t b = 0;
  for (std::size_t u = 0; u <= uses.size(); ++u) {
    const std::size_t pass = u < uses.size() ? uses[u].pass : std::size_t(-1);
    for (; b < barriers.size() && barriers[b].pass <= pass; ++b) {
      const GraphBarrier& barrier = barriers[b].barrier;
      text += "\n  barrier before pass " + std::to_string(barriers[b].pass) + ": " + vk::to_string(barrier.srcStages) +
              " " + vk::to_string(barrier.srcAccess) + " -> " + vk::to_string(barrier.dstStages) + " " +
              vk::to_string(barrier.dstAccess) + ", " + vk::to_string(barrier.oldLayout) + " -> " +
              vk::to_string(barrier.newLayout);
    }
    if (u == uses.size()) break;
    text += "\n  use " + std::to_string(u + 1) + " in pass " + std::to_string(uses[u].pass) + ": " +
            vk::to_string(uses[u].use.stages) + " " + vk::to_string(uses[u].use.access) + " " +
            vk::to_string(uses[u].use.layout) + (uses[u].discard ? " discard" : "");
  }
  return text;
}

std::vector<ResourceUse> imageUses() {
  return {ResourceUse::sampled(Stage::eFragmentShader),
          ResourceUse::sampled(Stage::eComputeShader),
          ResourceUse::sampled(Stage::eFragmentShader | Stage::eComputeShader),
          ResourceUse::colorAttachment(),
          ResourceUse::storageWrite(Stage::eComputeShader),
          ResourceUse::storageRead(Stage::eComputeShader),
          ResourceUse::storageReadWrite(Stage::eComputeShader),
          ResourceUse::depthAttachment()};
}

std::vector<ResourceUse> bufferUses() {
  return {ResourceUse::storageRead(Stage::eComputeShader),
          ResourceUse::storageRead(Stage::eVertexShader),
          ResourceUse::storageWrite(Stage::eComputeShader),
          ResourceUse::storageReadWrite(Stage::eFragmentShader),
          ResourceUse::vertexInput(),
          ResourceUse::indirectCommands(),
          ResourceUse::indexInput()};
}

TEST(FrameGraph, RandomUsesGetExactlyTheBarriersVulkanAsksFor) {
  std::mt19937 random(30);
  const std::vector<ResourceUse> forImages = imageUses(), forBuffers = bufferUses();
  for (int trial = 0; trial < 300; ++trial) {
    const std::vector<GraphResource> resources{fakeImage(1), fakeImage(2), fakeBuffer(3), fakeBuffer(4)};
    std::vector<std::vector<Access1>> uses(resources.size());
    FrameGraph graph;
    const std::size_t passes = 2 + random() % 12;
    for (std::size_t p = 0; p < passes; ++p) {
      graph.addPass(
          kPass,
          [&](FrameGraph::Builder& pass) {
            for (std::size_t r = 0; r < resources.size(); ++r) {
              if (random() % 3 == 0) continue;
              const bool image = resources[r].isImage();
              const std::vector<ResourceUse>& choices = image ? forImages : forBuffers;
              const ResourceUse use = choices[random() % choices.size()];
              const bool discard = use.writes() && random() % 3 == 0;
              if (use.writes())
                pass.write(resources[r], use, discard ? Contents::kDiscard : Contents::kKeep);
              else
                pass.read(resources[r], use);
              uses[r].push_back({.pass = p, .use = use, .write = use.writes(), .discard = discard});
            }
          },
          kNothing);
    }
    graph.compile();
    std::vector<std::vector<Placed>> placed(resources.size());
    for (std::size_t p = 0; p < passes; ++p)
      for (const GraphBarrier& barrier : graph.barriersBefore(p))
        for (std::size_t r = 0; r < resources.size(); ++r)
          if (barrier.resource == resources[r]) placed[r].push_back({p, barrier});
    for (std::size_t r = 0; r < resources.size(); ++r) {
      const bool image = resources[r].isImage();
      const auto wrong = violation(uses[r], placed[r], image);
      ASSERT_FALSE(wrong) << "trial " << trial << ", resource " << r << ": " << *wrong << describe(uses[r], placed[r]);
      // Every barrier is needed: without it, something above breaks.
      for (std::size_t b = 0; b < placed[r].size(); ++b) {
        std::vector<Placed> fewer = placed[r];
        fewer.erase(fewer.begin() + std::ptrdiff_t(b));
        EXPECT_TRUE(violation(uses[r], fewer, image))
            << "trial " << trial << ", resource " << r << ": barrier " << b << " before pass " << placed[r][b].pass
            << " is not needed" << describe(uses[r], placed[r]);
      }
    }
  }
}

}  // namespace
}  // namespace mane::render
