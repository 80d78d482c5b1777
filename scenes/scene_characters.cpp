#include "scenes/detail/scene_characters.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "scenes/detail/json_fields.hpp"
#include "scenes/detail/scene_bodies.hpp"

namespace mane::scenes::detail {
namespace {

using Json = nlohmann::json;

ClipPlay parseClipPlay(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  ClipPlay play;
  play.clip = fields.required<std::string>("clip");
  require(!play.clip.empty(), fields.child("clip"), "expected the name of an animation in the file");
  play.startSeconds = fields.optional<float>("start", play.startSeconds);
  play.speed = fields.optional<float>("speed", play.speed);
  play.loop = fields.optional<bool>("loop", play.loop);
  play.crossFadeSeconds = fields.optional<float>("cross_fade", play.crossFadeSeconds);
  fields.finish();
  require(play.startSeconds >= 0.0f, fields.child("start"), "expected a start time >= 0 seconds");
  require(play.speed > 0.0f && play.speed <= 100.0f, fields.child("speed"), "expected a speed in (0, 100]");
  require(play.crossFadeSeconds >= 0.0f && play.crossFadeSeconds <= 60.0f, fields.child("cross_fade"),
          "expected a cross-fade of 0..60 seconds");
  return play;
}

MorphTrack parseMorphTrack(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  MorphTrack track;
  track.target = fields.required<std::string>("target");
  require(!track.target.empty(), fields.child("target"), "expected a morph target name");
  const Json* weight = fields.take("weight");
  const Json& keys = fields.array("keys", false);
  require((weight != nullptr) != !keys.empty(), fields.path(), "expected either \"weight\" or \"keys\"");
  const auto checkedWeight = [](float value, const std::string& path) {
    require(value >= -10.0f && value <= 10.0f, path, "expected a weight in [-10, 10]");
    return value;
  };
  if (weight) track.keys.push_back({0.0f, checkedWeight(read<float>(*weight, fields.child("weight")), fields.child("weight"))});
  for (std::size_t i = 0; i < keys.size(); ++i) {
    ObjectFields key(keys[i], indexPath(fields.child("keys"), i));
    MorphKey morph{key.required<float>("time"), checkedWeight(key.required<float>("weight"), key.child("weight"))};
    key.finish();
    require(track.keys.empty() || morph.timeSeconds > track.keys.back().timeSeconds, key.child("time"),
            "expected times in strictly increasing order");
    track.keys.push_back(morph);
  }
  fields.finish();
  return track;
}

}  // namespace

CharacterInstance parseCharacter(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  CharacterInstance character;
  character.name = fields.required<std::string>("name");
  require(!character.name.empty() && character.name.find(kCharacterPartSeparator) == std::string::npos,
          fields.child("name"), "expected a non-empty name without '/' (its meshes are named \"<name>/<mesh>\")");
  character.source = fields.required<std::string>("source");
  require(!character.source.empty(), fields.child("source"), "expected a .glb/.gltf asset name or file path");
  if (const Json* transform = fields.take("transform")) {
    character.transform = parseTransform(*transform, fields.child("transform"));
  }
  character.material = fields.optional<std::string>("material", "");
  if (const Json* materials = fields.take("materials")) {
    require(materials->is_object(), fields.child("materials"),
            "expected an object mapping glTF material names to scene materials" + got(*materials));
    for (const auto& item : materials->items())
      character.materials.emplace_back(item.key(),
                                       read<std::string>(item.value(), childPath(fields.child("materials"), item.key())));
  }
  const std::string skinning = fields.optional<std::string>("skinning", "linear_blend");
  require(skinning == "linear_blend" || skinning == "dual_quaternion", fields.child("skinning"),
          "expected \"linear_blend\" or \"dual_quaternion\", got \"" + skinning + "\"");
  character.skinning = skinning == "dual_quaternion" ? physics::SkinningMethod::DualQuaternion
                                                     : physics::SkinningMethod::LinearBlend;
  character.clips = parseList<ClipPlay>(fields, "clips", parseClipPlay);
  for (std::size_t i = 1; i < character.clips.size(); ++i)
    require(character.clips[i].startSeconds > character.clips[i - 1].startSeconds,
            indexPath(fields.child("clips"), i) + ".start", "expected start times in strictly increasing order");
  character.morphs = parseList<MorphTrack>(fields, "morphs", parseMorphTrack);
  if (const Json* subdivision = fields.take("subdivision")) {
    // The meshes it names, then the block a mesh's subdivision has.
    const std::string at = fields.child("subdivision");
    require(subdivision->is_object(), at, "expected an object" + got(*subdivision));
    Json settings = *subdivision;
    const auto meshes = settings.find("meshes");
    require(meshes != settings.end() && meshes->is_array() && !meshes->empty(), childPath(at, "meshes"),
            "expected the names of the character's meshes to draw as limit surfaces");
    for (std::size_t i = 0; i < meshes->size(); ++i)
      character.subdividedMeshes.push_back(read<std::string>((*meshes)[i], indexPath(childPath(at, "meshes"), i)));
    settings.erase("meshes");
    character.subdivision = parseSubdivision(settings, at);
    require(!character.subdivision->coarseCage, childPath(at, "coarse_cage"),
            "does not apply to a character: its meshes are their own cages");
  }
  fields.finish();
  return character;
}

}  // namespace mane::scenes::detail
