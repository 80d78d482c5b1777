#include "scenes/world.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "physics/groom_generator.hpp"
#include "physics/hash.hpp"
#include "physics/interpolation.hpp"
#include "scenes/groom_loader.hpp"
#include "scenes/groom_looks.hpp"
#include "scenes/limit_scalp.hpp"
#include "scenes/mesh_curvature.hpp"
#include "scenes/scene_colliders.hpp"
#include "scenes/scene_environment.hpp"
#include "scenes/subdivided_mesh.hpp"

namespace mane::scenes {
namespace {

render::TextureData textureOf(const Image& image) {
  return {static_cast<std::uint32_t>(image.width), static_cast<std::uint32_t>(image.height), image.rgba};
}

// The triangles a procedural groom grows from: in the top quarter of the mesh's height, facing
// up (unit normal y ≥ minNormalY).
std::vector<std::uint32_t> scalpTriangles(const Mesh& mesh, const ScalpRegion& region) {
  const Bounds bounds = mesh.bounds();
  const float lowest = bounds.max.y - region.topFraction * bounds.size().y;
  std::vector<std::uint32_t> scalp;
  for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::vec3& a = mesh.positions[mesh.indices[3 * t]];
    const glm::vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
    const glm::vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
    const glm::vec3 normal = glm::cross(b - a, c - a);
    const float length = glm::length(normal);
    if (length > 0.0f && normal.y >= region.minUp * length && normal.z <= region.maxForward * length &&
        (a.y + b.y + c.y) / 3.0f >= lowest)
      scalp.push_back(t);
  }
  return scalp;
}

// A groom draws as Nalu's unless its scene says otherwise: 4,095 dense strands (or one per guide
// where there are more), each following one guide with a root offset and some clumping
// (physics/interpolation.hpp).
constexpr std::size_t kDefaultDenseStrands = 4095;

// "a.tfx, b.tfx" for messages.
std::string sourceList(const Groom& groom) {
  std::string list;
  for (const std::string& source : groom.sources) list += (list.empty() ? "" : ", ") + source;
  return list;
}

physics::SolverSettings solverSettings(const HairSimulation& simulation, const SimulationSettings& world) {
  physics::SolverSettings settings;
  settings.fixedStep = world.stepSeconds;
  settings.gravity = simulation.gravity;
  settings.damping = simulation.damping;
  settings.constraintIterations = simulation.iterations;
  settings.shapeStiffness = simulation.shapeStiffness;
  settings.maxSubstepsPerFrame = world.maxStepsPerFrame;
  return settings;
}

}  // namespace

Result<World> World::create(Scene scene, const AssetResolver& resolver, const WorldSettings& settings) {
  World world;
  world.scene_ = std::move(scene);
  if (auto loaded = world.loadMeshes(resolver); !loaded) return std::unexpected(loaded.error());
  if (auto loaded = world.loadCharacters(resolver); !loaded) return std::unexpected(loaded.error());
  if (auto subdivided = world.subdivideMeshes(); !subdivided) return std::unexpected(subdivided.error());
  world.prepareFurMeshes();
  if (settings.loadTextures) {
    if (auto loaded = world.loadMaterials(resolver); !loaded) return std::unexpected(loaded.error());
    auto environment = loadSceneEnvironment(world.scene_, resolver, world.notes_);
    if (!environment) return std::unexpected(environment.error());
    if (*environment) {
      world.environment_ = std::move((*environment)->data);
      world.environmentSun_ = (*environment)->sun;
    }
  } else {
    world.materials_.resize(world.scene_.materials.size());
  }
  if (auto computed = world.computeSkinCurvatures(); !computed) return std::unexpected(computed.error());
  // Collider fields are built here, once each, and shared by the grooms and cloths that use them.
  SceneColliders colliders(world.scene_, world.meshes_);
  if (auto loaded = world.loadGrooms(resolver, colliders); !loaded) return std::unexpected(loaded.error());
  if (auto loaded = world.loadCloths(resolver, colliders); !loaded) return std::unexpected(loaded.error());
  if (auto loaded = world.loadFurDynamics(); !loaded) return std::unexpected(loaded.error());
  if (auto loaded = world.loadGlasses(); !loaded) return std::unexpected(loaded.error());
  if (world.scene_.ocean) {
    std::size_t shipIndex = 0;
    const Mesh* shipMesh = nullptr;
    for (std::size_t m = 0; m < world.scene_.meshes.size(); ++m)
      if (world.scene_.ship && world.scene_.meshes[m].name == world.scene_.ship->mesh) {
        shipIndex = m;
        shipMesh = &world.meshes_[m].mesh;
      }
    auto ocean = SceneOcean::create(world.scene_, shipMesh, shipIndex);
    if (!ocean) return std::unexpected(ocean.error());
    world.ocean_ = std::move(*ocean);
  }
  // Settling: 1/60 s frames with every body held where it is at time 0; the clock stays at 0.
  const int settleFrames = static_cast<int>(std::lround(world.scene_.simulation.settleSeconds * 60.0f));
  for (int frame = 0; frame < settleFrames; ++frame)
    if (auto settled = world.simulate(1.0 / 60.0, 1); !settled) return std::unexpected(settled.error());
  if (world.ocean_) world.ocean_->forgetSettlingSpray();
  return world;
}

Result<void> World::loadMeshes(const AssetResolver& resolver) {
  for (const MeshInstance& instance : scene_.meshes) {
    auto loaded = loadSceneMesh(instance, resolver, scene_.file.parent_path());
    if (!loaded) return std::unexpected(loaded.error());
    if (!loaded->note.empty()) notes_.push_back(loaded->note);
    meshes_.push_back(std::move(*loaded));
  }
  return {};
}

Result<void> World::subdivideMeshes() {
  subdivided_.resize(meshes_.size());
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const LoadedMesh& loaded = meshes_[m];
    const MeshInstance& instance = scene_.meshes[m];
    if (!loaded.cage || !instance.subdivision) continue;
    auto surface = SubdividedSurface::create(*loaded.cage, *instance.subdivision);
    if (!surface) return fail("mesh '" + instance.name + "': subdivision: " + surface.error().message);
    subdivided_[m] = std::move(*surface);
  }
  // For the scene's camera and output size at time 0, as the renderer sets them up; load time:
  // use the machine (the triangles do not depend on the thread count).
  const auto refined = refineForCamera(frameInput().camera, glm::uvec2(scene_.output.width, scene_.output.height),
                                       std::max(1u, std::thread::hardware_concurrency()));
  if (!refined) return std::unexpected(refined.error());
  return {};
}

Result<std::vector<std::size_t>> World::refineForCamera(const render::Camera& camera, glm::uvec2 size,
                                                        unsigned threads) {
  if (size.x == 0 || size.y == 0) return fail("refining for the camera: the image must be at least 1x1 pixels");
  const glm::vec2 viewport(size);
  const glm::mat4 viewProjection = camera.projection(viewport.x / viewport.y) * camera.view();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(viewProjection[c][r]))
        return fail("refining for the camera: its position, target, up, field of view and planes give no projection");
  std::vector<std::size_t> changed;
  for (std::size_t m = 0; m < subdivided_.size(); ++m) {
    if (!subdivided_[m]) continue;
    const MeshInstance& instance = scene_.meshes[m];
    const Material* material = scene_.findMaterial(instance.material);
    // Fur keeps its load-time triangles: prepareFurMeshes remade their uvs for the fur once.
    if (material != nullptr && material->kind == MaterialKind::fur) continue;
    LoadedMesh& loaded = meshes_[m];
    const glm::mat4 modelViewProjection = viewProjection * animatedMatrix(scene_, instance, float(time_));
    if (!subdivided_[m]->tessellate(modelViewProjection, viewport, loaded.mesh, loaded.limitInverseRadius, threads))
      continue;
    changed.push_back(m);
  }
  for (std::size_t m = 0; m < skinnedCages_.size(); ++m) {
    if (!skinnedCages_[m]) continue;
    const CharacterPart& part = *characterParts_[m];
    const SceneCharacter& character = characters_[part.character];
    // Posed in the part frame, which frameInput() draws the mesh with.
    const glm::mat4 partFrame = character.partFrame(part.part);
    auto posed = skinnedCages_[m]->pose(character.jointMatricesInPartFrame(part.part),
                                        character.morphWeights(part.part), threads);
    if (!posed) return fail("mesh " + scene_.meshes[m].name + ": " + posed.error().message);
    LoadedMesh& loaded = meshes_[m];
    if (skinnedCages_[m]->tessellate(viewProjection * partFrame, viewport, loaded.mesh, loaded.limitInverseRadius,
                                     threads))
      changed.push_back(m);
  }
  // Skin shades with the limit surface's own curvature (computeSkinCurvatures).
  for (const std::size_t m : changed) {
    const Material* material = scene_.findMaterial(scene_.meshes[m].material);
    if (m < meshCurvatures_.size() && material != nullptr && material->kind == MaterialKind::skin)
      meshCurvatures_[m] = meshes_[m].limitInverseRadius;
  }
  return changed;
}

render::MeshData World::meshData(std::size_t mesh) const {
  const Mesh& geometry = meshes_.at(mesh).mesh;
  return render::MeshData{.positions = geometry.positions,
                          .normals = geometry.normals,
                          .uvs = geometry.uvs,
                          .indices = geometry.indices,
                          .curvatures = meshCurvatures_.at(mesh)};
}

void World::prepareFurMeshes() {
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const Material* material = scene_.findMaterial(scene_.meshes[m].material);
    Mesh& mesh = meshes_[m].mesh;
    if (material == nullptr || material->kind != MaterialKind::fur) continue;
    if (mesh.uvs.empty()) {
      // In metres on the placed mesh, so the material's uv_scale is photo repeats per metre.
      boxProjectUvs(mesh, scene_.meshes[m].transform.scale * material->furUvScale);
      notes_.push_back("mesh " + scene_.meshes[m].name + " has no uvs: its fur uses a box projection");
    } else {
      for (glm::vec2& uv : mesh.uvs) uv *= material->furUvScale;
    }
  }
}

std::vector<render::FurSurfaceData> World::furSurfaces() const {
  std::vector<render::FurSurfaceData> result;
  for (std::size_t i = 0; i < scene_.materials.size(); ++i) {
    // Fur without its photo (a missing asset, or textures not loaded) stays a plain surface.
    if (scene_.materials[i].kind != MaterialKind::fur || !materials_[i].albedo) continue;
    for (std::size_t m = 0; m < scene_.meshes.size(); ++m)
      if (scene_.meshes[m].material == scene_.materials[i].name) result.push_back({.mesh = m, .material = i});
  }
  return result;
}

Result<void> World::loadFurDynamics() {
  // Simulated whether or not the fur is drawn (`mane sim` loads no photos), so the state is the same.
  const std::vector<render::FurSurfaceData> drawn = furSurfaces();
  for (std::size_t m = 0; m < scene_.meshes.size(); ++m) {
    const MeshInstance& instance = scene_.meshes[m];
    const Material* found = scene_.findMaterial(instance.material);
    if (found == nullptr || found->kind != MaterialKind::fur || !found->furMotion) continue;
    const Material& material = *found;
    const FurMotion& motion = *material.furMotion;
    physics::SolverSettings solver;
    solver.fixedStep = scene_.simulation.stepSeconds;
    solver.maxSubstepsPerFrame = scene_.simulation.maxStepsPerFrame;
    solver.damping = motion.damping;
    solver.constraintIterations = motion.iterations;
    solver.shapeStiffness = motion.shapeStiffness;
    auto dynamics = FurDynamics::create(
        meshes_[m].mesh, instance.transform.scale,
        {.guides = motion.guides, .thickness = material.fur.thickness, .solver = solver}, bodyPlacement(m, 0.0));
    if (!dynamics)
      return fail("mesh " + instance.name + ", material " + material.name + ": " + dynamics.error().message);
    const auto index = std::ranges::find_if(drawn, [&](const render::FurSurfaceData& fur) { return fur.mesh == m; });
    movingFurs_.push_back({.fur = std::size_t(index - drawn.begin()), .mesh = m, .dynamics = std::move(*dynamics)});
  }
  return {};
}

std::vector<World::FurLeans> World::furLeans() const {
  std::vector<FurLeans> result;
  const std::size_t drawn = furSurfaces().size();
  for (const MovingFur& fur : movingFurs_)
    if (fur.fur < drawn) result.push_back({fur.fur, fur.dynamics.leans()});
  return result;
}

Result<void> World::loadMaterials(const AssetResolver& resolver) {
  auto loadTexture = [&](const std::string& asset, const std::string& material,
                         const char* role) -> Result<std::optional<Image>> {
    if (asset.empty()) return std::optional<Image>();
    auto lookup = resolver.lookupForScene(asset, scene_.file.parent_path());
    if (!lookup) return std::unexpected(lookup.error());
    if (!lookup->path) {
      notes_.push_back("material " + material + ": " + role + " " + asset + " missing (" + lookup->missingReason +
                       "): rendering without it");
      return std::optional<Image>();
    }
    auto image = loadImage(*lookup->path);
    if (!image) return std::unexpected(image.error());
    return std::optional<Image>(std::move(*image));
  };
  for (const Material& material : scene_.materials) {
    LoadedMaterial loaded;
    auto albedo = loadTexture(material.albedoTexture, material.name, "albedo texture");
    if (!albedo) return std::unexpected(albedo.error());
    auto normal = loadTexture(material.normalMap, material.name, "normal map");
    if (!normal) return std::unexpected(normal.error());
    loaded.albedo = std::move(*albedo);
    loaded.normalMap = std::move(*normal);
    if (material.kind == MaterialKind::skin) {  // Lambert has no use for it
      auto specular = loadTexture(material.specularMap, material.name, "specular map");
      if (!specular) return std::unexpected(specular.error());
      loaded.specularMap = std::move(*specular);
    }
    materials_.push_back(std::move(loaded));
  }
  return {};
}

Result<void> World::computeSkinCurvatures() {
  meshCurvatures_.assign(meshes_.size(), {});
  for (std::size_t m = 0; m < scene_.meshes.size(); ++m) {
    const Material* material = scene_.findMaterial(scene_.meshes[m].material);
    if (material == nullptr || material->kind != MaterialKind::skin) continue;
    const Mesh& mesh = meshes_[m].mesh;
    if (!meshes_[m].limitInverseRadius.empty()) {  // subdivided: the limit surface's own curvature
      meshCurvatures_[m] = meshes_[m].limitInverseRadius;
      continue;
    }
    auto curvature = computeVertexCurvature(mesh);
    if (!curvature) return fail("mesh " + scene_.meshes[m].name + ": curvature: " + curvature.error().message);
    auto inverseRadius = skinInverseRadius(mesh, *curvature);
    if (!inverseRadius) return fail("mesh " + scene_.meshes[m].name + ": curvature: " + inverseRadius.error().message);
    meshCurvatures_[m] = std::move(*inverseRadius);
  }
  return {};
}

Result<void> World::loadGrooms(const AssetResolver& resolver, SceneColliders& colliders) {
  for (std::size_t sceneGroom = 0; sceneGroom < scene_.grooms.size(); ++sceneGroom) {
    const Groom& groom = scene_.grooms[sceneGroom];
    const auto meshIt = std::find_if(scene_.meshes.begin(), scene_.meshes.end(),
                                     [&](const MeshInstance& mesh) { return mesh.name == groom.attachedMesh; });
    const auto meshIndex = static_cast<std::size_t>(meshIt - scene_.meshes.begin());
    // The solver takes its rest lengths in head space and wants a rigid head transform, so
    // head space is the mesh's model space scaled to metres: the mesh's uniform scale goes into
    // the guide points here and out of the transform (bodyPlacement).
    const float scale = meshIt->transform.scale;
    std::vector<std::vector<glm::vec3>> guides;
    GuideLooks looks;
    if (groom.isProcedural()) {
      // Guides rooted by area on the mesh's scalp, the groom's ScalpRegion (by default the
      // upward-facing triangles, normal y ≥ 0.2, in the top quarter of its height). Lengths are
      // in metres, so the mesh goes to metres.
      const Mesh& mesh = meshes_[meshIndex].mesh;
      std::vector<glm::vec3> metres(mesh.positions.size());
      for (std::size_t v = 0; v < metres.size(); ++v) metres[v] = mesh.positions[v] * scale;
      physics::GroomSettings settings;
      settings.seed = 1 + sceneGroom;
      if (groom.strandCount > 0) settings.strandCount = static_cast<std::size_t>(groom.strandCount);
      if (groom.strandLengthMetres > 0.0f) settings.strandLength = groom.strandLengthMetres;
      settings.comb = groom.comb;
      settings.partingComb = groom.parting.comb;
      settings.partingX = groom.parting.x;
      settings.partingBackZ = groom.parting.backZ;
      if (subdivided_[meshIndex]) {
        // Drawn as its limit surface: the roots sit on that surface itself, which every
        // re-tessellation approximates, rather than on the triangles of the load-time view.
        auto roots = sampleScalpOnLimitSurface(subdivided_[meshIndex]->limit(), groom.scalp, settings.strandCount,
                                               settings.seed);
        if (!roots) return fail("groom " + groom.name + ": mesh " + meshIt->name + ": " + roots.error().message);
        std::vector<glm::vec3> points, normals;
        for (const LimitRoot& root : *roots) {
          points.push_back(root.position * scale);
          normals.push_back(root.normal);
        }
        auto generated = physics::generateGroomFromRoots(settings, points, normals);
        if (!generated) return fail("groom " + groom.name + ": " + generated.error().message);
        guides = std::move(*generated);
      } else {
        const std::vector<std::uint32_t> scalp = scalpTriangles(mesh, groom.scalp);
        if (scalp.empty())
          return fail("groom " + groom.name + ": mesh " + meshIt->name +
                      " has no scalp (no triangle in the groom's scalp region)");
        std::vector<float> density;
        if (groom.scalp.hairlineDensity > 1.0f)
          for (const std::uint32_t t : scalp) {
            const glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
            density.push_back(groom.scalp.densityAt(glm::normalize(
                glm::cross(mesh.positions[mesh.indices[3 * t + 1]] - a, mesh.positions[mesh.indices[3 * t + 2]] - a))));
          }
        auto generated = physics::generateGroomOnMesh(settings, metres, mesh.indices, scalp, density);
        if (!generated) return fail("groom " + groom.name + ": " + generated.error().message);
        guides = std::move(*generated);
      }
      if (groom.drape) {
        physics::ColliderSet shapes;
        if (!groom.colliders.empty()) {
          auto set = colliders.build(groom.colliders, meshIndex);
          if (!set) return fail("groom " + groom.name + ": colliders: " + set.error().message);
          shapes = std::move(*set);
        }
        // Gravity as the guides' frame (the body's, where it stands at time 0) sees it.
        physics::DrapeSettings drape = *groom.drape;
        if (groom.simulation.gravity != glm::vec3(0.0f))
          drape.down = glm::mat3(glm::inverse(bodyPlacement(meshIndex, 0.0))) * groom.simulation.gravity;
        if (auto laid = physics::drapeGuides(guides, shapes, drape); !laid)
          return fail("groom " + groom.name + ": drape: " + laid.error().message);
      }
      appendSceneLooks(guides.size(), groom.rendering, looks);
    } else {
      // Like meshes: a missing asset is a note and the groom is skipped (all its files or
      // nothing); a file that does not parse is an error. Groom files hold strands in their head
      // mesh's model space (the TressFX ponytail's four files sit on their own head in the same
      // units, ../shared/assets/README.md, once their inverted z is turned back: `invert_z`).
      std::vector<std::filesystem::path> files;
      for (const std::string& source : groom.sources) {
        auto lookup = resolver.lookupForScene(source, scene_.file.parent_path());
        if (!lookup) return fail("groom " + groom.name + ": " + lookup.error().message);
        if (!lookup->path) {
          notes_.push_back("groom " + groom.name + ": " + source + " missing (" + lookup->missingReason + "): skipped");
          break;
        }
        files.push_back(*lookup->path);
      }
      if (files.size() < groom.sources.size()) continue;
      // Flawed strands are repaired or dropped by the loader; one note per groom says which.
      std::string repairs;
      for (std::size_t f = 0; f < files.size(); ++f) {
        const std::filesystem::path& file = files[f];
        auto loaded = loadGroomFile(file, {.strict = groom.strict});
        if (!loaded) return fail("groom " + groom.name + ": " + loaded.error().message);
        if (!loaded->repairs.clean())
          repairs += (repairs.empty() ? "" : "; ") + groom.sources[f] + ": " + loaded->repairs.summary();
        // Widths in file units become metres as the points do (below), by the mesh's scale.
        appendFileLooks(*loaded, groom.rendering, scale, looks);
        guides.insert(guides.end(), std::make_move_iterator(loaded->strands.begin()),
                      std::make_move_iterator(loaded->strands.end()));
      }
      if (!repairs.empty())
        notes_.push_back("groom " + groom.name + ": flawed strands repaired or dropped (\"strict\": true refuses them): " +
                         repairs);
      if (const std::string note = looks.note(); !note.empty()) notes_.push_back("groom " + groom.name + ": " + note);
      const glm::vec3 axes(1.0f, 1.0f, groom.invertZ ? -1.0f : 1.0f);
      for (std::vector<glm::vec3>& strand : guides)
        for (glm::vec3& point : strand) point *= axes * scale;
    }
    const glm::mat4 body = bodyPlacement(meshIndex, 0.0);
    auto hair = physics::HairSystem::create(guides, solverSettings(groom.simulation, scene_.simulation), body);
    if (!hair) return fail("groom " + groom.name + " (" + sourceList(groom) + "): " + hair.error().message);
    std::optional<JointColliders> jointColliders;
    if (!groom.colliders.empty()) {
      auto set = colliders.build(groom.colliders, meshIndex);
      if (!set) return fail("groom " + groom.name + ": colliders: " + set.error().message);
      if (groom.colliders.followsJoints()) {
        auto joints = JointColliders::create(groom.colliders, std::move(*set),
                                             characters_[characterParts_[meshIndex]->character]);
        if (!joints) return fail("groom " + groom.name + ": colliders: " + joints.error().message);
        jointColliders = std::move(*joints);
        set = jointColliders->at(characters_[characterParts_[meshIndex]->character], body);
      }
      if (auto applied = hair->setColliders(std::move(*set)); !applied)
        return fail("groom " + groom.name + ": colliders: " + applied.error().message);
    }
    // On a character: each root bound to the surface under it, its rest normal the surface's.
    std::optional<physics::SurfaceBinding> roots;
    if (characterParts_[meshIndex]) {
      std::vector<glm::vec3> rootPoints;
      for (std::size_t strand = 0; strand < hair->strandCount(); ++strand)
        rootPoints.push_back(hair->strandPositions(strand).front());
      auto bound = bindToPart(meshIndex, rootPoints, "groom " + groom.name);
      if (!bound) return std::unexpected(bound.error());
      std::vector<glm::vec3> normals;
      if (auto followed = followPart(meshIndex, *bound, rootPoints, normals); !followed) return followed;
      const glm::mat3 toHead(glm::inverse(body));
      for (glm::vec3& normal : normals) normal = toHead * normal;
      if (auto set = hair->setRootRestNormals(normals); !set) return fail("groom " + groom.name + ": " + set.error().message);
      roots = std::move(*bound);
    }
    const std::size_t denseStrands = groom.rendering.denseStrands > 0
                                         ? static_cast<std::size_t>(groom.rendering.denseStrands)
                                         : std::max(kDefaultDenseStrands, guides.size());
    std::optional<DenseStrandLayout> dense = denseGroom(guides, denseStrands, groom.rendering);
    std::vector<render::HairStrandLook> denseLooks;
    if (dense) denseLooks = denseStrandLooks(*dense, looks.guides);
    grooms_.push_back(SimulatedGroom{meshIndex, std::move(*hair), sceneGroom, std::move(dense), std::move(denseLooks),
                                     std::move(roots), std::move(jointColliders)});
    if (!grooms_.back().dense)
      notes_.push_back("groom " + groom.name + ": guides of different lengths: simulated, not drawn");
  }
  return {};
}

std::optional<DenseStrandLayout> World::denseGroom(std::span<const std::vector<glm::vec3>> guides,
                                                   std::size_t strandCount, const GroomRendering& rendering) {
  physics::DenseGroomSettings settings;
  settings.strandCount = strandCount;
  settings.verticesPerStrand = static_cast<std::size_t>(rendering.verticesPerStrand);
  settings.blend = rendering.guideBlend;
  settings.curve = rendering.curve;
  settings.clump = rendering.clump;
  settings.clumpProfile = rendering.clumpProfile;
  settings.curlRadius = rendering.curlRadius;
  settings.curlPeriod = rendering.curlPeriod;
  settings.curlVariation = rendering.curlVariation;
  settings.frizz = rendering.frizz;
  auto layout = physics::buildDenseStrandLayout(guides, settings);
  if (!layout) return std::nullopt;  // unequal point counts: the only failure valid guides can give
  return std::move(*layout);
}

std::vector<World::HairGuides> World::hairGuides() const {
  std::vector<HairGuides> result;
  for (const SimulatedGroom& groom : grooms_)
    if (groom.dense)
      result.push_back({result.size(), groom.hair.particles().positions, std::size_t(&groom - grooms_.data())});
  return result;
}

bool World::fireCannon() {
  if (!ocean_ || !ocean_->smoke()) return false;
  ocean_->fireCannon();
  return true;
}

Result<void> World::setWindSpeed(float speed) {
  if (!ocean_) return fail("the scene has no sea for the wind to blow on");
  const float scale = speed / scene_.ocean->waves.windSpeed;
  if (auto set = ocean_->setWindSpeed(speed); !set) return set;
  for (std::size_t i = 0; i < cloths_.size(); ++i)
    if (const std::optional<glm::vec3>& wind = scene_.cloths[i].wind)
      if (auto set = cloths_[i].setWind(*wind * scale); !set) return set;
  return {};
}

glm::mat4 World::meshModel(std::size_t mesh) const {
  if (ocean_ && ocean_->shipMesh() == mesh) return ocean_->shipModel();
  const MeshInstance& instance = scene_.meshes[mesh];
  if (!instance.attachedMesh.empty()) {
    const auto body = std::ranges::find(scene_.meshes, instance.attachedMesh, &MeshInstance::name);
    return bodyPlacement(static_cast<std::size_t>(body - scene_.meshes.begin()), time_) * instance.transform.matrix();
  }
  return animatedMatrix(scene_, instance, static_cast<float>(time_));
}

glm::mat4 World::bodyPlacement(std::size_t mesh, double time) const {
  if (ocean_ && ocean_->shipMesh() == mesh) return ocean_->shipBody();
  if (const std::optional<CharacterPart>& part = characterParts_[mesh])
    return characters_[part->character].partFrame(part->part);
  return bodyMatrix(scene_, scene_.meshes[mesh], static_cast<float>(time));
}

Result<void> World::loadGlasses() {
  for (const Glasses& glasses : scene_.glasses) {
    auto model = buildGlasses(glasses);
    if (!model) return std::unexpected(model.error());
    const auto body = std::find_if(scene_.meshes.begin(), scene_.meshes.end(),
                                   [&](const MeshInstance& mesh) { return mesh.name == glasses.attachedMesh; });
    glasses_.push_back({.body = static_cast<std::size_t>(body - scene_.meshes.begin()),
                        .placement = glasses.transform.matrix(),
                        .model = std::move(*model)});
  }
  return {};
}

Result<void> World::loadCloths(const AssetResolver& resolver, SceneColliders& colliders) {
  for (const Cloth& cloth : scene_.cloths) {
    auto rest = loadClothMesh(cloth, resolver, scene_.file.parent_path());
    if (!rest) return std::unexpected(rest.error());
    const auto body = std::find_if(scene_.meshes.begin(), scene_.meshes.end(),
                                   [&](const MeshInstance& mesh) { return mesh.name == cloth.attachedMesh; });
    const auto bodyIndex = static_cast<std::size_t>(body - scene_.meshes.begin());
    const glm::mat4 placement = bodyPlacement(bodyIndex, 0.0);
    ClothOnCharacter follower;
    physics::ColliderSet set;
    if (!cloth.colliders.empty()) {
      auto built = colliders.build(cloth.colliders, bodyIndex);
      if (!built) return fail("cloth '" + cloth.name + "': colliders: " + built.error().message);
      set = std::move(*built);
      if (cloth.colliders.followsJoints()) {
        auto joints = JointColliders::create(cloth.colliders, std::move(set),
                                             characters_[characterParts_[bodyIndex]->character]);
        if (!joints) return fail("cloth '" + cloth.name + "': colliders: " + joints.error().message);
        follower.jointColliders = std::move(*joints);
        set = follower.jointColliders->at(characters_[characterParts_[bodyIndex]->character], placement);
      }
    }
    Cloth placed = cloth;
    if (const std::optional<CharacterPart>& part = characterParts_[bodyIndex]) {
      // On a character the transform places the cloth in the character's own frame at time 0
      // (its axes, metres), where people author it, rather than in the part frame of a joint.
      const glm::mat4 inCharacter = rigidPart(scene_.characters[part->character].transform.matrix()) *
                                    glm::translate(glm::mat4(1.0f), cloth.transform.translation) *
                                    glm::mat4(glm::mat3(Transform{.rotationDegrees = cloth.transform.rotationDegrees}.matrix()));
      placed.transform = transformOf(glm::inverse(placement) * inCharacter);
      placed.transform.scale = cloth.transform.scale;
    }
    auto created = SceneCloth::create(placed, std::move(*rest), scene_.simulation, placement, std::move(set));
    if (!created) return std::unexpected(created.error());
    if (characterParts_[bodyIndex]) {
      // Each pin bound to the surface under it, where the cloth's transform placed it.
      std::vector<glm::vec3> pins;
      for (std::uint32_t v : created->cloth().pinnedVertices()) pins.push_back(created->cloth().particles().positions[v]);
      auto bound = bindToPart(bodyIndex, pins, "cloth '" + cloth.name + "'");
      if (!bound) return std::unexpected(bound.error());
      follower.pins = std::move(*bound);
    }
    cloths_.push_back(std::move(*created));
    clothBodies_.push_back(bodyIndex);
    clothFollowers_.push_back(std::move(follower));
  }
  return {};
}

Result<void> World::advance(double frameDt, unsigned threads) {
  if (!(frameDt >= 0.0) || !std::isfinite(frameDt)) return fail("frame time must be finite and ≥ 0");
  time_ += frameDt;
  lastFrameDt_ = frameDt;
  poseCharacters();
  return simulate(frameDt, threads);
}

Result<void> World::showTime(double time) {
  if (!(time >= 0.0) || !std::isfinite(time)) return fail("time must be finite and ≥ 0");
  time_ = time;
  lastFrameDt_ = 0.0;
  poseCharacters();
  return {};
}

Result<void> World::simulate(double frameDt, unsigned threads) {
  // The ship first: what rides on it follows where it is at the end of the frame.
  if (ocean_)
    if (auto advanced = ocean_->advance(time_, frameDt, threads); !advanced)
      return fail("ocean: " + advanced.error().message);
  std::vector<glm::vec3> targets, normals;
  for (SimulatedGroom& groom : grooms_) {
    const std::string& name = scene_.grooms[groom.sceneGroom].name;
    const glm::mat4 head = bodyPlacement(groom.mesh, time_);
    if (auto set = groom.hair.setHeadTransform(head); !set) return std::unexpected(set.error());
    if (groom.roots) {
      if (auto followed = followPart(groom.mesh, *groom.roots, targets, normals, threads); !followed)
        return fail("groom " + name + ": " + followed.error().message);
      if (auto set = groom.hair.setRootTargets(targets, normals); !set)
        return fail("groom " + name + ": " + set.error().message);
    }
    if (groom.jointColliders) {
      const SceneCharacter& character = characters_[characterParts_[groom.mesh]->character];
      if (auto set = groom.hair.setColliders(groom.jointColliders->at(character, head)); !set)
        return fail("groom " + name + ": colliders: " + set.error().message);
    }
    if (auto advanced = groom.hair.advance(frameDt, threads); !advanced)
      return fail("groom " + scene_.grooms[groom.sceneGroom].name + ": " + advanced.error().message);
  }
  for (std::size_t i = 0; i < cloths_.size(); ++i) {
    const glm::mat4 body = bodyPlacement(clothBodies_[i], time_);
    const ClothOnCharacter& follower = clothFollowers_[i];
    if (follower.pins) {
      if (auto followed = followPart(clothBodies_[i], *follower.pins, targets, normals, threads); !followed)
        return fail("cloth '" + scene_.cloths[i].name + "': " + followed.error().message);
      if (auto set = cloths_[i].setPinTargets(targets); !set) return set;
    }
    if (follower.jointColliders) {
      const SceneCharacter& character = characters_[characterParts_[clothBodies_[i]]->character];
      if (auto set = cloths_[i].setColliders(follower.jointColliders->at(character, body)); !set) return set;
    }
    if (auto advanced = cloths_[i].advance(body, frameDt, threads); !advanced) return advanced;
  }
  if (auto handed = handSailsToShip(); !handed) return handed;
  for (MovingFur& fur : movingFurs_)
    if (auto advanced = fur.dynamics.advance(bodyPlacement(fur.mesh, time_), frameDt, threads);
        !advanced)
      return fail("mesh " + scene_.meshes[fur.mesh].name + ": " + advanced.error().message);
  return {};
}

Result<void> World::handSailsToShip() {
  const std::optional<std::size_t> ship = ocean_ ? ocean_->shipMesh() : std::nullopt;
  if (!ship) return {};
  // The air's push on each sail reaches the hull through the yards it is pinned to: summed about
  // the ship's centre of mass, it acts on the ship's next frame (its own is stepped first).
  const glm::vec3 centre(ocean_->shipBody()[3]);
  physics::WindPush push;
  for (std::size_t i = 0; i < cloths_.size(); ++i) {
    if (clothBodies_[i] != *ship) continue;
    const physics::WindPush sail = cloths_[i].cloth().windPush(centre);
    push.force += sail.force;
    push.moment += sail.moment;
  }
  if (auto set = ocean_->setShipLoad(push.force, push.moment); !set)
    return fail("ocean: sails: " + set.error().message);
  return {};
}

render::StaticScene World::staticScene() const {
  render::StaticScene result;
  result.environment = environment_;
  if (ocean_) result.ocean = ocean_->oceanData();
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const Mesh& mesh = meshes_[m].mesh;
    result.meshes.push_back(render::MeshData{.positions = mesh.positions,
                                             .normals = mesh.normals,
                                             .uvs = mesh.uvs,
                                             .indices = mesh.indices,
                                             .curvatures = meshCurvatures_[m],
                                             .skinning = gpuSkins_[m] ? &*gpuSkins_[m] : nullptr});
  }
  for (std::size_t i = 0; i < scene_.materials.size(); ++i) {
    render::MaterialData material{.baseColor = scene_.materials[i].baseColour,
                                  .translucency = scene_.materials[i].translucency,
                                  .transmission = scene_.materials[i].transmission,
                                  .doubleSided = scene_.materials[i].doubleSided};
    if (materials_[i].albedo) material.albedo = textureOf(*materials_[i].albedo);
    if (materials_[i].normalMap) material.normalMap = textureOf(*materials_[i].normalMap);
    if (scene_.materials[i].kind == MaterialKind::fur && material.albedo) {
      material.shading = render::SurfaceShading::kFur;
      material.fur = scene_.materials[i].fur;
    }
    if (scene_.materials[i].kind == MaterialKind::skin) {
      material.shading = render::SurfaceShading::kSkin;
      material.skin = scene_.materials[i].skin;
      if (materials_[i].specularMap) material.specularMap = textureOf(*materials_[i].specularMap);
    }
    result.materials.push_back(material);
  }
  // Last: the material of meshes that name none (a plain Material's defaults).
  result.materials.push_back(render::MaterialData{.baseColor = Material{}.baseColour});
  // Grooms, drawn as their scene's `render` block says (scenes/README.md).
  for (const SimulatedGroom& groom : grooms_) {
    if (!groom.dense) continue;
    const GroomRendering& rendering = scene_.grooms[groom.sceneGroom].rendering;
    result.grooms.push_back(render::HairGroomData{
        .layout = *groom.dense, .look = rendering.look, .settings = rendering.settings, .strandLooks = groom.denseLooks});
  }
  result.hairShadows = scene_.hairShadows;
  result.furs = furSurfaces();
  // Cloth surfaces come after the scene's meshes, in world space, rewritten every frame.
  for (const SceneCloth& cloth : cloths_) {
    const Mesh& surface = cloth.surface();
    result.meshes.push_back(render::MeshData{surface.positions, surface.normals, surface.uvs, surface.indices, true});
  }
  // Then the glasses' frames, in their own frame.
  for (const WornGlasses& glasses : glasses_) {
    const Mesh& frame = glasses.model.frame;
    result.meshes.push_back(render::MeshData{
        .positions = frame.positions, .normals = frame.normals, .uvs = frame.uvs, .indices = frame.indices});
  }
  return result;
}

std::vector<World::DynamicMesh> World::dynamicMeshes() const {
  std::vector<DynamicMesh> result;
  for (std::size_t i = 0; i < cloths_.size(); ++i)
    result.push_back({meshes_.size() + i, cloths_[i].surface().positions, cloths_[i].surface().normals});
  return result;
}

render::FrameInput World::frameInput() const {
  render::FrameInput frame;
  frame.post = scene_.post;
  if (ocean_) {
    frame.ocean = ocean_->frame(time_, static_cast<float>(lastFrameDt_));
    frame.effects = ocean_->effects();
  }
  const Camera& camera = scene_.camera;
  frame.camera = render::Camera{.position = cameraPositionAt(camera, time_),
                                .target = camera.target,
                                .up = camera.up,
                                .verticalFovRadians = glm::radians(camera.verticalFovDegrees),
                                .nearPlane = camera.nearPlane,
                                .farPlane = camera.farPlane};
  if (environmentSun_) frame.lights.push_back(*environmentSun_);
  for (const Light& light : scene_.lights)
    // The scene says where light travels; the renderer wants the way back to the light.
    frame.lights.push_back({.direction = -light.direction,
                            .color = light.colour,
                            .intensity = light.intensity,
                            .discRadius = glm::radians(light.discRadiusDegrees),
                            .discRadiance = light.discRadiance});
  // loadScene has checked that a named material exists; no name means the default one, which
  // staticScene() puts after the scene's own.
  auto materialIndex = [&](const std::string& name) {
    std::size_t material = scene_.materials.size();
    for (std::size_t m = 0; m < scene_.materials.size(); ++m)
      if (scene_.materials[m].name == name) material = m;
    return material;
  };
  for (std::size_t i = 0; i < scene_.meshes.size(); ++i) {
    const MeshInstance& mesh = scene_.meshes[i];
    const std::optional<CharacterPart>& part = characterParts_[i];
    if (part && part->primitive < 0) continue;  // a whole part, for the physics; its primitives draw it
    frame.instances.push_back({.mesh = i,
                               .material = materialIndex(mesh.material),
                               .model = part ? characters_[part->character].partFrame(part->part) : meshModel(i)});
  }
  for (std::size_t i = 0; i < cloths_.size(); ++i)  // already in world space
    frame.instances.push_back({.mesh = meshes_.size() + i, .material = materialIndex(scene_.cloths[i].material)});
  for (std::size_t i = 0; i < glasses_.size(); ++i) {
    const WornGlasses& glasses = glasses_[i];
    const glm::mat4 placed = bodyPlacement(glasses.body, time_) * glasses.placement;
    frame.instances.push_back({.mesh = meshes_.size() + cloths_.size() + i,
                               .material = materialIndex(scene_.glasses[i].material),
                               .model = placed});
    for (const render::Lens& lens : glasses.model.lenses) frame.lenses.push_back({lens.shape, placed * lens.model});
  }
  return frame;
}

std::uint64_t World::stateHash() const {
  physics::StateHasher hasher;
  for (const SimulatedGroom& groom : grooms_) hasher.addValue(groom.hair.stateHash());
  for (const SceneCloth& cloth : cloths_) hasher.addValue(cloth.cloth().stateHash());
  for (const MovingFur& fur : movingFurs_) hasher.addValue(fur.dynamics.guides().stateHash());
  if (ocean_) ocean_->hash(hasher);
  hasher.addValue(time_);
  return hasher.value();
}

std::size_t World::guideStrandCount() const {
  std::size_t count = 0;
  for (const SimulatedGroom& groom : grooms_) count += groom.hair.strandCount();
  return count;
}

std::size_t World::particleCount() const {
  std::size_t count = 0;
  for (const SimulatedGroom& groom : grooms_) count += groom.hair.particles().size();
  for (const SceneCloth& cloth : cloths_) count += cloth.cloth().particles().size();
  return count;
}

}  // namespace mane::scenes
