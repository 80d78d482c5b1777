#pragma once
// The passes of a frame in the order they run, each with the images and buffers it shares with
// other passes and how it uses them; from those declarations the graph derives the barriers and
// image layout transitions between the passes (a frame graph after Filament's FrameGraph, much
// reduced: nothing is culled or reordered, and every resource is owned outside the graph).
//
//   graph.addPass(PassName::kOutput,
//                 [&](FrameGraph::Builder& pass) {
//                   pass.read(target.hdr(), ResourceUse::sampled(vk::PipelineStageFlagBits2::eFragmentShader));
//                   pass.write(target.output(), ResourceUse::colorAttachment(), Contents::kDiscard);
//                 },
//                 [&](const vk::raii::CommandBuffer& commands) { output.record(commands, ...); });
//   graph.leaveAs(target.output(), ResourceUse::transferSource());
//   graph.compile();
//   graph.execute(commands, &timer);
//
// compile() walks the passes in insertion order and keeps, per resource, its layout, its last
// write and where that write has been made visible, and the stages that read it since. A use
// needs a barrier (Vulkan's synchronization rules, per resource):
//  - after a write (read after write, write after write), unless a barrier before it already
//    made the write visible to the use's stages and accesses;
//  - for a write after reads (write after read): an execution dependency on those reads;
//  - for an image in another layout, or whose contents the use discards: a layout transition
//    (from UNDEFINED when discarding).
// Reads after reads need nothing. Before the first pass anything may have read or written a
// resource (an earlier frame, or earlier commands of the command buffer), so its first use
// waits for every earlier command. An image whose first use keeps its contents must then be in
// that use's layout: the layout it rests in between frames.
//
// A pass that synchronises a resource itself, over several steps of its own, declares it with
// produce(): the graph places nothing before the pass for it, and takes it as written and made
// visible to the use the pass leaves it ready for. What a pass does between its own steps (a
// dispatch reading what the one before it wrote, an image no other pass sees) stays in the pass.
//
// execute() records each pass's barriers in one vkCmdPipelineBarrier2, then the pass; on
// lavapipe every barrier waits for all the work recorded before it, so the graph places one
// barrier command per pass at most. Consecutive passes of the same name are timed as one.
//
// A graph is rebuilt every frame: reset() keeps the memory of the previous one, and the pass
// callbacks are stored inline, so a frame allocates nothing once the vectors have grown.

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <span>
#include <type_traits>
#include <vector>

#include "render/pass_name.hpp"
#include "render/resources.hpp"

namespace mane::render {

class GpuTimer;

/// How a pass touches a resource: the pipeline stages, the accesses (reads, writes or both) and,
/// for an image, the layout it must be in.
struct ResourceUse {
  vk::PipelineStageFlags2 stages;
  vk::AccessFlags2 access;
  vk::ImageLayout layout = vk::ImageLayout::eUndefined;  ///< images only

  /// Read through a sampler or a texel buffer (images: SHADER_READ_ONLY_OPTIMAL).
  static ResourceUse sampled(vk::PipelineStageFlags2 stages);
  /// Read as a storage buffer (or a storage image in GENERAL layout).
  static ResourceUse storageRead(vk::PipelineStageFlags2 stages);
  /// Written as a storage buffer or image (GENERAL), not read.
  static ResourceUse storageWrite(vk::PipelineStageFlags2 stages);
  /// Read and written as a storage buffer or image (GENERAL).
  static ResourceUse storageReadWrite(vk::PipelineStageFlags2 stages);
  /// Drawn into (and blended over, or resolved into) as a colour attachment.
  static ResourceUse colorAttachment();
  /// Tested against and written as the depth attachment.
  static ResourceUse depthAttachment();
  static ResourceUse vertexInput();
  static ResourceUse indexInput();
  static ResourceUse indirectCommands();
  /// Copied or blitted from (images: TRANSFER_SRC_OPTIMAL).
  static ResourceUse transferSource();
  /// Copied or blitted into (images: TRANSFER_DST_OPTIMAL).
  static ResourceUse transferDestination();
  /// Read by the host after the commands complete (a mapped buffer).
  static ResourceUse hostRead();
  /// Vertex data a compute pass wrote, as its later readers take it: drawn from (vertex input or
  /// storage reads in the vertex shader) or copied, and read by the host too where `host`.
  static ResourceUse computedVertices(bool host);

  /// Whether `access` holds a write.
  [[nodiscard]] bool writes() const;
  friend bool operator==(const ResourceUse&, const ResourceUse&) = default;
};

/// What a write does to the contents before it: keep them (load, blend) or drop them (clear,
/// overwrite everything).
enum class Contents { kKeep, kDiscard };

/// A buffer or an image (a range of its subresources) as the graph tells resources apart: by
/// Vulkan handle.
class GraphResource {
public:
  GraphResource(const Buffer& buffer);  // NOLINT(google-explicit-constructor): any Buffer is one
  GraphResource(const Image& image);    // NOLINT(google-explicit-constructor): any Image is one
  explicit GraphResource(vk::Buffer buffer);
  GraphResource(vk::Image image, const vk::ImageSubresourceRange& range);

  [[nodiscard]] bool isImage() const { return image_; }
  [[nodiscard]] vk::Buffer buffer() const;
  [[nodiscard]] vk::Image image() const;
  [[nodiscard]] const vk::ImageSubresourceRange& range() const { return range_; }
  friend bool operator==(const GraphResource& a, const GraphResource& b) {
    return a.handle_ == b.handle_ && a.image_ == b.image_;
  }

private:
  std::uint64_t handle_ = 0;
  bool image_ = false;
  vk::ImageSubresourceRange range_{};
};

/// One barrier the graph derived: from the accesses before it to the use after it, with the
/// layout transition of an image.
struct GraphBarrier {
  GraphResource resource;
  vk::PipelineStageFlags2 srcStages;
  vk::AccessFlags2 srcAccess;
  vk::PipelineStageFlags2 dstStages;
  vk::AccessFlags2 dstAccess;
  vk::ImageLayout oldLayout = vk::ImageLayout::eUndefined;  ///< images only
  vk::ImageLayout newLayout = vk::ImageLayout::eUndefined;
};

/// What a pass records, called with the frame's command buffer: any callable that is trivially
/// copyable and small (a lambda capturing a few references), kept inline.
class PassCommands {
public:
  static constexpr std::size_t kCapacity = 64;
  template <class F>
  requires std::is_trivially_copyable_v<F> && std::is_invocable_v<const F&, const vk::raii::CommandBuffer&>
  PassCommands(const F& f)  // NOLINT(google-explicit-constructor): lambdas convert
      : call_([](const void* self, const vk::raii::CommandBuffer& commands) {
          (*static_cast<const F*>(self))(commands);
        }) {
    static_assert(sizeof(F) <= kCapacity && alignof(F) <= alignof(std::max_align_t),
                  "capture less in a pass's commands");
    std::memcpy(storage_.data(), &f, sizeof(F));
  }
  void operator()(const vk::raii::CommandBuffer& commands) const { call_(storage_.data(), commands); }

private:
  alignas(std::max_align_t) std::array<std::byte, kCapacity> storage_{};
  void (*call_)(const void*, const vk::raii::CommandBuffer&);
};

class FrameGraph {
public:
  /// Declares what one pass uses; handed to the pass's setup callback.
  class Builder {
  public:
    void read(const GraphResource& resource, const ResourceUse& use);
    void write(const GraphResource& resource, const ResourceUse& use, Contents contents = Contents::kKeep);
    /// The pass writes `resource` and synchronises it itself, leaving it visible to `readyFor`
    /// (in its layout): the graph places no barrier for it before the pass, and none after it
    /// for uses within `readyFor`.
    void produce(const GraphResource& resource, const ResourceUse& readyFor);

  private:
    friend class FrameGraph;
    explicit Builder(FrameGraph& graph) : graph_(&graph) {}
    FrameGraph* graph_;
  };

  /// Forgets the passes and resources, keeping the memory.
  void reset();

  /// Adds a pass after the others: `setup(builder)` declares its uses now, `commands` records it
  /// at execute().
  template <class Setup>
  void addPass(PassName name, Setup&& setup, PassCommands commands) {
    beginPass(name, commands);
    Builder builder(*this);
    setup(builder);
  }

  /// After the last pass, `resource` must be ready for `use` (read back, presented, copied).
  void leaveAs(const GraphResource& resource, const ResourceUse& use);

  /// A resource and what it must be left ready for.
  struct Leave {
    GraphResource resource;
    ResourceUse use;
  };
  /// Records `pass` (anything with declare(Builder&) and execute(commands)) as a graph of its
  /// own: after every earlier command, and leaving each of `leave` ready for its use. For tests
  /// and benchmarks, which run a pass without the rest of a frame.
  template <class Pass>
  static void recordAlone(const vk::raii::CommandBuffer& commands, PassName name, const Pass& pass,
                          std::initializer_list<Leave> leave = {}) {
    FrameGraph graph;
    const Pass* p = &pass;
    graph.addPass(
        name, [p](Builder& builder) { p->declare(builder); }, [p](const vk::raii::CommandBuffer& c) { p->execute(c); });
    for (const Leave& left : leave) graph.leaveAs(left.resource, left.use);
    graph.compile();
    graph.execute(commands);
  }

  /// Derives the barriers before each pass and after the last one.
  void compile();

  /// Records every pass with the barriers compile() derived; times them with `timer` where given
  /// (between its reset and its results).
  void execute(const vk::raii::CommandBuffer& commands, GpuTimer* timer = nullptr);

  [[nodiscard]] std::size_t passCount() const { return passes_.size(); }
  /// The barriers compile() placed before pass `pass` (in insertion order).
  [[nodiscard]] std::span<const GraphBarrier> barriersBefore(std::size_t pass) const;
  /// Those it placed after the last pass, for leaveAs.
  [[nodiscard]] std::span<const GraphBarrier> barriersAfter() const;

private:
  enum class UseKind : std::uint8_t { kRead, kWrite, kProduce };
  struct DeclaredUse {
    std::uint32_t resource;
    ResourceUse use;
    UseKind kind;
    bool discard;
  };
  struct Pass {
    PassName name;
    PassCommands commands;
    std::uint32_t firstUse;
    std::uint32_t firstBarrier = 0;
    std::uint32_t barrierCount = 0;
  };
  // What compile() knows of a resource between two passes.
  struct State {
    vk::ImageLayout layout;
    bool layoutKnown;
    vk::PipelineStageFlags2 writeStages;  ///< of the last write
    vk::AccessFlags2 writeAccess;
    vk::PipelineStageFlags2 visibleStages;  ///< where a barrier has made that write visible
    vk::AccessFlags2 visibleAccess;
    vk::PipelineStageFlags2 readStages;  ///< reads since the last write, not yet waited for by a write
  };

  void beginPass(PassName name, PassCommands commands);
  void declare(const GraphResource& resource, const ResourceUse& use, UseKind kind, bool discard);
  std::uint32_t resourceIndex(const GraphResource& resource);
  /// Appends the barrier `use` needs after `state` (if any) and moves the state past the use.
  void applyUse(const DeclaredUse& use, State& state);
  void recordBarriers(const vk::raii::CommandBuffer& commands, std::span<const GraphBarrier> barriers);

  std::vector<GraphResource> resources_;
  std::vector<Pass> passes_;
  std::vector<DeclaredUse> uses_;       ///< pass after pass
  std::vector<DeclaredUse> finalUses_;  ///< leaveAs
  std::vector<GraphBarrier> barriers_;
  std::uint32_t firstFinalBarrier_ = 0;
  std::vector<State> states_;
  std::vector<vk::ImageMemoryBarrier2> imageBarriers_;  ///< execute()'s scratch
  std::vector<vk::BufferMemoryBarrier2> bufferBarriers_;
};

}  // namespace mane::render
