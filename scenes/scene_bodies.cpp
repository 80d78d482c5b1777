#include "scenes/detail/scene_bodies.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "render/lens.hpp"
#include "scenes/detail/json_fields.hpp"

namespace mane::scenes::detail {
namespace {

using Json = nlohmann::json;

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

// A sphere in the body frame, or carried by a joint ("joint": its centre in the joint's frame).
void parseSphereCollider(const Json& json, const std::string& path, Colliders& colliders) {
  ObjectFields fields(json, path);
  // Unknown fields first: "center" for "centre" is then reported as the typo it is.
  for (const char* key : {"centre", "radius", "joint"}) fields.take(key);
  fields.finish();
  physics::SphereCollider sphere;
  sphere.centre = fields.required<glm::vec3>("centre");
  sphere.radius = fields.required<float>("radius");
  require(sphere.radius > 0.0f, fields.child("radius"), "expected a radius > 0 metres");
  const std::string joint = fields.optional<std::string>("joint", "");
  if (fields.take("joint")) {
    require(!joint.empty(), fields.child("joint"), "expected a joint (node) name");
    colliders.jointSpheres.push_back(JointSphere{joint, sphere});
  } else {
    colliders.spheres.push_back(sphere);
  }
}

// A capsule in the body frame, carried by a joint ("joint", with "a" and "b" in its frame), or
// spanning two joints ("joint" and "to_joint": from one origin to the other).
void parseCapsuleCollider(const Json& json, const std::string& path, Colliders& colliders) {
  ObjectFields fields(json, path);
  for (const char* key : {"a", "b", "radius", "joint", "to_joint"}) fields.take(key);
  fields.finish();
  physics::CapsuleCollider capsule;
  capsule.radius = fields.required<float>("radius");
  require(capsule.radius > 0.0f, fields.child("radius"), "expected a radius > 0 metres");
  const std::string joint = fields.optional<std::string>("joint", "");
  const std::string toJoint = fields.optional<std::string>("to_joint", "");
  require(!fields.take("to_joint") || fields.take("joint"), fields.child("to_joint"),
          "needs \"joint\": the capsule runs from that joint's origin to this one's");
  if (!toJoint.empty()) {
    require(!fields.take("a") && !fields.take("b"), fields.child("a"),
            "a capsule from \"joint\" to \"to_joint\" takes its axis from them; leave out \"a\" and \"b\"");
  } else {
    capsule.a = fields.required<glm::vec3>("a");
    capsule.b = fields.required<glm::vec3>("b");
  }
  if (fields.take("joint")) {
    require(!joint.empty(), fields.child("joint"), "expected a joint (node) name");
    colliders.jointCapsules.push_back(JointCapsule{joint, toJoint, capsule});
  } else {
    colliders.capsules.push_back(capsule);
  }
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
  const Json& spheres = fields.array("spheres", false);
  for (std::size_t i = 0; i < spheres.size(); ++i)
    parseSphereCollider(spheres[i], indexPath(fields.child("spheres"), i), colliders);
  const Json& capsules = fields.array("capsules", false);
  for (std::size_t i = 0; i < capsules.size(); ++i)
    parseCapsuleCollider(capsules[i], indexPath(fields.child("capsules"), i), colliders);
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
  // What the scene gives here holds for every strand; a groom file fills in the rest.
  const auto given = [&](const char* key, float& value) {
    const Json* field = fields.take(key);
    if (field) value = detail::read<float>(*field, fields.child(key));
    return field != nullptr;
  };
  rendering.given.width = given("width", settings.width);
  rendering.given.tipWidthScale = given("tip_width_scale", settings.tipWidthScale);
  rendering.given.opacity = given("opacity", settings.opacity);
  if (const Json* colour = fields.take("colour")) rendering.colour = detail::read<glm::vec3>(*colour, fields.child("colour"));
  settings.minimumPixelWidth = fields.optional<float>("min_pixel_width", settings.minimumPixelWidth);
  settings.lodPixelWidth = fields.optional<float>("lod_pixel_width", settings.lodPixelWidth);
  settings.shadowExtinction = fields.optional<float>("shadow_extinction", settings.shadowExtinction);
  const Json* strands = fields.take("strands");
  if (strands) rendering.denseStrands = detail::read<int>(*strands, fields.child("strands"));
  const Json* vertices = fields.take("vertices_per_strand");
  if (vertices) rendering.verticesPerStrand = detail::read<int>(*vertices, fields.child("vertices_per_strand"));
  const std::string blend = fields.optional<std::string>("guide_blend", "single");
  require(blend == "single" || blend == "barycentric", fields.child("guide_blend"),
          "expected \"single\" or \"barycentric\", got \"" + blend + "\"");
  rendering.guideBlend = blend == "barycentric" ? physics::GuideBlend::kBarycentric : physics::GuideBlend::kSingle;
  const std::string curve = fields.optional<std::string>("curve", "catmull_rom");
  require(curve == "catmull_rom" || curve == "linear", fields.child("curve"),
          "expected \"catmull_rom\" or \"linear\", got \"" + curve + "\"");
  rendering.curve = curve == "linear" ? StrandCurve::kLinear : StrandCurve::kCatmullRom;
  rendering.clump = fields.optional<float>("clump", rendering.clump);
  rendering.clumpProfile = fields.optional<float>("clump_profile", rendering.clumpProfile);
  if (const Json* curl = fields.take("curl")) {
    ObjectFields curlFields(*curl, fields.child("curl"));
    rendering.curlRadius = curlFields.required<float>("radius");
    rendering.curlPeriod = curlFields.optional<float>("period", rendering.curlPeriod);
    rendering.curlVariation = curlFields.optional<float>("variation", rendering.curlVariation);
    curlFields.finish();
    require(rendering.curlRadius >= 0.0f && rendering.curlRadius <= 0.05f, curlFields.child("radius"),
            "expected a radius in [0, 0.05] metres");
    require(rendering.curlPeriod >= 0.001f && rendering.curlPeriod <= 10.0f, curlFields.child("period"),
            "expected a length in [0.001, 10] metres per turn");
    require(rendering.curlVariation >= 0.0f && rendering.curlVariation <= 1.0f, curlFields.child("variation"),
            "expected a share in [0, 1]");
  }
  rendering.frizz = fields.optional<float>("frizz", rendering.frizz);
  fields.finish();
  require(rendering.frizz >= 0.0f && rendering.frizz <= 0.01f, fields.child("frizz"),
          "expected a frizz in [0, 0.01] metres");
  require(rendering.clump >= 0.0f && rendering.clump <= 1.0f, fields.child("clump"), "expected a clump in [0, 1]");
  require(rendering.clumpProfile >= 0.0f && rendering.clumpProfile <= 8.0f, fields.child("clump_profile"),
          "expected an exponent in [0, 8]");
  require(!strands || (rendering.denseStrands >= 1 && rendering.denseStrands <= kMaxDenseStrands),
          fields.child("strands"), "expected a dense strand count in 1.." + std::to_string(kMaxDenseStrands));
  require(!vertices || (rendering.verticesPerStrand >= 2 && rendering.verticesPerStrand <= kMaxDenseStrandVertices),
          fields.child("vertices_per_strand"),
          "expected 2.." + std::to_string(kMaxDenseStrandVertices) + " vertices per strand");
  require(settings.width > 0.0f && settings.width <= 0.01f, fields.child("width"),
          "expected a root width in (0, 0.01] metres");
  require(settings.tipWidthScale >= 0.0f && settings.tipWidthScale <= 1.0f, fields.child("tip_width_scale"),
          "expected a tip width scale in [0, 1]");
  // Not 0: a groom's strands add its opacity to the shadow maps, which need it positive.
  require(settings.opacity > 0.0f && settings.opacity <= 1.0f, fields.child("opacity"),
          "expected an opacity in (0, 1]");
  for (int c = 0; rendering.colour && c < 3; ++c)
    require((*rendering.colour)[c] >= 0.0f && (*rendering.colour)[c] <= 1.0f, fields.child("colour"),
            "expected an RGB colour with components in [0, 1]");
  require(settings.minimumPixelWidth >= 0.25f, fields.child("min_pixel_width"),
          "expected a minimum width >= 0.25 pixels");
  require(std::isfinite(settings.lodPixelWidth) && settings.lodPixelWidth >= 0.0f, fields.child("lod_pixel_width"),
          "expected a level-of-detail width >= 0 pixels (0: every strand drawn)");
  require(settings.shadowExtinction > 0.0f, fields.child("shadow_extinction"), "expected a shadow extinction > 0");
  return rendering;
}

physics::DrapeSettings parseDrape(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  physics::DrapeSettings drape;
  drape.droop = fields.optional<float>("droop", drape.droop);
  drape.layer = fields.optional<float>("layer", drape.layer);
  drape.combedLength = fields.optional<float>("combed_length", drape.combedLength);
  fields.finish();
  require(drape.droop >= 0.0f && drape.droop <= 1000.0f, fields.child("droop"),
          "expected a droop in [0, 1000] per metre");
  require(drape.layer >= 0.0f && drape.layer <= 0.1f, fields.child("layer"), "expected a layer in [0, 0.1] metres");
  require(drape.combedLength >= 0.0f && drape.combedLength <= 10.0f, fields.child("combed_length"),
          "expected a length in [0, 10] metres");
  return drape;
}

GroomParting parseParting(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  GroomParting parting;
  parting.comb = fields.required<float>("comb");
  parting.x = fields.optional<float>("x", parting.x);
  parting.backZ = fields.optional<float>("back_z", parting.backZ);
  fields.finish();
  require(parting.comb >= 0.0f && parting.comb <= 10.0f, fields.child("comb"), "expected a comb in [0, 10]");
  require(std::abs(parting.x) <= 10.0f, fields.child("x"), "expected a position within 10 metres of the body");
  require(std::abs(parting.backZ) <= 10.0f, fields.child("back_z"), "expected a position within 10 metres of the body");
  return parting;
}

ScalpRegion parseScalp(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  ScalpRegion scalp;
  scalp.topFraction = fields.optional<float>("top_fraction", scalp.topFraction);
  scalp.minUp = fields.optional<float>("min_up", scalp.minUp);
  scalp.maxForward = fields.optional<float>("max_forward", scalp.maxForward);
  scalp.hairlineDensity = fields.optional<float>("hairline_density", scalp.hairlineDensity);
  fields.finish();
  require(scalp.topFraction > 0.0f && scalp.topFraction <= 1.0f, fields.child("top_fraction"),
          "expected a fraction of the mesh's height in (0, 1]");
  require(scalp.minUp >= -1.0f && scalp.minUp <= 1.0f, fields.child("min_up"),
          "expected a normal component in [-1, 1]");
  require(scalp.maxForward >= -1.0f && scalp.maxForward <= 1.0f, fields.child("max_forward"),
          "expected a normal component in [-1, 1]");
  require(scalp.hairlineDensity >= 1.0f && scalp.hairlineDensity <= 16.0f, fields.child("hairline_density"),
          "expected a density in [1, 16] times the scalp's");
  return scalp;
}

// "top_edge", "none", or an object naming the top edge, vertices and boxes to pin.
void parsePins(const Json& json, const std::string& path, Cloth& cloth) {
  if (json.is_string()) {
    const std::string pinned = json.get<std::string>();
    require(pinned == "top_edge" || pinned == "none", path,
            "expected \"top_edge\", \"none\" or an object, got \"" + pinned + "\"");
    cloth.pinTopEdge = pinned == "top_edge";
    return;
  }
  ObjectFields fields(json, path);
  cloth.pinTopEdge = fields.optional<bool>("top_edge", false);
  const Json& vertices = fields.array("vertices", false);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const int vertex = read<int>(vertices[i], indexPath(fields.child("vertices"), i));
    require(vertex >= 0, indexPath(fields.child("vertices"), i), "expected a vertex index >= 0");
    cloth.pinVertices.push_back(static_cast<std::uint32_t>(vertex));
  }
  const Json& regions = fields.array("regions", false);
  for (std::size_t i = 0; i < regions.size(); ++i) {
    ObjectFields region(regions[i], indexPath(fields.child("regions"), i));
    const glm::vec3 lower = region.required<glm::vec3>("min");
    const glm::vec3 upper = region.required<glm::vec3>("max");
    region.finish();
    require(lower.x <= upper.x && lower.y <= upper.y && lower.z <= upper.z, region.child("max"),
            "expected a corner at or above \"min\" on every axis");
    cloth.pinRegions.push_back({lower, upper});
  }
  fields.finish();
}

}  // namespace

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
  groom.strict = fields.optional<bool>("strict", false);
  require(!groom.strict || !groom.isProcedural(), fields.child("strict"),
          "applies to groom files only, not to \"procedural\"");
  if (const Json* scalp = fields.take("scalp")) {
    require(groom.isProcedural(), fields.child("scalp"), "applies to \"procedural\" grooms only");
    groom.scalp = parseScalp(*scalp, fields.child("scalp"));
  }
  if (const Json* comb = fields.take("comb")) {
    require(groom.isProcedural(), fields.child("comb"), "applies to \"procedural\" grooms only");
    groom.comb = detail::read<glm::vec3>(*comb, fields.child("comb"));
  }
  if (const Json* parting = fields.take("parting")) {
    require(groom.isProcedural(), fields.child("parting"), "applies to \"procedural\" grooms only");
    groom.parting = parseParting(*parting, fields.child("parting"));
  }
  if (const Json* drape = fields.take("drape")) {
    require(groom.isProcedural(), fields.child("drape"), "applies to \"procedural\" grooms only");
    groom.drape = parseDrape(*drape, fields.child("drape"));
  }
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

CapeShape parseCapeShape(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  CapeShape cape;
  cape.collarRadius = fields.optional<float>("collar_radius", cape.collarRadius);
  cape.hemRadius = fields.optional<float>("hem_radius", cape.hemRadius);
  cape.length = fields.optional<float>("length", cape.length);
  cape.wrapDegrees = fields.optional<float>("wrap_degrees", cape.wrapDegrees);
  cape.columns = fields.optional<int>("columns", cape.columns);
  cape.rows = fields.optional<int>("rows", cape.rows);
  fields.finish();
  require(cape.collarRadius > 0.0f && cape.collarRadius <= 10.0f, fields.child("collar_radius"),
          "expected a radius in (0, 10] metres");
  require(cape.length > 0.0f && cape.length <= 10.0f, fields.child("length"), "expected a length in (0, 10] metres");
  // A cone's side can flare no wider than a flat ring: its slant is the length.
  require(cape.hemRadius >= cape.collarRadius && cape.hemRadius <= cape.collarRadius + cape.length,
          fields.child("hem_radius"), "expected a radius from collar_radius to collar_radius + length");
  require(cape.wrapDegrees > 0.0f && cape.wrapDegrees <= 360.0f, fields.child("wrap_degrees"),
          "expected an angle in (0, 360] degrees");
  require(cape.columns >= 2 && cape.columns <= 512, fields.child("columns"), "expected 2..512 vertices");
  require(cape.rows >= 2 && cape.rows <= 512, fields.child("rows"), "expected 2..512 vertices");
  return cape;
}

FinShape parseFinShape(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  FinShape fin;
  fin.rays = fields.optional<int>("rays", fin.rays);
  fin.length = fields.optional<float>("length", fin.length);
  fin.root = fields.optional<float>("root", fin.root);
  fin.spreadDegrees = fields.optional<float>("spread_degrees", fin.spreadDegrees);
  fin.taper = fields.optional<float>("taper", fin.taper);
  fin.scallop = fields.optional<float>("scallop", fin.scallop);
  fin.pleat = fields.optional<float>("pleat", fin.pleat);
  fin.rows = fields.optional<int>("rows", fin.rows);
  fin.rayStiffness = fields.optional<float>("ray_stiffness", fin.rayStiffness);
  fields.finish();
  require(fin.rays >= 3 && fin.rays <= 32, fields.child("rays"), "expected 3..32 rays");
  // Below a millimetre the membrane's triangles near the root lose their area to rounding.
  require(fin.length >= 0.001f && fin.length <= 1.0f, fields.child("length"), "expected a length in [0.001, 1] metres");
  require(fin.root >= 0.001f && fin.root <= 1.0f, fields.child("root"), "expected a length in [0.001, 1] metres");
  require(fin.spreadDegrees > 0.0f && fin.spreadDegrees <= 150.0f, fields.child("spread_degrees"),
          "expected an angle in (0, 150] degrees");
  require(fin.taper > 0.0f && fin.taper <= 1.0f, fields.child("taper"), "expected a share in (0, 1]");
  require(fin.scallop >= 0.0f && fin.scallop <= 0.5f, fields.child("scallop"), "expected a share in [0, 0.5]");
  require(fin.pleat >= 0.0f && fin.pleat <= 0.5f, fields.child("pleat"), "expected a share in [0, 0.5]");
  require(fin.rows >= 4 && fin.rows <= 128, fields.child("rows"), "expected 4..128 vertices");
  require(fin.rayStiffness > 0.0f && fin.rayStiffness <= 1.0f, fields.child("ray_stiffness"),
          "expected a stiffness in (0, 1]");
  return fin;
}

Cloth parseCloth(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Cloth cloth;
  cloth.name = fields.required<std::string>("name");
  require(!cloth.name.empty(), fields.child("name"), "expected a non-empty name");
  cloth.source = fields.required<std::string>("source");
  const bool isCape = cloth.source == "procedural:cape", isFin = cloth.source == "procedural:fin";
  require(!cloth.source.empty() &&
              (!cloth.source.starts_with(kProceduralPrefix) || cloth.source == "procedural:grid" || isCape || isFin),
          fields.child("source"),
          "expected a mesh asset, a file path, \"procedural:grid\", \"procedural:cape\" or \"procedural:fin\"");
  if (const Json* cape = fields.take("cape")) {
    require(isCape, fields.child("cape"), "applies to \"procedural:cape\" cloths only");
    cloth.cape = parseCapeShape(*cape, fields.child("cape"));
  }
  if (const Json* fin = fields.take("fin")) {
    require(isFin, fields.child("fin"), "applies to \"procedural:fin\" cloths only");
    cloth.fin = parseFinShape(*fin, fields.child("fin"));
  }
  cloth.attachedMesh = fields.required<std::string>("attached_mesh");
  cloth.material = fields.optional<std::string>("material", "");
  if (const Json* transform = fields.take("transform")) {
    cloth.transform = parseTransform(*transform, fields.child("transform"));
  }
  if (const Json* pinned = fields.take("pinned")) parsePins(*pinned, fields.child("pinned"), cloth);
  if (const Json* sim = fields.take("simulation")) {
    ObjectFields simFields(*sim, fields.child("simulation"));
    cloth.iterations = simFields.optional<int>("iterations", cloth.iterations);
    cloth.damping = simFields.optional<float>("damping", cloth.damping);
    cloth.bendingStiffness = simFields.optional<float>("bending", cloth.bendingStiffness);
    cloth.selfCollision = simFields.optional<float>("self_collision", cloth.selfCollision);
    cloth.gravity = simFields.optional<glm::vec3>("gravity", cloth.gravity);
    if (const Json* wind = simFields.take("wind")) cloth.wind = detail::read<glm::vec3>(*wind, simFields.child("wind"));
    cloth.arealDensity = simFields.optional<float>("areal_density", cloth.arealDensity);
    simFields.finish();
    require(cloth.arealDensity > 0.0f && cloth.arealDensity <= 100.0f, simFields.child("areal_density"),
            "expected kilograms per square metre in (0, 100]");
    require(cloth.iterations >= 1 && cloth.iterations <= 1000, simFields.child("iterations"),
            "expected 1..1000 iterations");
    require(cloth.damping >= 0.0f && cloth.damping < 1.0f, simFields.child("damping"), "expected a damping in [0, 1)");
    require(cloth.bendingStiffness >= 0.0f && cloth.bendingStiffness <= 1.0f, simFields.child("bending"),
            "expected a bending stiffness in [0, 1]");
    require(cloth.selfCollision >= 0.0f && cloth.selfCollision <= 0.1f, simFields.child("self_collision"),
            "expected a thickness in [0, 0.1] metres (0: off)");
  }
  if (const Json* colliders = fields.take("colliders")) {
    cloth.colliders = parseColliders(*colliders, fields.child("colliders"));
  }
  fields.finish();
  return cloth;
}

Glasses parseGlasses(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Glasses glasses;
  glasses.name = fields.required<std::string>("name");
  require(!glasses.name.empty(), fields.child("name"), "expected a non-empty name");
  glasses.attachedMesh = fields.required<std::string>("attached_mesh");
  if (const Json* transform = fields.take("transform")) {
    glasses.transform = parseTransform(*transform, fields.child("transform"));
    require(glasses.transform.scale == 1.0f, fields.child("transform") + ".scale",
            "glasses are sized by lens_width, lens_height, bridge and temple_length; leave the scale at 1");
  }
  glasses.powerDioptres = fields.optional<float>("power_dioptres", glasses.powerDioptres);
  glasses.lensWidth = fields.optional<float>("lens_width", glasses.lensWidth);
  glasses.lensHeight = fields.optional<float>("lens_height", glasses.lensHeight);
  glasses.bridge = fields.optional<float>("bridge", glasses.bridge);
  glasses.templeLength = fields.optional<float>("temple_length", glasses.templeLength);
  glasses.templeWidth = fields.optional<float>("temple_width", glasses.templeWidth);
  glasses.ior = fields.optional<float>("ior", glasses.ior);
  glasses.tint = fields.optional<glm::vec3>("tint", glasses.tint);
  glasses.material = fields.optional<std::string>("material", "");
  fields.finish();
  require(std::abs(glasses.powerDioptres) <= render::kMaxLensPower, fields.child("power_dioptres"),
          "expected a power in [-20, 20] dioptres");
  require(glasses.lensWidth > 0.0f && glasses.lensWidth <= 0.2f, fields.child("lens_width"),
          "expected a width in (0, 0.2] metres");
  require(glasses.lensHeight > 0.0f && glasses.lensHeight <= 0.2f, fields.child("lens_height"),
          "expected a height in (0, 0.2] metres");
  require(glasses.bridge >= 0.0f && glasses.bridge <= 0.1f, fields.child("bridge"),
          "expected a gap in [0, 0.1] metres");
  require(glasses.templeLength >= 0.0f && glasses.templeLength <= 0.3f, fields.child("temple_length"),
          "expected a length in [0, 0.3] metres");
  require(glasses.templeWidth >= 0.0f && glasses.templeWidth <= 0.5f, fields.child("temple_width"),
          "expected a width in [0, 0.5] metres (0: the frame's width and 1 cm)");
  require(glasses.ior > 1.0f && glasses.ior <= 3.0f, fields.child("ior"), "expected an index of refraction in (1, 3]");
  require(glasses.tint.x >= 0.0f && glasses.tint.y >= 0.0f && glasses.tint.z >= 0.0f && glasses.tint.x <= 1.0f &&
              glasses.tint.y <= 1.0f && glasses.tint.z <= 1.0f,
          fields.child("tint"), "expected each channel in [0, 1]");
  return glasses;
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

render::PostSettings parsePost(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  render::PostSettings post;
  const std::string toneMapping = fields.optional<std::string>("tone_mapping", "linear");
  require(toneMapping == "linear" || toneMapping == "reinhard", fields.child("tone_mapping"),
          "expected \"linear\" or \"reinhard\", got \"" + toneMapping + "\"");
  post.toneMapping = toneMapping == "reinhard" ? render::ToneMapping::kReinhard : render::ToneMapping::kLinear;
  post.autoGain = fields.optional<bool>("auto_gain", post.autoGain);
  post.key = fields.optional<float>("key", post.key);
  post.glowStrength = fields.optional<float>("glow", post.glowStrength);
  post.adaptationSeconds = fields.optional<float>("adaptation_seconds", post.adaptationSeconds);
  post.godRays = fields.optional<float>("god_rays", post.godRays);
  const int godRayLight = fields.optional<int>("god_ray_light", 0);
  fields.finish();
  require(post.key > 0.0f && post.key <= 1.0f, fields.child("key"), "expected a key value in (0, 1]");
  require(post.glowStrength >= 0.0f && post.glowStrength <= 1.0f, fields.child("glow"),
          "expected a glow strength in [0, 1]");
  require(post.adaptationSeconds >= 0.0f && post.adaptationSeconds <= 60.0f, fields.child("adaptation_seconds"),
          "expected an adaptation time in [0, 60] seconds");
  require(post.godRays >= 0.0f && post.godRays <= 10.0f, fields.child("god_rays"),
          "expected a god-ray strength in [0, 10]");
  require(godRayLight >= 0, fields.child("god_ray_light"), "expected a light's index, 0 or more");
  post.godRayLight = static_cast<std::uint32_t>(godRayLight);
  return post;
}

}  // namespace mane::scenes::detail
