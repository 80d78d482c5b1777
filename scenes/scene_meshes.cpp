#include "scenes/scene_meshes.hpp"

#include <cctype>
#include <optional>
#include <string_view>
#include <utility>

#include "scenes/mesh_simplify.hpp"
#include "scenes/obj_loader.hpp"
#include "scenes/procedural.hpp"
#include "scenes/subdivided_mesh.hpp"
#include "subdiv/cage_obj.hpp"

namespace mane::scenes {
namespace {

// Fine enough that the silhouette of a head-sized sphere looks round at 1280×720.
constexpr int kSphereRings = 32;
constexpr int kSphereSegments = 64;

// The voxelized-translucency paper's test objects, in model units (the instance's scale sets the size).
// The hollow is seen only through the material, but its outline shows in the transmitted light
// and the voxelization: as fine as the sphere. The torus's tube steps 360°/32 = 11°.
constexpr float kCubeHalfSide = 1.0f;
constexpr float kHollowRadius = 0.5f;
constexpr float kTorusMajorRadius = 1.0f;
constexpr float kTorusMinorRadius = 0.4f;
constexpr int kTorusMajorSegments = 96;
constexpr int kTorusMinorSegments = 32;
constexpr int kHullStations = 64;
constexpr int kHullSectionPoints = 24;
constexpr float kSparRadius = 0.015f;
constexpr int kSparSegments = 16;

/// The mesh of a `kProceduralMeshKinds` entry; nothing for another kind.
std::optional<Mesh> makeProceduralMesh(std::string_view kind) {
  if (kind == "sphere") return makeSphere(kSphereRings, kSphereSegments, 1.0f);
  if (kind == "cube_with_hollow")
    return makeCubeWithHollow(kCubeHalfSide, kHollowRadius, kSphereRings, kSphereSegments);
  if (kind == "torus") return makeTorus(kTorusMajorRadius, kTorusMinorRadius, kTorusMajorSegments, kTorusMinorSegments);
  if (kind == "plane") return makePlane(0.5f);
  if (kind == "hull") return makeHull(kHullStations, kHullSectionPoints);
  if (kind == "spar") return makeSpar(kSparRadius, kSparSegments);
  return std::nullopt;
}

/// The geometry of the entry, without its subdivision cage.
Result<LoadedMesh> loadTriangles(const MeshInstance& instance, const AssetResolver& resolver,
                                 const std::filesystem::path& sceneDirectory,
                                 std::optional<std::filesystem::path>& file) {
  LoadedMesh loaded;
  if (instance.isProcedural()) {
    std::optional<Mesh> mesh = makeProceduralMesh(instance.proceduralKind());
    if (!mesh) return fail("mesh '" + instance.name + "': unknown procedural mesh '" + instance.source + "'");
    loaded.mesh = std::move(*mesh);
    loaded.procedural = true;
    return loaded;
  }
  auto found = resolver.lookupForScene(instance.source, sceneDirectory);
  if (!found) return fail("mesh '" + instance.name + "': " + found.error().message);
  if (!found->path) {
    loaded.mesh = makeSphere(kSphereRings, kSphereSegments, kFallbackSphereRadius / instance.transform.scale);
    loaded.procedural = true;
    loaded.note = "asset " + instance.source + " missing: using a procedural sphere (" + found->missingReason + ")";
    return loaded;
  }
  auto mesh = loadMesh(*found->path);
  if (!mesh) return fail("mesh '" + instance.name + "': " + mesh.error().message);
  loaded.mesh = std::move(*mesh);
  file = *found->path;
  return loaded;
}

bool isObj(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".obj";
}

}  // namespace

Result<LoadedMesh> loadSceneMesh(const MeshInstance& instance, const AssetResolver& resolver,
                                 const std::filesystem::path& sceneDirectory) {
  std::optional<std::filesystem::path> file;
  auto loaded = loadTriangles(instance, resolver, sceneDirectory, file);
  if (loaded && instance.simplify) {
    auto simplified = simplifyMesh(loaded->mesh, {.targetTriangles = std::size_t(instance.simplify->triangles),
                                                  .maxRelativeError = instance.simplify->maxRelativeError});
    if (!simplified) return fail("mesh '" + instance.name + "': " + simplified.error().message);
    loaded->mesh = std::move(simplified->mesh);
  }
  if (!loaded || !instance.subdivision) return loaded;
  if (const auto& coarse = instance.subdivision->coarseCage) {
    auto cage = coarseCageFromTriangles(loaded->mesh, *coarse);
    if (!cage) return fail("mesh '" + instance.name + "': subdivision " + cage.error().message);
    loaded->cage = std::move(cage->cage);
  } else if (file && isObj(*file)) {
    // The OBJ's own polygons: quads stay quads, and `t crease` / `t corner` tags are kept.
    auto cage = subdiv::loadCageObj(*file);
    if (!cage) return fail("mesh '" + instance.name + "': subdivision cage: " + cage.error().message);
    flipCageUvsToTopLeft(*cage);
    loaded->cage = std::move(*cage);
  } else {
    loaded->cage = cageFromTriangles(loaded->mesh);
  }
  if (instance.subdivision->capHoles) capBoundaryLoops(*loaded->cage);
  return loaded;
}

}  // namespace mane::scenes
