#include "scenes/scene_meshes.hpp"

#include "scenes/obj_loader.hpp"
#include "scenes/procedural.hpp"

namespace mane::scenes {
namespace {

// Fine enough that the silhouette of a head-sized sphere looks round at 1280×720.
constexpr int kSphereRings = 32;
constexpr int kSphereSegments = 64;

}  // namespace

Result<LoadedMesh> loadSceneMesh(const MeshInstance& instance, const AssetResolver& resolver,
                                 const std::filesystem::path& sceneDirectory) {
  LoadedMesh loaded;
  if (instance.isProcedural()) {
    if (instance.proceduralKind() != "sphere") {
      return fail("mesh '" + instance.name + "': unknown procedural mesh '" + instance.source + "'");
    }
    // Unit radius: the instance's transform scale sets the size.
    loaded.mesh = makeSphere(kSphereRings, kSphereSegments, 1.0f);
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
  return loaded;
}

}  // namespace mane::scenes
