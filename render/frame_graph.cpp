#include "render/frame_graph.hpp"

#include <algorithm>
#include <stdexcept>

#include "render/gpu_timer.hpp"

namespace mane::render {
namespace {

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

constexpr vk::AccessFlags2 kWrites = Access::eShaderWrite | Access::eShaderStorageWrite |
                                     Access::eColorAttachmentWrite | Access::eDepthStencilAttachmentWrite |
                                     Access::eTransferWrite | Access::eHostWrite | Access::eMemoryWrite;
constexpr auto kDepthTests = Stage::eEarlyFragmentTests | Stage::eLateFragmentTests;

bool covers(vk::PipelineStageFlags2 outer, vk::PipelineStageFlags2 inner) {
  return (outer & inner) == inner;
}

bool covers(vk::AccessFlags2 outer, vk::AccessFlags2 inner) {
  return (outer & inner) == inner;
}

}  // namespace

ResourceUse ResourceUse::sampled(vk::PipelineStageFlags2 stages) {
  return {stages, Access::eShaderSampledRead, Layout::eShaderReadOnlyOptimal};
}

ResourceUse ResourceUse::storageRead(vk::PipelineStageFlags2 stages) {
  return {stages, Access::eShaderStorageRead, Layout::eGeneral};
}

ResourceUse ResourceUse::storageWrite(vk::PipelineStageFlags2 stages) {
  return {stages, Access::eShaderStorageWrite, Layout::eGeneral};
}

ResourceUse ResourceUse::storageReadWrite(vk::PipelineStageFlags2 stages) {
  return {stages, Access::eShaderStorageRead | Access::eShaderStorageWrite, Layout::eGeneral};
}

ResourceUse ResourceUse::colorAttachment() {
  return {Stage::eColorAttachmentOutput, Access::eColorAttachmentRead | Access::eColorAttachmentWrite,
          Layout::eColorAttachmentOptimal};
}

ResourceUse ResourceUse::depthAttachment() {
  return {kDepthTests, Access::eDepthStencilAttachmentRead | Access::eDepthStencilAttachmentWrite,
          Layout::eDepthAttachmentOptimal};
}

ResourceUse ResourceUse::vertexInput() {
  return {Stage::eVertexAttributeInput, Access::eVertexAttributeRead};
}

ResourceUse ResourceUse::computedVertices(bool host) {
  ResourceUse use{Stage::eVertexAttributeInput | Stage::eVertexShader | Stage::eCopy,
                  Access::eVertexAttributeRead | Access::eShaderStorageRead | Access::eTransferRead};
  if (host) use = {use.stages | Stage::eHost, use.access | Access::eHostRead};
  return use;
}

ResourceUse ResourceUse::indexInput() {
  return {Stage::eIndexInput, Access::eIndexRead};
}

ResourceUse ResourceUse::indirectCommands() {
  return {Stage::eDrawIndirect, Access::eIndirectCommandRead};
}

ResourceUse ResourceUse::transferSource() {
  return {Stage::eTransfer, Access::eTransferRead, Layout::eTransferSrcOptimal};
}

ResourceUse ResourceUse::transferDestination() {
  return {Stage::eTransfer, Access::eTransferWrite, Layout::eTransferDstOptimal};
}

ResourceUse ResourceUse::hostRead() {
  return {Stage::eHost, Access::eHostRead};
}

bool ResourceUse::writes() const {
  return bool(access & kWrites);
}

GraphResource::GraphResource(const Buffer& buffer) : GraphResource(*buffer.buffer()) {}

GraphResource::GraphResource(const Image& image)
    : GraphResource(*image.image(),
                    {image.settings().aspect, 0, image.settings().mipLevels, 0, image.settings().layers}) {}

GraphResource::GraphResource(vk::Buffer buffer)
    : handle_(reinterpret_cast<std::uint64_t>(static_cast<VkBuffer>(buffer))) {}

GraphResource::GraphResource(vk::Image image, const vk::ImageSubresourceRange& range)
    : handle_(reinterpret_cast<std::uint64_t>(static_cast<VkImage>(image))), image_(true), range_(range) {}

vk::Buffer GraphResource::buffer() const {
  return image_ ? vk::Buffer() : vk::Buffer(reinterpret_cast<VkBuffer>(handle_));
}

vk::Image GraphResource::image() const {
  return image_ ? vk::Image(reinterpret_cast<VkImage>(handle_)) : vk::Image();
}

void FrameGraph::Builder::read(const GraphResource& resource, const ResourceUse& use) {
  if (use.writes()) throw std::logic_error("FrameGraph: a read declared with a writing access");
  graph_->declare(resource, use, UseKind::kRead, false);
}

void FrameGraph::Builder::write(const GraphResource& resource, const ResourceUse& use, Contents contents) {
  graph_->declare(resource, use, UseKind::kWrite, contents == Contents::kDiscard);
}

void FrameGraph::Builder::produce(const GraphResource& resource, const ResourceUse& readyFor) {
  graph_->declare(resource, readyFor, UseKind::kProduce, false);
}

void FrameGraph::reset() {
  resources_.clear();
  passes_.clear();
  uses_.clear();
  finalUses_.clear();
  barriers_.clear();
  firstFinalBarrier_ = 0;
}

void FrameGraph::beginPass(PassName name, PassCommands commands) {
  if (!finalUses_.empty()) throw std::logic_error("FrameGraph: a pass added after leaveAs");
  passes_.push_back({.name = name, .commands = commands, .firstUse = std::uint32_t(uses_.size())});
}

std::uint32_t FrameGraph::resourceIndex(const GraphResource& resource) {
  const auto found = std::find(resources_.begin(), resources_.end(), resource);
  if (found != resources_.end()) return std::uint32_t(found - resources_.begin());
  resources_.push_back(resource);
  return std::uint32_t(resources_.size() - 1);
}

void FrameGraph::declare(const GraphResource& resource, const ResourceUse& use, UseKind kind, bool discard) {
  const std::uint32_t index = resourceIndex(resource);
  // One use per resource and pass: a second declaration widens the first.
  for (std::size_t u = passes_.back().firstUse; u < uses_.size(); ++u) {
    DeclaredUse& earlier = uses_[u];
    if (earlier.resource != index) continue;
    if ((earlier.kind == UseKind::kProduce) != (kind == UseKind::kProduce))
      throw std::logic_error("FrameGraph: a pass both produces a resource and uses it");
    if (resource.isImage() && earlier.use.layout != use.layout)
      throw std::logic_error("FrameGraph: one pass uses an image in two layouts");
    earlier.use.stages |= use.stages;
    earlier.use.access |= use.access;
    if (kind == UseKind::kWrite) earlier.kind = UseKind::kWrite;
    earlier.discard = earlier.discard && discard;
    return;
  }
  uses_.push_back({.resource = index, .use = use, .kind = kind, .discard = discard});
}

void FrameGraph::leaveAs(const GraphResource& resource, const ResourceUse& use) {
  finalUses_.push_back({.resource = resourceIndex(resource), .use = use, .kind = UseKind::kRead, .discard = false});
}

void FrameGraph::applyUse(const DeclaredUse& declared, State& state) {
  const ResourceUse& use = declared.use;
  const bool image = resources_[declared.resource].isImage();
  if (declared.kind == UseKind::kProduce) {
    // The pass waited for what came before and made its writes visible to `use` itself.
    state = {.layout = use.layout,
             .layoutKnown = true,
             .writeStages = Stage::eAllCommands,
             .writeAccess = Access::eMemoryWrite,
             .visibleStages = use.stages,
             .visibleAccess = use.access,
             .readStages = use.stages};
    return;
  }
  if (image && !state.layoutKnown && !declared.discard) state.layout = use.layout;  // where it rests
  state.layoutKnown = true;
  const bool transition = image && (declared.discard || state.layout != use.layout);
  // A read must see the last write; a write that reads nothing only needs it made available
  // (done by any barrier since it) and to come after it, which the reads' barrier below gives.
  const vk::AccessFlags2 reads = use.access & ~kWrites;
  const bool afterWrite =
      bool(state.writeAccess) &&
      (reads ? !(covers(state.visibleStages, use.stages) && covers(state.visibleAccess, reads)) : !state.visibleStages);
  const bool afterRead = declared.kind == UseKind::kWrite && bool(state.readStages);
  const bool barrier = transition || afterWrite || afterRead;
  if (barrier) {
    const bool waitsForWrite = transition || afterWrite;
    barriers_.push_back(
        {.resource = resources_[declared.resource],
         .srcStages = (waitsForWrite ? state.writeStages : vk::PipelineStageFlags2{}) | state.readStages,
         .srcAccess = waitsForWrite ? state.writeAccess : vk::AccessFlags2{},
         .dstStages = use.stages,
         .dstAccess = use.access,
         .oldLayout = image ? (declared.discard ? Layout::eUndefined : state.layout) : Layout::eUndefined,
         .newLayout = image ? use.layout : Layout::eUndefined});
  }
  if (declared.kind == UseKind::kWrite) {
    state.layout = use.layout;
    state.writeStages = use.stages;
    state.writeAccess = use.access & kWrites;
    state.visibleStages = {};
    state.visibleAccess = {};
    state.readStages = {};
    return;
  }
  state.layout = use.layout;
  if (barrier) {
    // Later readers chain on this barrier: it waited for the write and the reads before it.
    state.visibleStages = transition ? use.stages : state.visibleStages | use.stages;
    state.visibleAccess = transition ? use.access : state.visibleAccess | use.access;
    state.readStages = use.stages;
  } else {
    state.readStages |= use.stages;
  }
}

void FrameGraph::compile() {
  barriers_.clear();
  // Before the first pass, anything may have read or written any resource.
  states_.assign(resources_.size(), State{.layout = Layout::eUndefined,
                                          .layoutKnown = false,
                                          .writeStages = Stage::eAllCommands,
                                          .writeAccess = Access::eMemoryWrite,
                                          .visibleStages = {},
                                          .visibleAccess = {},
                                          .readStages = Stage::eAllCommands});
  for (std::size_t p = 0; p < passes_.size(); ++p) {
    Pass& pass = passes_[p];
    pass.firstBarrier = std::uint32_t(barriers_.size());
    const std::size_t end = p + 1 < passes_.size() ? passes_[p + 1].firstUse : uses_.size();
    for (std::size_t u = pass.firstUse; u < end; ++u) applyUse(uses_[u], states_[uses_[u].resource]);
    pass.barrierCount = std::uint32_t(barriers_.size()) - pass.firstBarrier;
  }
  firstFinalBarrier_ = std::uint32_t(barriers_.size());
  for (const DeclaredUse& use : finalUses_) applyUse(use, states_[use.resource]);
}

std::span<const GraphBarrier> FrameGraph::barriersBefore(std::size_t pass) const {
  const Pass& p = passes_.at(pass);
  return std::span(barriers_).subspan(p.firstBarrier, p.barrierCount);
}

std::span<const GraphBarrier> FrameGraph::barriersAfter() const {
  return std::span(barriers_).subspan(firstFinalBarrier_);
}

void FrameGraph::recordBarriers(const vk::raii::CommandBuffer& commands, std::span<const GraphBarrier> barriers) {
  if (barriers.empty()) return;
  imageBarriers_.clear();
  bufferBarriers_.clear();
  for (const GraphBarrier& barrier : barriers) {
    if (barrier.resource.isImage())
      imageBarriers_.push_back({.srcStageMask = barrier.srcStages,
                                .srcAccessMask = barrier.srcAccess,
                                .dstStageMask = barrier.dstStages,
                                .dstAccessMask = barrier.dstAccess,
                                .oldLayout = barrier.oldLayout,
                                .newLayout = barrier.newLayout,
                                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .image = barrier.resource.image(),
                                .subresourceRange = barrier.resource.range()});
    else
      bufferBarriers_.push_back({.srcStageMask = barrier.srcStages,
                                 .srcAccessMask = barrier.srcAccess,
                                 .dstStageMask = barrier.dstStages,
                                 .dstAccessMask = barrier.dstAccess,
                                 .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                 .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                 .buffer = barrier.resource.buffer(),
                                 .offset = 0,
                                 .size = VK_WHOLE_SIZE});
  }
  commands.pipelineBarrier2(vk::DependencyInfo{.bufferMemoryBarrierCount = std::uint32_t(bufferBarriers_.size()),
                                               .pBufferMemoryBarriers = bufferBarriers_.data(),
                                               .imageMemoryBarrierCount = std::uint32_t(imageBarriers_.size()),
                                               .pImageMemoryBarriers = imageBarriers_.data()});
}

void FrameGraph::execute(const vk::raii::CommandBuffer& commands, GpuTimer* timer) {
  for (std::size_t p = 0; p < passes_.size(); ++p) {
    const Pass& pass = passes_[p];
    if (timer && (p == 0 || passes_[p - 1].name != pass.name)) {
      if (p > 0) timer->end(commands);
      timer->begin(commands, pass.name);
    }
    recordBarriers(commands, barriersBefore(p));
    pass.commands(commands);
  }
  if (timer && !passes_.empty()) timer->end(commands);
  recordBarriers(commands, barriersAfter());
}

}  // namespace mane::render
