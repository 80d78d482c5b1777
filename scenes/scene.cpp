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

namespace mane::scenes {
namespace {

using detail::FieldError;
using detail::ObjectFields;
using Json = nlohmann::json;

// Procedural mesh kinds the loader can build (scenes/procedural.hpp).
const std::set<std::string> kProceduralMeshKinds = {"sphere"};

glm::mat4 rotationMatrix(const glm::vec3& degrees) {
  const glm::vec3 r = glm::radians(degrees);
  glm::mat4 m(1.0f);
  m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
  m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
  m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
  return m;
}

void require(bool condition, const std::string& path, const std::string& message) {
  if (!condition) throw FieldError{path, message};
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
  fields.finish();
  require(light.colour.r >= 0 && light.colour.g >= 0 && light.colour.b >= 0, fields.child("colour"),
          "expected non-negative linear RGB");
  require(light.intensity >= 0.0f, fields.child("intensity"), "expected an intensity >= 0");
  return light;
}

// Skin shading parameters (render::SkinParameters).
render::SkinParameters parseSkinParameters(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  render::SkinParameters skin;
  const std::string range = fields.optional<std::string>("range", "curvature");
  require(range == "curvature" || range == "penner", fields.child("range"),
          "expected \"curvature\" or \"penner\", got \"" + range + "\"");
  skin.range = range == "penner" ? render::SkinIntegrationRange::kPenner : render::SkinIntegrationRange::kCurvature;
  skin.roughness = fields.optional<float>("roughness", skin.roughness);
  skin.specularIntensity = fields.optional<float>("specular_intensity", skin.specularIntensity);
  fields.finish();
  require(skin.roughness > 0.0f && skin.roughness <= 1.0f, fields.child("roughness"),
          "expected a Beckmann roughness in (0, 1]");
  require(skin.specularIntensity >= 0.0f && skin.specularIntensity <= 10.0f, fields.child("specular_intensity"),
          "expected a specular intensity in [0, 10]");
  return skin;
}

Material parseMaterial(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Material material;
  material.name = fields.required<std::string>("name");
  require(!material.name.empty(), fields.child("name"), "expected a non-empty name");
  const std::string kind = fields.optional<std::string>("kind", "lambert");
  require(kind == "lambert" || kind == "skin", fields.child("kind"),
          "expected \"lambert\" or \"skin\", got \"" + kind + "\"");
  material.kind = kind == "skin" ? MaterialKind::skin : MaterialKind::lambert;
  if (const Json* skin = fields.take("skin")) {
    require(material.kind == MaterialKind::skin, fields.child("skin"), "applies to materials of kind \"skin\" only");
    material.skin = parseSkinParameters(*skin, fields.child("skin"));
  }
  material.albedoTexture = fields.optional<std::string>("albedo_texture", "");
  material.normalMap = fields.optional<std::string>("normal_map", "");
  material.specularMap = fields.optional<std::string>("specular_map", "");
  material.baseColour = fields.optional<glm::vec3>("base_colour", material.baseColour);
  fields.finish();
  return material;
}

Transform parseTransform(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Transform transform;
  transform.translation = fields.optional<glm::vec3>("translation", transform.translation);
  transform.rotationDegrees = fields.optional<glm::vec3>("rotation_degrees", transform.rotationDegrees);
  transform.scale = fields.optional<float>("scale", transform.scale);
  require(transform.scale > 0.0f, fields.child("scale"), "expected a uniform scale > 0");
  fields.finish();
  return transform;
}

MeshInstance parseMesh(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  MeshInstance mesh;
  mesh.name = fields.required<std::string>("name");
  require(!mesh.name.empty(), fields.child("name"), "expected a non-empty name");
  mesh.source = fields.required<std::string>("source");
  require(!mesh.source.empty(), fields.child("source"), "expected an asset name or \"procedural:<kind>\"");
  if (mesh.isProcedural()) {
    require(kProceduralMeshKinds.contains(mesh.proceduralKind()), fields.child("source"),
            "unknown procedural mesh \"" + mesh.source + "\" (known: procedural:sphere)");
  }
  mesh.material = fields.optional<std::string>("material", "");
  if (const Json* transform = fields.take("transform")) {
    mesh.transform = parseTransform(*transform, fields.child("transform"));
  }
  fields.finish();
  return mesh;
}

HairSimulation parseHairSimulation(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  HairSimulation sim;
  sim.iterations = fields.optional<int>("iterations", sim.iterations);
  sim.damping = fields.optional<float>("damping", sim.damping);
  sim.gravity = fields.optional<glm::vec3>("gravity", sim.gravity);
  sim.shapeStiffness = fields.optional<float>("shape_stiffness", sim.shapeStiffness);
  fields.finish();
  require(sim.iterations >= 1 && sim.iterations <= 1000, fields.child("iterations"), "expected 1..1000 iterations");
  require(sim.shapeStiffness >= 0.0f && sim.shapeStiffness <= 1.0f, fields.child("shape_stiffness"),
          "expected a shape stiffness in [0, 1]");
  require(sim.damping >= 0.0f && sim.damping < 1.0f, fields.child("damping"), "expected a damping in [0, 1)");
  return sim;
}

template <class T, class Parse>
std::vector<T> parseList(ObjectFields& fields, const std::string& key, Parse parse) {
  std::vector<T> out;
  const Json& items = fields.array(key, false);
  for (std::size_t i = 0; i < items.size(); ++i) {
    out.push_back(parse(items[i], detail::indexPath(fields.child(key), i)));
  }
  return out;
}

physics::SphereCollider parseSphereCollider(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  // Unknown fields first: "center" for "centre" is then reported as the typo it is.
  for (const char* key : {"centre", "radius"}) fields.take(key);
  fields.finish();
  physics::SphereCollider sphere;
  sphere.centre = fields.required<glm::vec3>("centre");
  sphere.radius = fields.required<float>("radius");
  require(sphere.radius > 0.0f, fields.child("radius"), "expected a radius > 0 metres");
  return sphere;
}

physics::CapsuleCollider parseCapsuleCollider(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  for (const char* key : {"a", "b", "radius"}) fields.take(key);
  fields.finish();
  physics::CapsuleCollider capsule;
  capsule.a = fields.required<glm::vec3>("a");
  capsule.b = fields.required<glm::vec3>("b");
  capsule.radius = fields.required<float>("radius");
  require(capsule.radius > 0.0f, fields.child("radius"), "expected a radius > 0 metres");
  return capsule;
}

SdfColliderSource parseSdfCollider(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  for (const char* key : {"mesh", "resolution"}) fields.take(key);
  fields.finish();
  SdfColliderSource sdf;
  sdf.mesh = fields.required<std::string>("mesh");
  require(!sdf.mesh.empty(), fields.child("mesh"), "expected the name of a mesh in meshes");
  sdf.resolution = fields.optional<int>("resolution", sdf.resolution);
  require(sdf.resolution >= kMinSdfResolution && sdf.resolution <= kMaxSdfResolution, fields.child("resolution"),
          "expected a resolution in " + std::to_string(kMinSdfResolution) + ".." + std::to_string(kMaxSdfResolution) +
              " grid nodes");
  return sdf;
}

// Shapes in the attached body's frame (scenes/README.md, "Colliders").
Colliders parseColliders(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Colliders colliders;
  colliders.spheres = parseList<physics::SphereCollider>(fields, "spheres", parseSphereCollider);
  colliders.capsules = parseList<physics::CapsuleCollider>(fields, "capsules", parseCapsuleCollider);
  if (const Json* sdf = fields.take("sdf")) colliders.sdf = parseSdfCollider(*sdf, fields.child("sdf"));
  colliders.friction = fields.optional<float>("friction", colliders.friction);
  colliders.thickness = fields.optional<float>("thickness", colliders.thickness);
  fields.finish();
  require(colliders.friction >= 0.0f, fields.child("friction"), "expected a friction coefficient >= 0");
  require(colliders.thickness >= 0.0f && colliders.thickness <= 1.0f, fields.child("thickness"),
          "expected a thickness in [0, 1] metres");
  return colliders;
}

// "procedural", one groom file, or several whose guides make one groom.
std::vector<std::string> parseGroomSources(ObjectFields& fields) {
  const std::string path = fields.child("source");
  const Json* source = fields.take("source");
  if (!source) throw FieldError{path, "required field is missing"};
  if (source->is_string()) {
    const std::string name = source->get<std::string>();
    require(!name.empty(), path, "expected a .tfx/.hair asset name or \"procedural\"");
    return {name};
  }
  require(source->is_array(), path,
          "expected a .tfx/.hair asset name, an array of them or \"procedural\"" + detail::got(*source));
  require(!source->empty(), path, "expected at least one .tfx/.hair asset name");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < source->size(); ++i) {
    const std::string itemPath = detail::indexPath(path, i);
    names.push_back(detail::read<std::string>((*source)[i], itemPath));
    require(!names.back().empty(), itemPath, "expected a .tfx/.hair asset name");
    require(names.back() != "procedural", itemPath,
            "\"procedural\" cannot be combined with groom files (write \"source\": \"procedural\")");
  }
  return names;
}

// How the groom is drawn; the ranges are those render::HairGroomSettings documents.
GroomRendering parseGroomRendering(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  GroomRendering rendering;
  render::HairGroomSettings& settings = rendering.settings;
  const std::string look = fields.optional<std::string>("look", "blonde");
  require(look == "blonde" || look == "dark", fields.child("look"),
          "expected \"blonde\" or \"dark\", got \"" + look + "\"");
  rendering.look = look == "dark" ? render::HairLook::kDark : render::HairLook::kBlonde;
  settings.width = fields.optional<float>("width", settings.width);
  settings.tipWidthScale = fields.optional<float>("tip_width_scale", settings.tipWidthScale);
  settings.opacity = fields.optional<float>("opacity", settings.opacity);
  settings.minimumPixelWidth = fields.optional<float>("min_pixel_width", settings.minimumPixelWidth);
  settings.shadowExtinction = fields.optional<float>("shadow_extinction", settings.shadowExtinction);
  const Json* strands = fields.take("strands");
  if (strands) rendering.denseStrands = detail::read<int>(*strands, fields.child("strands"));
  fields.finish();
  require(!strands || (rendering.denseStrands >= 1 && rendering.denseStrands <= kMaxDenseStrands),
          fields.child("strands"), "expected a dense strand count in 1.." + std::to_string(kMaxDenseStrands));
  require(settings.width > 0.0f && settings.width <= 0.01f, fields.child("width"),
          "expected a root width in (0, 0.01] metres");
  require(settings.tipWidthScale >= 0.0f && settings.tipWidthScale <= 1.0f, fields.child("tip_width_scale"),
          "expected a tip width scale in [0, 1]");
  // Not 0: a groom's strands add its opacity to the shadow maps, which need it positive.
  require(settings.opacity > 0.0f && settings.opacity <= 1.0f, fields.child("opacity"),
          "expected an opacity in (0, 1]");
  require(settings.minimumPixelWidth >= 0.25f, fields.child("min_pixel_width"),
          "expected a minimum width >= 0.25 pixels");
  require(settings.shadowExtinction > 0.0f, fields.child("shadow_extinction"), "expected a shadow extinction > 0");
  return rendering;
}

Groom parseGroom(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Groom groom;
  groom.name = fields.required<std::string>("name");
  groom.sources = parseGroomSources(fields);
  groom.attachedMesh = fields.required<std::string>("attached_mesh");
  groom.strandCount = fields.optional<int>("strands", 0);
  groom.strandLengthMetres = fields.optional<float>("length", 0.0f);
  require(groom.strandCount >= 0 && groom.strandCount <= kMaxGuideStrands, fields.child("strands"),
          "expected a strand count in 0.." + std::to_string(kMaxGuideStrands));
  require(groom.strandLengthMetres >= 0.0f && groom.strandLengthMetres <= 10.0f, fields.child("length"),
          "expected a length in [0, 10] metres");
  groom.invertZ = fields.optional<bool>("invert_z", false);
  require(!groom.invertZ || !groom.isProcedural(), fields.child("invert_z"),
          "applies to groom files only, not to \"procedural\"");
  if (const Json* sim = fields.take("simulation")) {
    groom.simulation = parseHairSimulation(*sim, fields.child("simulation"));
  }
  if (const Json* colliders = fields.take("colliders")) {
    groom.colliders = parseColliders(*colliders, fields.child("colliders"));
  }
  if (const Json* rendering = fields.take("render")) {
    groom.rendering = parseGroomRendering(*rendering, fields.child("render"));
  }
  fields.finish();
  return groom;
}

Cloth parseCloth(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Cloth cloth;
  cloth.name = fields.required<std::string>("name");
  require(!cloth.name.empty(), fields.child("name"), "expected a non-empty name");
  cloth.source = fields.required<std::string>("source");
  require(!cloth.source.empty() && (!cloth.source.starts_with(kProceduralPrefix) || cloth.source == "procedural:grid"),
          fields.child("source"), "expected a mesh asset, a file path or \"procedural:grid\"");
  cloth.attachedMesh = fields.required<std::string>("attached_mesh");
  cloth.material = fields.optional<std::string>("material", "");
  if (const Json* transform = fields.take("transform")) {
    cloth.transform = parseTransform(*transform, fields.child("transform"));
  }
  const std::string pinned = fields.optional<std::string>("pinned", "top_edge");
  require(pinned == "top_edge" || pinned == "none", fields.child("pinned"),
          "expected \"top_edge\" or \"none\", got \"" + pinned + "\"");
  cloth.pinTopEdge = pinned == "top_edge";
  if (const Json* sim = fields.take("simulation")) {
    ObjectFields simFields(*sim, fields.child("simulation"));
    cloth.iterations = simFields.optional<int>("iterations", cloth.iterations);
    cloth.damping = simFields.optional<float>("damping", cloth.damping);
    cloth.bendingStiffness = simFields.optional<float>("bending", cloth.bendingStiffness);
    cloth.gravity = simFields.optional<glm::vec3>("gravity", cloth.gravity);
    simFields.finish();
    require(cloth.iterations >= 1 && cloth.iterations <= 1000, simFields.child("iterations"),
            "expected 1..1000 iterations");
    require(cloth.damping >= 0.0f && cloth.damping < 1.0f, simFields.child("damping"), "expected a damping in [0, 1)");
    require(cloth.bendingStiffness >= 0.0f && cloth.bendingStiffness <= 1.0f, simFields.child("bending"),
            "expected a bending stiffness in [0, 1]");
  }
  if (const Json* colliders = fields.take("colliders")) {
    cloth.colliders = parseColliders(*colliders, fields.child("colliders"));
  }
  fields.finish();
  return cloth;
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

render::HairShadowSettings parseHairShadows(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  render::HairShadowSettings shadows;
  const std::string mode = fields.optional<std::string>("mode", "opacity");
  if (mode == "opacity") {
    shadows.mode = render::HairShadowMode::kOpacityShadowMap;
  } else if (mode == "deep") {
    shadows.mode = render::HairShadowMode::kDeepOpacityMap;
  } else if (mode == "off") {
    shadows.mode = render::HairShadowMode::kOff;
  } else {
    throw FieldError{fields.child("mode"), "expected \"opacity\", \"deep\" or \"off\", got \"" + mode + "\""};
  }
  const int resolution = fields.optional<int>("resolution", static_cast<int>(shadows.resolution));
  fields.finish();
  require(resolution >= kMinHairShadowResolution && resolution <= kMaxHairShadowResolution, fields.child("resolution"),
          "expected a resolution in " + std::to_string(kMinHairShadowResolution) + ".." +
              std::to_string(kMaxHairShadowResolution) + " texels");
  shadows.resolution = static_cast<std::uint32_t>(resolution);
  return shadows;
}

void checkColliderReferences(const Scene& scene, const Colliders& colliders, const std::string& path) {
  if (colliders.sdf) {
    require(scene.findMesh(colliders.sdf->mesh) != nullptr, path + ".sdf.mesh",
            "no mesh named \"" + colliders.sdf->mesh + "\" in meshes");
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
    require(mesh.material.empty() || scene.findMaterial(mesh.material), path + ".material",
            "no material named \"" + mesh.material + "\" in materials");
  }
  for (std::size_t i = 0; i < scene.grooms.size(); ++i) {
    const Groom& groom = scene.grooms[i];
    const std::string path = "grooms[" + std::to_string(i) + "]";
    require(scene.findMesh(groom.attachedMesh) != nullptr, path + ".attached_mesh",
            "no mesh named \"" + groom.attachedMesh + "\" in meshes");
    checkColliderReferences(scene, groom.colliders, path + ".colliders");
  }
  for (std::size_t i = 0; i < scene.cloths.size(); ++i) {
    const Cloth& cloth = scene.cloths[i];
    const std::string path = "cloths[" + std::to_string(i) + "]";
    require(scene.findMesh(cloth.attachedMesh) != nullptr, path + ".attached_mesh",
            "no mesh named \"" + cloth.attachedMesh + "\" in meshes");
    require(cloth.material.empty() || scene.findMaterial(cloth.material), path + ".material",
            "no material named \"" + cloth.material + "\" in materials");
    checkColliderReferences(scene, cloth.colliders, path + ".colliders");
  }
  if (scene.headMotion.kind != HeadMotionKind::none) {
    require(scene.findMesh(scene.headMotion.mesh) != nullptr, "animation.head.mesh",
            "no mesh named \"" + scene.headMotion.mesh + "\" in meshes");
  }
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
  scene.materials = parseList<Material>(fields, "materials", parseMaterial);
  scene.meshes = parseList<MeshInstance>(fields, "meshes", parseMesh);
  scene.grooms = parseList<Groom>(fields, "grooms", parseGroom);
  scene.cloths = parseList<Cloth>(fields, "cloths", parseCloth);
  if (const Json* animation = fields.take("animation")) {
    ObjectFields anim(*animation, "animation");
    if (const Json* head = anim.take("head")) scene.headMotion = parseHeadMotion(*head, "animation.head");
    anim.finish();
  }
  if (const Json* sim = fields.take("simulation")) {
    scene.simulation = parseSimulation(*sim, "simulation");
  }
  if (const Json* shadows = fields.take("hair_shadows")) scene.hairShadows = parseHairShadows(*shadows, "hair_shadows");
  fields.finish();
  checkReferences(scene);
  return scene;
}

}  // namespace

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

}  // namespace mane::scenes
