#include "scenes/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "scenes/detail/json_fields.hpp"
#include "scenes/detail/scene_bodies.hpp"
#include "scenes/detail/scene_characters.hpp"
#include "scenes/detail/scene_materials.hpp"
#include "scenes/detail/scene_ocean.hpp"

namespace mane::scenes {
namespace {

using detail::FieldError;
using detail::ObjectFields;
using detail::parseCharacter;
using detail::parseCloth;
using detail::parseGlasses;
using detail::parseGroom;
using detail::parseHairShadows;
using detail::parseMaterial;
using detail::parsePost;
using detail::parseSubdivision;
using detail::parseTransform;
using detail::require;
using Json = nlohmann::json;

// "procedural:sphere, procedural:cube_with_hollow, ..." for error messages.
std::string knownProceduralMeshes() {
  std::string list;
  for (const std::string_view kind : kProceduralMeshKinds) {
    list += (list.empty() ? "" : ", ") + std::string(kProceduralPrefix) + std::string(kind);
  }
  return list;
}

glm::mat4 rotationMatrix(const glm::vec3& degrees) {
  const glm::vec3 r = glm::radians(degrees);
  glm::mat4 m(1.0f);
  m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
  m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
  m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
  return m;
}

glm::vec3 unitDirection(ObjectFields& fields, const std::string& key) {
  const glm::vec3 v = fields.required<glm::vec3>(key);
  const float length = glm::length(v);
  require(length > 1e-6f, fields.child(key), "expected a non-zero direction");
  return v / length;
}

OutputSettings parseOutput(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  OutputSettings output;
  output.width = fields.optional<int>("width", output.width);
  output.height = fields.optional<int>("height", output.height);
  require(output.width > 0 && output.width <= 16384, fields.child("width"), "expected a width in 1..16384 pixels");
  require(output.height > 0 && output.height <= 16384, fields.child("height"), "expected a height in 1..16384 pixels");
  fields.finish();
  return output;
}

Camera parseCamera(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Camera camera;
  camera.position = fields.required<glm::vec3>("position");
  camera.target = fields.required<glm::vec3>("target");
  camera.up = fields.optional<glm::vec3>("up", camera.up);
  camera.verticalFovDegrees = fields.optional<float>("fov_degrees", camera.verticalFovDegrees);
  camera.nearPlane = fields.optional<float>("near", camera.nearPlane);
  camera.farPlane = fields.optional<float>("far", camera.farPlane);
  if (const Json* orbit = fields.take("orbit")) {
    ObjectFields orbitFields(*orbit, path + ".orbit");
    CameraOrbit turn;
    turn.degrees = orbitFields.required<float>("degrees");
    turn.seconds = orbitFields.required<float>("seconds");
    orbitFields.finish();
    require(std::abs(turn.degrees) <= 3600.0f, orbitFields.child("degrees"), "expected a turn within ±3600 degrees");
    require(turn.seconds > 0.0f && turn.seconds <= 1e6f, orbitFields.child("seconds"),
            "expected a duration in (0, 1e6] seconds");
    camera.orbit = turn;
  }
  fields.finish();
  require(camera.verticalFovDegrees > 0.0f && camera.verticalFovDegrees < 180.0f, fields.child("fov_degrees"),
          "expected a vertical field of view in (0, 180) degrees");
  require(camera.nearPlane > 0.0f, fields.child("near"), "expected a near plane > 0 metres");
  require(camera.farPlane > camera.nearPlane, fields.child("far"), "expected a far plane beyond the near plane");
  const glm::vec3 view = camera.target - camera.position;
  require(glm::length(view) > 1e-6f, fields.child("target"), "expected a target different from the position");
  require(glm::length(glm::cross(view, camera.up)) > 1e-6f * glm::length(view), fields.child("up"),
          "expected an up vector not parallel to the view direction");
  return camera;
}

Light parseLight(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Light light;
  const std::string kind = fields.required<std::string>("kind");
  require(kind == "directional", fields.child("kind"),
          "expected \"directional\" (the only light kind so far), got \"" + kind + "\"");
  light.direction = unitDirection(fields, "direction");
  light.colour = fields.optional<glm::vec3>("colour", light.colour);
  light.intensity = fields.optional<float>("intensity", light.intensity);
  light.discRadiusDegrees = fields.optional<float>("disc_radius_degrees", light.discRadiusDegrees);
  light.discRadiance = fields.optional<float>("disc_radiance", light.discRadiance);
  fields.finish();
  require(light.colour.r >= 0 && light.colour.g >= 0 && light.colour.b >= 0, fields.child("colour"),
          "expected non-negative linear RGB");
  require(light.intensity >= 0.0f, fields.child("intensity"), "expected an intensity >= 0");
  require(light.discRadiusDegrees >= 0.0f && light.discRadiusDegrees <= 20.0f, fields.child("disc_radius_degrees"),
          "expected an angular radius in [0, 20] degrees");
  require(light.discRadiance >= 0.0f && light.discRadiance <= 1000.0f, fields.child("disc_radiance"),
          "expected a radiance in [0, 1000] (a multiple of the colour)");
  return light;
}

Environment parseEnvironment(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Environment environment;
  environment.file = fields.optional<std::string>("file", environment.file);
  if (const Json* sky = fields.take("sky")) {
    require(environment.file.empty(), fields.child("sky"), "expected a file or a sky, not both");
    ObjectFields skyFields(*sky, fields.child("sky"));
    environment.turbidity = skyFields.optional<float>("turbidity", environment.turbidity);
    environment.groundAlbedo = skyFields.optional<float>("ground_albedo", environment.groundAlbedo);
    skyFields.finish();
    require(environment.turbidity >= 1.7f && environment.turbidity <= 10.0f, skyFields.child("turbidity"),
            "expected a turbidity in [1.7, 10] (2: clear, 6: hazy)");
    require(environment.groundAlbedo >= 0.0f && environment.groundAlbedo <= 1.0f, skyFields.child("ground_albedo"),
            "expected an albedo in [0, 1]");
  }
  environment.rotationDegrees = fields.optional<float>("rotation_degrees", environment.rotationDegrees);
  environment.intensity = fields.optional<float>("intensity", environment.intensity);
  environment.cubeSize = fields.optional<int>("cube_size", environment.cubeSize);
  environment.sunLight = fields.optional<bool>("sun_light", environment.sunLight);
  fields.finish();
  require(!environment.sunLight || !environment.file.empty(), fields.child("sun_light"),
          "expected a panorama file to cut the sun from (the sky's sun is the first light already)");
  require(std::isfinite(environment.rotationDegrees), fields.child("rotation_degrees"), "expected a finite angle");
  require(environment.intensity >= 0.0f && environment.intensity <= 1000.0f, fields.child("intensity"),
          "expected an intensity in [0, 1000]");
  require(environment.cubeSize == 0 || (environment.cubeSize >= 8 && environment.cubeSize <= 2048),
          fields.child("cube_size"), "expected 8 to 2048 texels (or 0: the default)");
  return environment;
}

MeshSimplification parseSimplification(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  MeshSimplification simplify;
  simplify.triangles = fields.required<int>("triangles");
  require(simplify.triangles >= 1, fields.child("triangles"), "expected at least 1 triangle");
  simplify.maxRelativeError = fields.optional<float>("max_error", simplify.maxRelativeError);
  require(simplify.maxRelativeError > 0.0f && simplify.maxRelativeError <= 1.0f, fields.child("max_error"),
          "expected an error in (0, 1] of the mesh's extent");
  fields.finish();
  return simplify;
}

MeshInstance parseMesh(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  MeshInstance mesh;
  mesh.name = fields.required<std::string>("name");
  require(!mesh.name.empty(), fields.child("name"), "expected a non-empty name");
  mesh.source = fields.required<std::string>("source");
  require(!mesh.source.empty(), fields.child("source"), "expected an asset name or \"procedural:<kind>\"");
  if (mesh.isProcedural()) {
    require(std::ranges::find(kProceduralMeshKinds, mesh.proceduralKind()) != kProceduralMeshKinds.end(),
            fields.child("source"),
            "unknown procedural mesh \"" + mesh.source + "\" (known: " + knownProceduralMeshes() + ")");
  }
  mesh.material = fields.optional<std::string>("material", "");
  mesh.attachedMesh = fields.optional<std::string>("attached_mesh", "");
  if (const Json* transform = fields.take("transform")) {
    mesh.transform = parseTransform(*transform, fields.child("transform"));
  }
  if (const Json* subdivision = fields.take("subdivision")) {
    mesh.subdivision = parseSubdivision(*subdivision, fields.child("subdivision"));
  }
  if (const Json* simplify = fields.take("simplify")) {
    require(!mesh.subdivision, fields.child("simplify"),
            "a subdivided mesh is drawn from its limit surface: simplify its cage instead");
    mesh.simplify = parseSimplification(*simplify, fields.child("simplify"));
  }
  fields.finish();
  return mesh;
}

HeadMotion parseHeadMotion(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  HeadMotion motion;
  motion.mesh = fields.required<std::string>("mesh");
  const std::string kind = fields.required<std::string>("motion");
  if (kind == "none") {
    motion.kind = HeadMotionKind::none;
  } else if (kind == "turn") {
    motion.kind = HeadMotionKind::turn;
  } else if (kind == "nod") {
    motion.kind = HeadMotionKind::nod;
  } else if (kind == "shake") {
    motion.kind = HeadMotionKind::shake;
  } else if (kind == "keyframes") {
    motion.kind = HeadMotionKind::keyframes;
  } else {
    throw FieldError{fields.child("motion"),
                     "expected one of \"none\", \"turn\", \"nod\", "
                     "\"shake\", \"keyframes\", got \"" +
                         kind + "\""};
  }
  const bool periodic =
      motion.kind == HeadMotionKind::turn || motion.kind == HeadMotionKind::nod || motion.kind == HeadMotionKind::shake;
  if (periodic) {
    motion.amplitudeDegrees = fields.required<float>("amplitude_degrees");
    motion.frequencyHz = fields.required<float>("frequency_hz");
    require(motion.frequencyHz >= 0.0f, fields.child("frequency_hz"), "expected a frequency >= 0 Hz");
  }
  if (motion.kind == HeadMotionKind::keyframes) {
    const Json& keys = fields.array("keyframes", true);
    require(!keys.empty(), fields.child("keyframes"), "expected at least one keyframe");
    for (std::size_t i = 0; i < keys.size(); ++i) {
      ObjectFields key(keys[i], detail::indexPath(fields.child("keyframes"), i));
      Keyframe frame;
      frame.timeSeconds = key.required<float>("time");
      frame.rotationDegrees = key.optional<glm::vec3>("rotation_degrees", frame.rotationDegrees);
      frame.translation = key.optional<glm::vec3>("translation", frame.translation);
      key.finish();
      require(motion.keyframes.empty() || frame.timeSeconds > motion.keyframes.back().timeSeconds, key.child("time"),
              "expected times in strictly increasing order");
      motion.keyframes.push_back(frame);
    }
    motion.loop = fields.optional<bool>("loop", false);
    require(!motion.loop || motion.keyframes.size() >= 2, fields.child("loop"),
            "expected at least two keyframes to loop over");
  }
  fields.finish();
  return motion;
}

SimulationSettings parseSimulation(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  SimulationSettings sim;
  sim.stepSeconds = fields.optional<float>("step", sim.stepSeconds);
  sim.maxStepsPerFrame = fields.optional<int>("max_steps_per_frame", sim.maxStepsPerFrame);
  sim.settleSeconds = fields.optional<float>("settle_seconds", sim.settleSeconds);
  fields.finish();
  require(sim.stepSeconds > 0.0f && sim.stepSeconds <= 0.1f, fields.child("step"),
          "expected a time step in (0, 0.1] seconds");
  require(sim.maxStepsPerFrame >= 1 && sim.maxStepsPerFrame <= 1000, fields.child("max_steps_per_frame"),
          "expected 1..1000");
  require(sim.settleSeconds >= 0.0f && sim.settleSeconds <= 10.0f, fields.child("settle_seconds"),
          "expected 0..10 seconds");
  return sim;
}

std::string noMesh(const std::string& name) {
  return "no mesh named \"" + name + "\" in meshes, nor a character part \"<character>/<mesh>\" of characters";
}

bool isCharacterPart(const std::string& name) { return name.find(kCharacterPartSeparator) != std::string::npos; }

// Joint-bound shapes need a character to take their joints from: the body's own.
void checkColliderReferences(const Scene& scene, const Colliders& colliders, const std::string& body,
                             const std::string& path) {
  if (colliders.sdf) require(scene.namesMesh(colliders.sdf->mesh), path + ".sdf.mesh", noMesh(colliders.sdf->mesh));
  if (colliders.followsJoints()) {
    require(isCharacterPart(body), path,
            "shapes with a \"joint\" need a body that is a character part (attached_mesh \"<character>/<mesh>\")");
  }
}

/// Names must be unique and references must point at something.
void checkReferences(const Scene& scene) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    require(names.insert(scene.materials[i].name).second, "materials[" + std::to_string(i) + "].name",
            "duplicate material name \"" + scene.materials[i].name + "\"");
  }
  names.clear();
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshInstance& mesh = scene.meshes[i];
    const std::string path = "meshes[" + std::to_string(i) + "]";
    require(names.insert(mesh.name).second, path + ".name", "duplicate mesh name \"" + mesh.name + "\"");
    if (!mesh.attachedMesh.empty()) {
      const MeshInstance* body = scene.findMesh(mesh.attachedMesh);
      require(body != nullptr && body != &mesh, path + ".attached_mesh",
              "no other mesh named \"" + mesh.attachedMesh + "\" in meshes");
      require(body->attachedMesh.empty(), path + ".attached_mesh",
              "\"" + mesh.attachedMesh + "\" rides on another mesh itself: attach to the one it rides on");
      require(!mesh.subdivision, path + ".attached_mesh", "a subdivided mesh cannot ride on another");
    }
    require(mesh.material.empty() || scene.findMaterial(mesh.material), path + ".material",
            "no material named \"" + mesh.material + "\" in materials");
    require(!isCharacterPart(mesh.name), path + ".name", "expected a name without '/' (kept for character parts)");
  }
  names.clear();
  for (std::size_t i = 0; i < scene.characters.size(); ++i) {
    const CharacterInstance& character = scene.characters[i];
    const std::string path = "characters[" + std::to_string(i) + "]";
    require(names.insert(character.name).second, path + ".name",
            "duplicate character name \"" + character.name + "\"");
    require(character.material.empty() || scene.findMaterial(character.material), path + ".material",
            "no material named \"" + character.material + "\" in materials");
    for (const auto& [gltfMaterial, material] : character.materials)
      require(scene.findMaterial(material), path + ".materials." + gltfMaterial,
              "no material named \"" + material + "\" in materials");
  }
  for (std::size_t i = 0; i < scene.grooms.size(); ++i) {
    const Groom& groom = scene.grooms[i];
    const std::string path = "grooms[" + std::to_string(i) + "]";
    require(scene.namesMesh(groom.attachedMesh), path + ".attached_mesh", noMesh(groom.attachedMesh));
    checkColliderReferences(scene, groom.colliders, groom.attachedMesh, path + ".colliders");
  }
  for (std::size_t i = 0; i < scene.cloths.size(); ++i) {
    const Cloth& cloth = scene.cloths[i];
    const std::string path = "cloths[" + std::to_string(i) + "]";
    require(scene.namesMesh(cloth.attachedMesh), path + ".attached_mesh", noMesh(cloth.attachedMesh));
    require(cloth.material.empty() || scene.findMaterial(cloth.material), path + ".material",
            "no material named \"" + cloth.material + "\" in materials");
    require(cloth.material.empty() || scene.findMaterial(cloth.material)->kind != MaterialKind::fur, path + ".material",
            "fur grows on meshes, not on cloth (its shells need a mesh that does not deform)");
    checkColliderReferences(scene, cloth.colliders, cloth.attachedMesh, path + ".colliders");
  }
  names.clear();
  for (std::size_t i = 0; i < scene.glasses.size(); ++i) {
    const Glasses& glasses = scene.glasses[i];
    const std::string path = "glasses[" + std::to_string(i) + "]";
    require(names.insert(glasses.name).second, path + ".name", "duplicate glasses name \"" + glasses.name + "\"");
    require(scene.namesMesh(glasses.attachedMesh), path + ".attached_mesh", noMesh(glasses.attachedMesh));
    require(glasses.material.empty() || scene.findMaterial(glasses.material), path + ".material",
            "no material named \"" + glasses.material + "\" in materials");
    require(glasses.material.empty() || scene.findMaterial(glasses.material)->kind != MaterialKind::fur,
            path + ".material", "fur grows on meshes, not on a spectacle frame");
  }
  if (scene.ship) {
    require(scene.ocean.has_value(), "ship", "a ship floats on an ocean: the scene has none");
    const MeshInstance* hull = scene.findMesh(scene.ship->mesh);
    require(hull != nullptr, "ship.mesh", "no mesh named \"" + scene.ship->mesh + "\" in meshes");
    require(hull->transform.rotationDegrees.x == 0.0f && hull->transform.rotationDegrees.z == 0.0f, "ship.mesh",
            "the ship's mesh may turn about +Y only (its rotation's x and z must be 0)");
    require(!hull->subdivision, "ship.mesh", "a subdivided mesh cannot float (its triangles change with the view)");
    require(scene.headMotion.kind == HeadMotionKind::none || scene.headMotion.mesh != scene.ship->mesh, "ship.mesh",
            "the sea moves the ship; the head motion cannot move it too");
  }
  if (scene.headMotion.kind != HeadMotionKind::none) {
    require(scene.findMesh(scene.headMotion.mesh) != nullptr, "animation.head.mesh",
            "no mesh named \"" + scene.headMotion.mesh + "\" in meshes");
  }
  require(scene.post.godRayLight == 0 || scene.post.godRayLight < scene.lights.size(), "post.god_ray_light",
          "no light " + std::to_string(scene.post.godRayLight) + " in lights (it has " +
              std::to_string(scene.lights.size()) + ")");
}

Scene parseRoot(const Json& json) {
  ObjectFields fields(json, "");
  Scene scene;
  scene.name = fields.required<std::string>("name");
  if (const Json* output = fields.take("output")) scene.output = parseOutput(*output, "output");
  const Json* camera = fields.take("camera");
  if (!camera) throw FieldError{"camera", "required field is missing"};
  scene.camera = parseCamera(*camera, "camera");
  scene.lights = parseList<Light>(fields, "lights", parseLight);
  if (const Json* environment = fields.take("environment"))
    scene.environment = parseEnvironment(*environment, "environment");
  scene.materials = parseList<Material>(fields, "materials", parseMaterial);
  scene.meshes = parseList<MeshInstance>(fields, "meshes", parseMesh);
  scene.grooms = parseList<Groom>(fields, "grooms", parseGroom);
  scene.cloths = parseList<Cloth>(fields, "cloths", parseCloth);
  scene.characters = parseList<CharacterInstance>(fields, "characters", parseCharacter);
  scene.glasses = parseList<Glasses>(fields, "glasses", parseGlasses);
  if (const Json* ocean = fields.take("ocean")) scene.ocean = detail::parseOcean(*ocean, "ocean");
  if (const Json* ship = fields.take("ship")) scene.ship = detail::parseShip(*ship, "ship");
  if (const Json* animation = fields.take("animation")) {
    ObjectFields anim(*animation, "animation");
    if (const Json* head = anim.take("head")) scene.headMotion = parseHeadMotion(*head, "animation.head");
    anim.finish();
  }
  if (const Json* sim = fields.take("simulation")) {
    scene.simulation = parseSimulation(*sim, "simulation");
  }
  if (const Json* shadows = fields.take("hair_shadows")) scene.hairShadows = parseHairShadows(*shadows, "hair_shadows");
  if (const Json* post = fields.take("post")) scene.post = parsePost(*post, "post");
  fields.finish();
  checkReferences(scene);
  return scene;
}

}  // namespace

namespace detail {

Subdivision parseSubdivision(const nlohmann::json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Subdivision subdivision;
  subdivision.maxPixelError = fields.optional<float>("max_pixel_error", subdivision.maxPixelError);
  require(subdivision.maxPixelError > 0.0f && subdivision.maxPixelError <= kMaxSubdivisionPixelError,
          fields.child("max_pixel_error"),
          "expected a pixel error in (0, " + std::to_string(int(kMaxSubdivisionPixelError)) + "]");
  const std::string levels = std::to_string(kMinSubdivisionLevel) + ".." + std::to_string(kMaxSubdivisionLevel);
  subdivision.isolation = fields.optional<int>("isolation", subdivision.isolation);
  require(subdivision.isolation >= kMinSubdivisionLevel && subdivision.isolation <= kMaxSubdivisionLevel,
          fields.child("isolation"), "expected an isolation level in " + levels);
  subdivision.maxDepth = fields.optional<int>("max_depth", subdivision.maxDepth);
  require(subdivision.maxDepth >= kMinSubdivisionLevel && subdivision.maxDepth <= kMaxSubdivisionLevel,
          fields.child("max_depth"), "expected a depth in " + levels);
  subdivision.capHoles = fields.optional<bool>("cap_holes", subdivision.capHoles);
  if (const Json* coarseCage = fields.take("coarse_cage"))
    subdivision.coarseCage = parseSimplification(*coarseCage, fields.child("coarse_cage"));
  fields.finish();
  return subdivision;
}

}  // namespace detail

glm::mat4 Transform::matrix() const {
  return glm::translate(glm::mat4(1.0f), translation) * rotationMatrix(rotationDegrees) *
         glm::scale(glm::mat4(1.0f), glm::vec3(scale));
}

std::string MeshInstance::proceduralKind() const {
  return isProcedural() ? source.substr(kProceduralPrefix.size()) : std::string();
}

Keyframe HeadMotion::poseAt(float timeSeconds) const {
  Keyframe pose;
  pose.timeSeconds = timeSeconds;
  const float phase = 2.0f * std::numbers::pi_v<float> * frequencyHz * timeSeconds;
  switch (kind) {
    case HeadMotionKind::none: break;
    case HeadMotionKind::turn: pose.rotationDegrees.y = amplitudeDegrees * std::sin(phase); break;
    case HeadMotionKind::nod: pose.rotationDegrees.x = amplitudeDegrees * std::sin(phase); break;
    case HeadMotionKind::shake:
      pose.rotationDegrees.y = amplitudeDegrees * std::sin(phase);
      pose.rotationDegrees.x = 0.25f * amplitudeDegrees * std::sin(2.0f * phase);
      break;
    case HeadMotionKind::keyframes: {
      if (keyframes.empty()) break;
      const float first = keyframes.front().timeSeconds, last = keyframes.back().timeSeconds;
      if (loop && timeSeconds > last) timeSeconds = first + std::fmod(timeSeconds - first, last - first);
      if (timeSeconds <= keyframes.front().timeSeconds) return keyframes.front();
      if (timeSeconds >= keyframes.back().timeSeconds) return keyframes.back();
      const auto next = std::upper_bound(keyframes.begin(), keyframes.end(), timeSeconds,
                                         [](float t, const Keyframe& k) { return t < k.timeSeconds; });
      const Keyframe& a = *(next - 1);
      const Keyframe& b = *next;
      const float s = (timeSeconds - a.timeSeconds) / (b.timeSeconds - a.timeSeconds);
      pose.rotationDegrees = glm::mix(a.rotationDegrees, b.rotationDegrees, s);
      pose.translation = glm::mix(a.translation, b.translation, s);
      break;
    }
  }
  return pose;
}

const Material* Scene::findMaterial(std::string_view name) const {
  for (const Material& m : materials) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

const CharacterInstance* Scene::findCharacter(std::string_view name) const {
  for (const CharacterInstance& c : characters) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

bool Scene::namesMesh(std::string_view name) const {
  const std::size_t separator = name.find(kCharacterPartSeparator);
  if (separator == std::string_view::npos) return findMesh(name) != nullptr;
  return findCharacter(name.substr(0, separator)) != nullptr && separator + 1 < name.size();
}

float MorphTrack::weightAt(float timeSeconds) const {
  if (keys.empty()) return 0.0f;
  if (timeSeconds <= keys.front().timeSeconds) return keys.front().weight;
  if (timeSeconds >= keys.back().timeSeconds) return keys.back().weight;
  const auto next = std::upper_bound(keys.begin(), keys.end(), timeSeconds,
                                     [](float t, const MorphKey& k) { return t < k.timeSeconds; });
  const MorphKey& a = *(next - 1);
  const MorphKey& b = *next;
  return glm::mix(a.weight, b.weight, (timeSeconds - a.timeSeconds) / (b.timeSeconds - a.timeSeconds));
}

const MeshInstance* Scene::findMesh(std::string_view name) const {
  for (const MeshInstance& m : meshes) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

glm::mat4 animatedMatrix(const Scene& scene, const MeshInstance& mesh, float timeSeconds) {
  if (scene.headMotion.kind == HeadMotionKind::none || scene.headMotion.mesh != mesh.name) {
    return mesh.transform.matrix();
  }
  const Keyframe pose = scene.headMotion.poseAt(timeSeconds);
  const Transform& t = mesh.transform;
  // The head turns about its own placed origin: motion rotation after the mesh's rotation.
  return glm::translate(glm::mat4(1.0f), t.translation + pose.translation) * rotationMatrix(pose.rotationDegrees) *
         rotationMatrix(t.rotationDegrees) * glm::scale(glm::mat4(1.0f), glm::vec3(t.scale));
}

glm::mat4 bodyMatrix(const Scene& scene, const MeshInstance& mesh, float timeSeconds) {
  return animatedMatrix(scene, mesh, timeSeconds) * glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / mesh.transform.scale));
}

Result<Scene> parseScene(std::string_view text, const std::filesystem::path& file) {
  const std::string name = file.string();
  Json json;
  try {
    json = Json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::exception& e) {
    // parse_error for bad syntax, out_of_range for a number too large for a double (1e400).
    return fail(name + ": invalid JSON: " + e.what());
  }
  try {
    Scene scene = parseRoot(json);
    scene.file = file;
    return scene;
  } catch (const FieldError& e) {
    return fail(name + ": " + e.path + ": " + e.message);
  } catch (const nlohmann::json::exception& e) {
    return fail(name + ": " + e.what());
  }
}

Result<Scene> loadScene(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) return fail(file.string() + ": cannot open the scene file (does it exist?)");
  std::ostringstream text;
  text << stream.rdbuf();
  return parseScene(text.str(), file);
}

glm::vec3 cameraPositionAt(const Camera& camera, double seconds) {
  if (!camera.orbit || !(seconds > 0.0)) return camera.position;
  const double progress = std::min(seconds / double(camera.orbit->seconds), 1.0);
  const double eased = 0.5 * (1.0 - std::cos(std::numbers::pi * progress));
  const float angle = glm::radians(camera.orbit->degrees) * float(eased);
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), angle, glm::normalize(camera.up));
  return camera.target + glm::vec3(turn * glm::vec4(camera.position - camera.target, 0.0f));
}

}  // namespace mane::scenes
