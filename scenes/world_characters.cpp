// The World's characters (scenes/scene_character.hpp): loading them as meshes of the scene,
// following their deformed surfaces with hair roots and cloth pins, and what the renderer and
// viewers need of them.

#include <algorithm>
#include <map>
#include <tuple>

#include <glm/matrix.hpp>

#include "scenes/subdivided_mesh.hpp"
#include "scenes/world.hpp"

namespace mane::scenes {
namespace {

// Vertices [first, end) of a skinned mesh as the renderer deforms them.
render::GpuSkinnedMesh gpuSkinOf(const physics::SkinnedMeshData& data, std::size_t first, std::size_t end) {
  const auto range = [&](const auto& values, std::size_t width) {
    using Values = std::decay_t<decltype(values)>;
    if (values.empty()) return Values{};
    return Values(values.begin() + static_cast<std::ptrdiff_t>(first * width),
                  values.begin() + static_cast<std::ptrdiff_t>(end * width));
  };
  render::GpuSkinnedMesh mesh;
  mesh.positions = range(data.positions, 1);
  mesh.normals = range(data.normals, 1);
  mesh.tangents = range(data.tangents, 1);
  mesh.influencesPerVertex = static_cast<std::uint32_t>(data.influencesPerVertex);
  mesh.joints = range(data.joints, data.influencesPerVertex);
  mesh.weights = range(data.weights, data.influencesPerVertex);
  mesh.jointCount = static_cast<std::uint32_t>(data.jointCount);
  for (const physics::MorphTarget& target : data.morphTargets)
    mesh.morphTargets.push_back({range(target.positionDeltas, 1), range(target.normalDeltas, 1),
                                 range(target.tangentDeltas, 1)});
  mesh.method = data.method == physics::SkinningMethod::DualQuaternion ? render::GpuSkinningMethod::DualQuaternion
                                                                      : render::GpuSkinningMethod::LinearBlend;
  return mesh;
}

// Vertices [first, end) of a skinned mesh as a Catmull-Clark cage whose vertices are skinned:
// its triangles welded where positions are equal (cageFromTriangles), each cage vertex taking the
// influences and morph offsets of the first vertex at its position.
Result<std::unique_ptr<SkinnedCage>> skinnedCageOf(const physics::SkinnedMeshData& data, std::size_t first,
                                                   std::size_t end, std::span<const std::uint32_t> triangles,
                                                   const Subdivision& subdivision) {
  Mesh bind;
  bind.positions.assign(data.positions.begin() + static_cast<std::ptrdiff_t>(first),
                        data.positions.begin() + static_cast<std::ptrdiff_t>(end));
  bind.indices.assign(triangles.begin(), triangles.end());
  subdiv::Cage cage = cageFromTriangles(bind);
  std::map<std::tuple<float, float, float>, std::size_t> firstAt;
  for (std::size_t v = end; v-- > first;) {
    const glm::vec3& p = data.positions[v];
    firstAt[{p.x, p.y, p.z}] = v;
  }
  physics::SkinnedMeshData skin;
  skin.influencesPerVertex = data.influencesPerVertex;
  skin.jointCount = data.jointCount;
  skin.method = data.method;
  skin.morphTargets.resize(data.morphTargets.size());
  for (const glm::vec3& p : cage.positions) {
    const std::size_t v = firstAt.at({p.x, p.y, p.z});
    for (std::size_t i = 0; i < data.influencesPerVertex; ++i) {
      skin.joints.push_back(data.joints[v * data.influencesPerVertex + i]);
      skin.weights.push_back(data.weights[v * data.influencesPerVertex + i]);
    }
    for (std::size_t t = 0; t < data.morphTargets.size(); ++t)
      if (!data.morphTargets[t].positionDeltas.empty())
        skin.morphTargets[t].positionDeltas.push_back(data.morphTargets[t].positionDeltas[v]);
  }
  return SkinnedCage::create(std::move(cage), std::move(skin), subdivision);
}

// `points` taken into the frame whose placement is `frame` (rigid): p ↦ frame⁻¹ · p; normals
// turned likewise.
void intoFrame(const glm::mat4& frame, std::span<const glm::vec3> points, std::span<const glm::vec3> normals,
               std::span<glm::vec3> outPoints, std::span<glm::vec3> outNormals) {
  const glm::mat4 inverse = glm::inverse(frame);
  const glm::mat3 turn(inverse);
  for (std::size_t v = 0; v < points.size(); ++v) outPoints[v] = glm::vec3(inverse * glm::vec4(points[v], 1.0f));
  for (std::size_t v = 0; v < normals.size() && v < outNormals.size(); ++v)
    outNormals[v] = glm::normalize(turn * normals[v]);
}

}  // namespace

Result<void> World::loadCharacters(const AssetResolver& resolver) {
  characterParts_.assign(scene_.meshes.size(), std::nullopt);
  gpuSkins_.resize(scene_.meshes.size());
  skinnedCages_.resize(scene_.meshes.size());
  for (std::size_t c = 0; c < scene_.characters.size(); ++c) {
    const CharacterInstance& instance = scene_.characters[c];
    auto lookup = resolver.lookupForScene(instance.source, scene_.file.parent_path());
    if (!lookup) return fail("character '" + instance.name + "': " + lookup.error().message);
    if (!lookup->path) return fail("character '" + instance.name + "': " + lookup->missingReason);
    auto loaded = SceneCharacter::create(instance, *lookup->path);
    if (!loaded) return std::unexpected(loaded.error());
    for (const std::string& name : instance.subdividedMeshes)
      if (auto found = loaded->findPart(name); !found)
        return fail("characters[" + std::to_string(c) + "].subdivision.meshes: " + found.error().message);
    characters_.push_back(std::move(*loaded));
    for (std::size_t p = 0; p < characters_.back().partCount(); ++p)
      if (auto added = addCharacterPart(c, p); !added) return added;
  }
  return checkPartReferences();
}

Result<void> World::addCharacterPart(std::size_t c, std::size_t p) {
  SceneCharacter& character = characters_[c];
  const CharacterInstance& instance = character.instance();
  const CharacterMesh& source = character.character().meshes[p];
  auto deformed = character.deformed(p);
  if (!deformed) return std::unexpected(deformed.error());
  const glm::mat4 frame = character.partFrame(p);
  const physics::SkinnedMeshData& data = source.surface.data();
  LoadedMesh whole;
  whole.mesh.name = instance.name + kCharacterPartSeparator + source.name;
  whole.mesh.positions.resize(data.positions.size());
  whole.mesh.normals.resize(data.normals.size());
  intoFrame(frame, (*deformed)->positions, (*deformed)->normals, whole.mesh.positions, whole.mesh.normals);
  whole.mesh.indices = data.indices;
  const bool deforms = source.skin >= 0 || !data.morphTargets.empty();
  const bool subdivided = std::ranges::find(instance.subdividedMeshes, source.name) != instance.subdividedMeshes.end();
  const MeshInstance placed{.name = whole.mesh.name, .source = instance.source, .transform = transformOf(frame)};
  // Each primitive drawn on its own, with its own material; its vertices are a contiguous run.
  for (std::size_t primitive = 0; primitive < source.primitiveFirstVertex.size(); ++primitive) {
    const bool last = primitive + 1 == source.primitiveFirstVertex.size();
    const std::size_t firstVertex = source.primitiveFirstVertex[primitive];
    const std::size_t endVertex = last ? data.positions.size() : source.primitiveFirstVertex[primitive + 1];
    const std::size_t firstIndex = source.primitiveFirstIndex[primitive];
    const std::size_t endIndex = last ? data.indices.size() : source.primitiveFirstIndex[primitive + 1];
    LoadedMesh piece;
    piece.mesh.name = whole.mesh.name + "#" + std::to_string(primitive);
    piece.mesh.positions.assign(whole.mesh.positions.begin() + firstVertex, whole.mesh.positions.begin() + endVertex);
    piece.mesh.normals.assign(whole.mesh.normals.begin() + firstVertex, whole.mesh.normals.begin() + endVertex);
    for (std::size_t i = firstIndex; i < endIndex; ++i)
      piece.mesh.indices.push_back(data.indices[i] - static_cast<std::uint32_t>(firstVertex));
    std::optional<render::GpuSkinnedMesh> gpuSkin;
    std::unique_ptr<SkinnedCage> cage;
    if (subdivided) {
      auto made = skinnedCageOf(data, firstVertex, endVertex, piece.mesh.indices, *instance.subdivision);
      if (!made) return fail("character '" + instance.name + "', mesh " + piece.mesh.name + ": " + made.error().message);
      cage = std::move(*made);
    } else if (deforms) {
      gpuSkin = gpuSkinOf(data, firstVertex, endVertex);
    }
    MeshInstance drawn = placed;
    drawn.name = piece.mesh.name;
    for (const auto& [gltfMaterial, material] : instance.materials)
      if (gltfMaterial == source.primitiveMaterials[primitive]) drawn.material = material;
    if (drawn.material.empty()) drawn.material = instance.material;
    scene_.meshes.push_back(std::move(drawn));
    meshes_.push_back(std::move(piece));
    characterParts_.push_back(CharacterPart{c, p, static_cast<int>(primitive)});
    gpuSkins_.push_back(std::move(gpuSkin));
    skinnedCages_.push_back(std::move(cage));
  }
  scene_.meshes.push_back(placed);
  meshes_.push_back(std::move(whole));
  characterParts_.push_back(CharacterPart{c, p, -1});
  gpuSkins_.emplace_back();
  skinnedCages_.emplace_back();
  return {};
}

Result<void> World::checkPartReferences() const {
  // A whole part, never one of its drawn primitives ("…#k"): their vertices are a slice of the
  // part's, which roots, pins and fields are bound to.
  auto check = [&](const std::string& name, const std::string& where) -> Result<void> {
    for (std::size_t m = 0; m < scene_.meshes.size(); ++m)
      if (scene_.meshes[m].name == name && (!characterParts_[m] || characterParts_[m]->primitive < 0)) return {};
    const std::string character = name.substr(0, name.find(kCharacterPartSeparator));
    std::string parts;
    for (std::size_t m = 0; m < scene_.meshes.size(); ++m)
      if (characterParts_[m] && characterParts_[m]->primitive < 0 &&
          scene_.characters[characterParts_[m]->character].name == character)
        parts += (parts.empty() ? "'" : ", '") + scene_.meshes[m].name + "'";
    return fail(where + ": character '" + character + "' has no mesh named '" + name + "'; its meshes are " + parts);
  };
  for (const Groom& groom : scene_.grooms) {
    if (auto found = check(groom.attachedMesh, "groom " + groom.name + ": attached_mesh"); !found) return found;
    if (groom.colliders.sdf)
      if (auto found = check(groom.colliders.sdf->mesh, "groom " + groom.name + ": sdf"); !found) return found;
  }
  for (const Cloth& cloth : scene_.cloths) {
    if (auto found = check(cloth.attachedMesh, "cloth '" + cloth.name + "': attached_mesh"); !found) return found;
    if (cloth.colliders.sdf)
      if (auto found = check(cloth.colliders.sdf->mesh, "cloth '" + cloth.name + "': sdf"); !found) return found;
  }
  return {};
}

std::string World::playNextClips(float crossFadeSeconds) {
  std::string shown;
  for (SceneCharacter& character : characters_) {
    const std::size_t clips = character.character().clips.size();
    if (clips == 0) continue;
    const std::optional<std::size_t> playing = character.clipPlaying();
    const std::size_t next = playing ? (*playing + 1) % clips : 0;
    character.play(next, time_, crossFadeSeconds);
    shown += (shown.empty() ? "" : ", ") + character.instance().name + ": " + character.character().clips[next].name();
  }
  poseCharacters();
  return shown;
}

std::string World::nextExpression(float seconds) {
  expressions_.resize(characters_.size(), ~std::size_t{0});
  std::string shown;
  for (std::size_t c = 0; c < characters_.size(); ++c) {
    SceneCharacter& character = characters_[c];
    const std::vector<std::string> targets = character.morphTargetNames();
    if (targets.empty()) continue;
    std::size_t& current = expressions_[c];
    // The names come from the character itself, so the blends cannot fail.
    if (current < targets.size()) (void)character.blendMorph(targets[current], 0.0f, time_, seconds);
    current = current < targets.size() ? current + 1 : 0;
    if (current < targets.size()) (void)character.blendMorph(targets[current], 1.0f, time_, seconds);
    shown += (shown.empty() ? "" : ", ") + character.instance().name + ": " +
             (current < targets.size() ? targets[current] : std::string("none"));
  }
  poseCharacters();
  return shown;
}

void World::poseCharacters() {
  for (SceneCharacter& character : characters_) character.poseAt(time_);
}

Result<physics::SurfaceBinding> World::bindToPart(std::size_t mesh, std::span<const glm::vec3> points,
                                                  const std::string& owner) {
  const CharacterPart& part = *characterParts_[mesh];
  auto deformed = characters_[part.character].deformed(part.part);
  if (!deformed) return std::unexpected(deformed.error());
  auto binding = physics::SurfaceBinding::create((*deformed)->positions, meshes_[mesh].mesh.indices, points);
  if (!binding) return fail(owner + ": binding to " + scene_.meshes[mesh].name + ": " + binding.error().message);
  return binding;
}

Result<void> World::followPart(std::size_t mesh, const physics::SurfaceBinding& binding,
                               std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals, unsigned threads) {
  const CharacterPart& part = *characterParts_[mesh];
  auto deformed = characters_[part.character].deformed(part.part, threads);
  if (!deformed) return std::unexpected(deformed.error());
  positions.resize(binding.points().size());
  normals.resize(binding.points().size());
  return binding.evaluate((*deformed)->positions, (*deformed)->normals, positions, normals, {});
}

std::vector<World::SkinnedMesh> World::skinnedMeshes() const {
  std::vector<SkinnedMesh> result;
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    if (!gpuSkins_[m]) continue;
    const CharacterPart& part = *characterParts_[m];
    const SceneCharacter& character = characters_[part.character];
    result.push_back({.mesh = m, .jointMatrices = character.jointMatricesInPartFrame(part.part),
                      .morphWeights = character.morphWeights(part.part)});
  }
  return result;
}

Result<std::vector<glm::vec3>> World::boundRoots(std::size_t index) {
  const SimulatedGroom& groom = grooms_.at(index);
  std::vector<glm::vec3> positions, normals;
  if (groom.roots)
    if (auto followed = followPart(groom.mesh, *groom.roots, positions, normals); !followed)
      return std::unexpected(followed.error());
  return positions;
}

Result<std::vector<glm::vec3>> World::boundPins(std::size_t index) {
  std::vector<glm::vec3> positions, normals;
  if (const ClothOnCharacter& follower = clothFollowers_.at(index); follower.pins)
    if (auto followed = followPart(clothBodies_[index], *follower.pins, positions, normals); !followed)
      return std::unexpected(followed.error());
  return positions;
}

}  // namespace mane::scenes
