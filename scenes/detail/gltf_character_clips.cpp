#include "scenes/detail/gltf_character_clips.hpp"

#include <optional>
#include <string>
#include <utility>

namespace mane::scenes::detail {
namespace {

std::optional<physics::AnimatedProperty> propertyOf(const std::string& path) {
  if (path == "translation") return physics::AnimatedProperty::Translation;
  if (path == "rotation") return physics::AnimatedProperty::Rotation;
  if (path == "scale") return physics::AnimatedProperty::Scale;
  if (path == "weights") return physics::AnimatedProperty::MorphWeights;
  return std::nullopt;
}

std::optional<physics::Interpolation> interpolationOf(const std::string& name) {
  if (name == "LINEAR" || name.empty()) return physics::Interpolation::Linear;
  if (name == "STEP") return physics::Interpolation::Step;
  if (name == "CUBICSPLINE") return physics::Interpolation::CubicSpline;
  return std::nullopt;
}

/// glTF 2.0 §5.5 (animation sampler output): translation and scale are floats; rotations and
/// weights may also be normalised signed or unsigned bytes or shorts.
bool outputTypeAllowed(const tinygltf::Accessor& accessor, physics::AnimatedProperty property) {
  if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
  if (property == physics::AnimatedProperty::Translation || property == physics::AnimatedProperty::Scale) return false;
  const int type = accessor.componentType;
  return accessor.normalized &&
         (type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
          type == TINYGLTF_COMPONENT_TYPE_SHORT || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

Result<physics::AnimationChannel> readChannel(const GltfContext& ctx, const tinygltf::Animation& animation,
                                              const tinygltf::AnimationChannel& source,
                                              physics::AnimatedProperty property, const physics::Skeleton& skeleton,
                                              const std::string& where) {
  const auto& model = ctx.model;
  const auto node = static_cast<std::size_t>(source.target_node);
  const physics::SkeletonNode& target = skeleton.nodes()[node];
  if (property != physics::AnimatedProperty::MorphWeights && target.fixedMatrix) {
    return ctx.error(where + " animates node " + std::to_string(node) +
                     ", which is given by a matrix; glTF allows animating only nodes given by translation, rotation "
                     "and scale");
  }
  if (property == physics::AnimatedProperty::MorphWeights && target.restMorphWeights.empty()) {
    return ctx.error(where + " animates the morph weights of node " + std::to_string(node) +
                     ", which holds no mesh with morph targets");
  }
  if (source.sampler < 0 || static_cast<std::size_t>(source.sampler) >= animation.samplers.size()) {
    return ctx.error(where + " uses sampler " + std::to_string(source.sampler) + ", but the animation has " +
                     std::to_string(animation.samplers.size()) + " samplers");
  }
  const tinygltf::AnimationSampler& sampler = animation.samplers[static_cast<std::size_t>(source.sampler)];
  const std::string samplerWhere = where + " (sampler " + std::to_string(source.sampler) + ")";

  physics::AnimationChannel channel;
  channel.node = source.target_node;
  channel.property = property;
  const auto interpolation = interpolationOf(sampler.interpolation);
  if (!interpolation) {
    return ctx.error(samplerWhere + " has interpolation '" + sampler.interpolation +
                     "'; expected LINEAR, STEP or CUBICSPLINE");
  }
  channel.interpolation = *interpolation;
  switch (property) {
    case physics::AnimatedProperty::Translation:
    case physics::AnimatedProperty::Scale: channel.width = 3; break;
    case physics::AnimatedProperty::Rotation: channel.width = 4; break;
    case physics::AnimatedProperty::MorphWeights: channel.width = target.restMorphWeights.size(); break;
  }

  const bool inputInFile = sampler.input >= 0 && static_cast<std::size_t>(sampler.input) < model.accessors.size();
  if (inputInFile &&
      model.accessors[static_cast<std::size_t>(sampler.input)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    return ctx.error(samplerWhere + " input (accessor " + std::to_string(sampler.input) + ") must hold floats");
  }
  auto times = readFloats(ctx, sampler.input, 1, samplerWhere + " input");
  if (!times) return std::unexpected(times.error());
  channel.times = std::move(*times);

  // Weights are stored as scalars, the targets' weights of each key one after another.
  const int outputComponents =
      property == physics::AnimatedProperty::MorphWeights ? 1 : static_cast<int>(channel.width);
  const bool outputInFile = sampler.output >= 0 && static_cast<std::size_t>(sampler.output) < model.accessors.size();
  if (outputInFile && !outputTypeAllowed(model.accessors[static_cast<std::size_t>(sampler.output)], property)) {
    return ctx.error(samplerWhere + " output (accessor " + std::to_string(sampler.output) +
                     ") must hold floats (or, for rotations and weights, normalised integers)");
  }
  auto values = readFloats(ctx, sampler.output, outputComponents, samplerWhere + " output");
  if (!values) return std::unexpected(values.error());
  channel.values = std::move(*values);

  if (auto ok = physics::validateChannel(channel); !ok) return ctx.error(samplerWhere + ": " + ok.error().message);
  return channel;
}

}  // namespace

Result<std::vector<physics::AnimationClip>> readClips(const GltfContext& ctx, const physics::Skeleton& skeleton) {
  std::vector<physics::AnimationClip> clips;
  const auto& model = ctx.model;
  for (std::size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& animation = model.animations[a];
    const std::string label =
        "animation " + std::to_string(a) + (animation.name.empty() ? "" : " ('" + animation.name + "')");
    std::vector<physics::AnimationChannel> channels;
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
      const tinygltf::AnimationChannel& source = animation.channels[c];
      const std::string where = label + " channel " + std::to_string(c);
      // No node: an extension (such as KHR_animation_pointer) names the target; not ours.
      if (source.target_node < 0) continue;
      if (static_cast<std::size_t>(source.target_node) >= skeleton.nodeCount()) {
        return ctx.error(where + " targets node " + std::to_string(source.target_node) + ", but the file has " +
                         std::to_string(skeleton.nodeCount()) + " nodes");
      }
      const auto property = propertyOf(source.target_path);
      if (!property) continue;
      auto channel = readChannel(ctx, animation, source, *property, skeleton, where);
      if (!channel) return std::unexpected(channel.error());
      channels.push_back(std::move(*channel));
    }
    auto clip = physics::AnimationClip::create(animation.name, std::move(channels));
    if (!clip) return ctx.error(label + ": " + clip.error().message);
    clips.push_back(std::move(*clip));
  }
  return clips;
}

}  // namespace mane::scenes::detail
