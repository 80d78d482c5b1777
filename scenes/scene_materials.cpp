#include "scenes/detail/scene_materials.hpp"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "render/luts/fur_shells.hpp"
#include "render/luts/solid_voxels.hpp"
#include "scenes/detail/json_fields.hpp"

namespace mane::scenes::detail {
namespace {

using Json = nlohmann::json;

// Skin shading parameters (render::SkinParameters).
render::SkinParameters parseSkinParameters(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  render::SkinParameters skin;
  const std::string range = fields.optional<std::string>("range", "curvature");
  require(range == "curvature" || range == "penner", fields.child("range"),
          "expected \"curvature\" or \"penner\", got \"" + range + "\"");
  skin.range = range == "penner" ? render::SkinIntegrationRange::kPenner : render::SkinIntegrationRange::kCurvature;
  const std::string diffusion = fields.optional<std::string>("diffusion", "preintegrated");
  require(diffusion == "preintegrated" || diffusion == "texture_space", fields.child("diffusion"),
          "expected \"preintegrated\" or \"texture_space\", got \"" + diffusion + "\"");
  skin.diffusion =
      diffusion == "texture_space" ? render::SkinDiffusion::kTextureSpace : render::SkinDiffusion::kPreintegrated;
  const int size = fields.optional<int>("irradiance_size", static_cast<int>(skin.irradianceSize));
  require(size >= 64 && size <= 4096 && size % 8 == 0, fields.child("irradiance_size"),
          "expected a multiple of 8 texels in 64..4096");
  skin.irradianceSize = static_cast<std::uint32_t>(size);
  skin.roughness = fields.optional<float>("roughness", skin.roughness);
  skin.specularIntensity = fields.optional<float>("specular_intensity", skin.specularIntensity);
  fields.finish();
  require(skin.roughness > 0.0f && skin.roughness <= 1.0f, fields.child("roughness"),
          "expected a Beckmann roughness in (0, 1]");
  require(skin.specularIntensity >= 0.0f && skin.specularIntensity <= 10.0f, fields.child("specular_intensity"),
          "expected a specular intensity in [0, 10]");
  return skin;
}

FurMotion parseFurMotion(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  FurMotion motion;
  motion.guides = fields.optional<int>("guides", motion.guides);
  require(motion.guides >= 1 && motion.guides <= 100000, fields.child("guides"), "expected 1..100000 guide strands");
  motion.shapeStiffness = fields.optional<float>("shape_stiffness", motion.shapeStiffness);
  require(motion.shapeStiffness >= 0.0f && motion.shapeStiffness <= 1.0f, fields.child("shape_stiffness"),
          "expected a shape stiffness in [0, 1]");
  motion.damping = fields.optional<float>("damping", motion.damping);
  require(motion.damping >= 0.0f && motion.damping < 1.0f, fields.child("damping"), "expected a damping in [0, 1)");
  motion.iterations = fields.optional<int>("iterations", motion.iterations);
  require(motion.iterations >= 1 && motion.iterations <= 100, fields.child("iterations"), "expected 1..100 iterations");
  fields.finish();
  return motion;
}

// Fur grown from the material's photo (render::FurParameters, and the photo's tiling).
void parseFur(const Json& json, const std::string& path, Material& material) {
  ObjectFields fields(json, path);
  render::FurParameters& fur = material.fur;
  const int layers = fields.optional<int>("layers", static_cast<int>(fur.layers));
  require(layers >= 1 && layers <= static_cast<int>(render::kMaxFurLayers), fields.child("layers"),
          "expected 1.." + std::to_string(render::kMaxFurLayers) + " shells");
  fur.layers = static_cast<std::uint32_t>(layers);
  fur.pixelsPerLayer = fields.optional<float>("pixels_per_layer", fur.pixelsPerLayer);
  require(fur.pixelsPerLayer >= 0.0f && fur.pixelsPerLayer <= 100.0f, fields.child("pixels_per_layer"),
          "expected pixels of fur height per shell in [0, 100] (0: always every shell)");
  fur.thickness = fields.optional<float>("thickness", fur.thickness);
  require(fur.thickness > 0.0f && fur.thickness <= 0.1f, fields.child("thickness"),
          "expected a fur height in (0, 0.1] metres");
  material.furUvScale = fields.optional<float>("uv_scale", material.furUvScale);
  require(material.furUvScale > 0.0f && material.furUvScale <= 1.0e4f, fields.child("uv_scale"),
          "expected photo repeats per uv unit in (0, 10000]");
  fur.fins = fields.optional<bool>("fins", fur.fins);
  const float lay = fields.optional<float>("lay_degrees", glm::degrees(fur.layAngle));
  require(lay >= 0.0f && lay <= 90.0f, fields.child("lay_degrees"), "expected an angle in [0, 90] degrees");
  fur.layAngle = glm::radians(lay);
  fur.specularExponent = fields.optional<float>("specular_exponent", fur.specularExponent);
  require(fur.specularExponent >= 1.0f && fur.specularExponent <= 1000.0f, fields.child("specular_exponent"),
          "expected a Kajiya-Kay exponent in [1, 1000]");
  fur.specularStrength = fields.optional<float>("specular_strength", fur.specularStrength);
  require(fur.specularStrength >= 0.0f && fur.specularStrength <= 10.0f, fields.child("specular_strength"),
          "expected a specular strength in [0, 10]");
  if (const Json* motion = fields.take("dynamics"))
    material.furMotion = parseFurMotion(*motion, fields.child("dynamics"));
  fur.comb = fields.optional<glm::vec3>("comb", fur.comb);
  fur.layDirection = fields.optional<glm::vec3>("lay_direction", fur.layDirection);
  require(std::isfinite(glm::length(fur.layDirection)), fields.child("lay_direction"), "expected a finite direction");
  fur.layRepeatsPerMetre = material.furUvScale;
  require(std::isfinite(glm::length(fur.comb)) && glm::length(fur.comb) <= 2.0f, fields.child("comb"),
          "expected a lean of at most 2 fur heights");
  fields.finish();
}

render::TranslucencyMethod parseTranslucencyMethod(ObjectFields& fields) {
  const std::string method = fields.required<std::string>("method");
  if (method == "none") return render::TranslucencyMethod::kNone;
  if (method == "depth_map") return render::TranslucencyMethod::kDepthMap;
  if (method == "voxel_lut") return render::TranslucencyMethod::kVoxelLut;
  throw FieldError{fields.child("method"), "expected \"none\", \"depth_map\" or \"voxel_lut\", got \"" + method + "\""};
}

// Light through the object (render::TranslucencyParameters). As with `skin` on a Lambert
// material, a field the method or the material's kind would ignore is an error, not a no-op.
render::TranslucencyParameters parseTranslucency(const Json& json, const std::string& path, MaterialKind kind) {
  ObjectFields fields(json, path);
  render::TranslucencyParameters translucency;
  translucency.method = parseTranslucencyMethod(fields);
  if (const Json* extinction = fields.take("extinction")) {
    require(translucency.method != render::TranslucencyMethod::kNone, fields.child("extinction"),
            "applies to methods \"depth_map\" and \"voxel_lut\" only");
    require(kind != MaterialKind::skin, fields.child("extinction"),
            "applies to materials other than \"skin\" (skin transmits its diffusion profile)");
    translucency.extinction = detail::read<glm::vec3>(*extinction, fields.child("extinction"));
    for (int c = 0; c < 3; ++c) {
      require(translucency.extinction[c] >= 0.0f,
              detail::indexPath(fields.child("extinction"), static_cast<std::size_t>(c)),
              "expected an extinction >= 0 per metre");
    }
  }
  if (const Json* resolution = fields.take("voxel_resolution")) {
    require(translucency.method == render::TranslucencyMethod::kVoxelLut, fields.child("voxel_resolution"),
            "applies to method \"voxel_lut\" only");
    translucency.voxelResolution = detail::read<int>(*resolution, fields.child("voxel_resolution"));
    require(translucency.voxelResolution >= render::SolidVoxels::kMinResolution &&
                translucency.voxelResolution <= render::SolidVoxels::kMaxResolution,
            fields.child("voxel_resolution"),
            "expected a resolution in " + std::to_string(render::SolidVoxels::kMinResolution) + ".." +
                std::to_string(render::SolidVoxels::kMaxResolution) + " cells per axis");
  }
  fields.finish();
  return translucency;
}

}  // namespace

Material parseMaterial(const Json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Material material;
  material.name = fields.required<std::string>("name");
  require(!material.name.empty(), fields.child("name"), "expected a non-empty name");
  const std::string kind = fields.optional<std::string>("kind", "lambert");
  require(kind == "lambert" || kind == "skin" || kind == "fur", fields.child("kind"),
          "expected \"lambert\", \"skin\" or \"fur\", got \"" + kind + "\"");
  material.kind = kind == "skin" ? MaterialKind::skin : kind == "fur" ? MaterialKind::fur : MaterialKind::lambert;
  if (const Json* skin = fields.take("skin")) {
    require(material.kind == MaterialKind::skin, fields.child("skin"), "applies to materials of kind \"skin\" only");
    material.skin = parseSkinParameters(*skin, fields.child("skin"));
  }
  if (const Json* fur = fields.take("fur")) {
    require(material.kind == MaterialKind::fur, fields.child("fur"), "applies to materials of kind \"fur\" only");
    parseFur(*fur, fields.child("fur"), material);
  }
  material.albedoTexture = fields.optional<std::string>("albedo_texture", "");
  require(material.kind != MaterialKind::fur || !material.albedoTexture.empty(), fields.child("albedo_texture"),
          "a fur material needs the photo its shells are made from");
  material.normalMap = fields.optional<std::string>("normal_map", "");
  material.specularMap = fields.optional<std::string>("specular_map", "");
  material.baseColour = fields.optional<glm::vec3>("base_colour", material.baseColour);
  material.doubleSided = fields.optional<bool>("double_sided", material.doubleSided);
  material.transmission = fields.optional<float>("transmission", material.transmission);
  require(material.transmission >= 0.0f && material.transmission <= 1.0f, fields.child("transmission"),
          "expected a share in [0, 1]");
  require(material.transmission == 0.0f || material.kind == MaterialKind::lambert, fields.child("transmission"),
          "applies to materials of kind \"lambert\" only");
  if (const Json* translucency = fields.take("translucency")) {
    material.translucency = parseTranslucency(*translucency, fields.child("translucency"), material.kind);
  }
  fields.finish();
  return material;
}

}  // namespace mane::scenes::detail
