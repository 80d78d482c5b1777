#include "render/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "render/frame_validation.hpp"
#include "render/strand_lod.hpp"
#include "render/strand_looks.hpp"

namespace mane::render {
namespace {

vk::SampleCountFlagBits sampleCount(std::uint32_t samples) {
  return samples >= 4 ? vk::SampleCountFlagBits::e4 : vk::SampleCountFlagBits::e1;
}

}  // namespace

Renderer::Renderer(const Device& device, const RendererSettings& settings, std::unique_ptr<HairShadowPass> shadows)
    : device_(&device),
      target_(
          device,
          {.extent = settings.extent, .samples = sampleCount(settings.msaaSamples), .skinGBuffer = settings.deferSkin}),
      occlusion_(device, target_),
      hideOccludedHair_(settings.hideOccludedHair),
      shadows_(std::move(shadows)),
      translucency_(device),
      surfaceShadows_(device, SurfaceScene::kVertexStride),
      scene_(device, *shadows_, translucency_.lightDepth(), surfaceShadows_),
      surfaces_(device, scene_, translucency_, *shadows_, RenderTarget::kHdrFormat, RenderTarget::kDepthFormat,
                target_.samples()),
      deferredSkin_(device, scene_, *shadows_, RenderTarget::kHdrFormat, RenderTarget::kDepthFormat),
      discs_(device, RenderTarget::kHdrFormat, RenderTarget::kDepthFormat, target_.samples()),
      post_(device, target_.hdr()),
      output_(device, target_, post_),
      timer_(device, 16) {
  if (!target_.skinGBuffer().empty()) deferredSkin_.setGBuffer(target_.skinGBuffer());
}

Result<std::unique_ptr<Renderer>> Renderer::create(const Device& device, const RendererSettings& settings) {
  if (settings.extent.width == 0 || settings.extent.height == 0)
    return fail("the image size must be at least 1x1 pixels");
  if (settings.msaaSamples != 1 && settings.msaaSamples != 4)
    return fail("MSAA must be 1 or 4 samples, not " + std::to_string(settings.msaaSamples));
  const auto& limits = device.limits();
  if (settings.extent.width > limits.maxFramebufferWidth || settings.extent.height > limits.maxFramebufferHeight)
    return fail("the image size " + std::to_string(settings.extent.width) + "x" +
                std::to_string(settings.extent.height) + " exceeds the device's framebuffer limit");
  auto shadows = HairShadowPass::create(device);
  if (!shadows) return std::unexpected(shadows.error());
  try {
    return std::unique_ptr<Renderer>(new Renderer(device, settings, std::move(*shadows)));
  } catch (const std::exception& error) {
    return fail(std::string("creating the renderer failed: ") + error.what());
  }
}

Result<void> Renderer::setScene(const StaticScene& scene) {
  if (auto valid = validateScene(scene, device_->limits()); !valid) return valid;
  skinned_.clear();  // before the buffers they write into go
  scene_.setHairVisibility(nullptr);  // before the volume it reads goes
  hairDensity_.reset();               // before the strands it reads go
  hair_.clear();
  // Strands first: the shadow maps read their positions, and the shading reads the maps.
  std::vector<HairShadowPass::Groom> shadowed;
  for (std::size_t g = 0; g < scene.grooms.size(); ++g) {
    const HairGroomData& groom = scene.grooms[g];
    auto strands = StrandInterpolationPass::create(*device_, groom.layout);
    if (!strands) return fail("groom " + std::to_string(g) + ": " + strands.error().message);
    if (auto looks = validateStrandLooks(groom.strandLooks, groom.layout.strands.size()); !looks)
      return fail("groom " + std::to_string(g) + ": " + looks.error().message);
    const ShadowedLook shadowLook = shadowedLook(groom.settings, groom.strandLooks);
    float stray = 0.0f;
    for (const DenseStrand& strand : groom.layout.strands)
      stray = std::max(stray, glm::length(strand.rootOffset) + glm::length(strand.tipJitter));
    const StrandInterpolationPass& pass = **strands;
    shadowed.push_back({.strands = {.positions = &pass.positions(),
                                    .strandCount = pass.strandCount(),
                                    .verticesPerStrand = pass.vertexCount()},
                        .width = shadowLook.width,
                        .opacity = shadowLook.opacity,
                        .extinction = groom.settings.shadowExtinction});
    Buffer looks;
    if (!groom.strandLooks.empty()) looks = uploadStrandLooks(*device_, groom.strandLooks, pass.strandCount());
    hair_.push_back({.strands = std::move(*strands),
                     .order = std::make_unique<StrandDrawOrder>(groom.layout),
                     .looks = std::move(looks),
                     .settings = groom.settings,
                     .strayFromGuides = stray});
  }
  // The furs cast into the same maps, after the grooms; their pipelines follow the maps below.
  auto furs = FurSurfaces::create(*device_, scene,
                                  {.colorFormat = RenderTarget::kHdrFormat,
                                   .depthFormat = RenderTarget::kDepthFormat,
                                   .samples = target_.samples()},
                                  *shadows_);
  if (!furs) return std::unexpected(furs.error());
  furs_ = std::move(*furs);
  furShadowsBound_.assign(furs_.size(), false);
  const std::vector<HairShadowPass::Groom> furCasters = furs_.shadowCasters();
  shadowed.insert(shadowed.end(), furCasters.begin(), furCasters.end());
  if (auto set = shadows_->setGrooms(shadowed, scene.hairShadows); !set) return set;
  scene_.setEnvironment(nullptr);  // before the pass it may point at goes
  environment_.reset();
  if (scene.environment) {
    auto environment = EnvironmentPass::create(
        *device_, *scene.environment,
        {.color = RenderTarget::kHdrFormat, .depth = RenderTarget::kDepthFormat, .samples = target_.samples()});
    if (!environment) return std::unexpected(environment.error());
    environment_ = std::move(*environment);
  }
  // The hair hides part of the environment (render/passes/hair_density_pass.hpp): the grooms'
  // entries of `shadowed`, ahead of the furs'.
  if (scene.environment && !scene.grooms.empty()) {
    auto density = HairDensityPass::create(*device_, std::span(shadowed).first(scene.grooms.size()));
    if (!density) return std::unexpected(density.error());
    hairDensity_ = std::move(*density);
    scene_.setHairVisibility(hairDensity_.get());
  }
  ocean_.reset();
  if (scene.ocean) {
    auto ocean = OceanPass::create(*device_, *scene.ocean);
    if (!ocean) return std::unexpected(ocean.error());
    ocean_ = std::move(*ocean);
    if (auto built = ocean_->buildDrawPipeline(
            {.color = RenderTarget::kHdrFormat, .depth = RenderTarget::kDepthFormat, .samples = target_.samples()},
            scene_.frameLayout());
        !built)
      return built;
  }
  // After the maps exist: the surfaces' pipelines are specialised for them.
  try {
    scene_.setScene(scene);
    scene_.setEnvironment(environment_.get());
    translucency_.setScene(scene);
    surfaces_.buildPipelines();
    deferredSkin_.buildPipelines();
  } catch (const std::exception& error) {
    return fail(std::string("uploading the scene failed: ") + error.what());
  }
  if (auto set = setTextureSpaceSkins(scene); !set) return set;
  if (auto set = setSkinnedMeshes(scene); !set) return set;
  refreshShadowDescriptors();

  for (std::size_t g = 0; g < scene.grooms.size(); ++g) {
    const HairGroomData& groom = scene.grooms[g];
    HairGroom& drawn = hair_[g];
    const auto failed = [&](const Error& error) { return fail("groom " + std::to_string(g) + ": " + error.message); };
    const auto look = static_cast<std::size_t>(groom.look);
    if (look >= 2) return fail("groom " + std::to_string(g) + ": unknown hair look");
    if (luts_.size() < 2) luts_.resize(2);
    if (!luts_[look]) {
      auto lut = MarschnerLut::create(*device_, groom.look == HairLook::kDark ? darkHairParams() : blondeHairParams());
      if (!lut) return failed(lut.error());
      luts_[look] = std::make_unique<MarschnerLut>(std::move(*lut));
    }
    const StrandInterpolationPass& pass = *drawn.strands;
    auto lighting = HairLightingPass::create(*device_, *luts_[look], *shadows_, pass.positions(), pass.tangents(),
                                             pass.strandCount(), pass.vertexCount());
    if (!lighting) return failed(lighting.error());
    auto ribbons = HairPass::create(*device_, {.colorFormat = RenderTarget::kHdrFormat,
                                               .depthFormat = RenderTarget::kDepthFormat,
                                               .samples = target_.samples()});
    if (!ribbons) return failed(ribbons.error());
    if (auto set = (*ribbons)->setStrands({.positions = *pass.positions().buffer(),
                                           .tangents = *pass.tangents().buffer(),
                                           .radiance = *(*lighting)->radiance().buffer(),
                                           .strandCount = pass.strandCount(),
                                           .verticesPerStrand = pass.vertexCount()});
        !set)
      return failed(set.error());
    if (drawn.looks.size() != 0) {
      if (auto set = (*ribbons)->setStrandLooks(drawn.looks); !set) return failed(set.error());
      if (auto set = (*lighting)->setStrandLooks(drawn.looks); !set) return failed(set.error());
    }
    if (hideOccludedHair_) (*ribbons)->setOcclusion(occlusion_.tileMaxDepth(), occlusion_.tiles());
    (*lighting)->setShadeList((*ribbons)->shadeList());
    (*lighting)->setEnvironment(environment_ ? std::optional(environment_->irradianceOverPi()) : std::nullopt);
    (*lighting)->setHairVisibility(hairDensity_.get());
    drawn.lighting = std::move(*lighting);
    drawn.ribbons = std::move(*ribbons);
  }
  return {};
}

Result<void> Renderer::setTextureSpaceSkins(const StaticScene& scene) {
  textureSpaceSkins_.clear();
  diffusionMeshes_.clear();
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    const MaterialData& material = scene.materials[m];
    if (material.shading != SurfaceShading::kSkin || material.skin.diffusion != SkinDiffusion::kTextureSpace) continue;
    auto pass =
        SkinDiffusionPass::create(*device_, {.size = material.skin.irradianceSize}, shadows_.get(), &surfaceShadows_);
    if (!pass) return fail("material " + std::to_string(m) + ": " + pass.error().message);
    if (auto set = pass->setNormalMap(material.normalMap); !set)
      return fail("material " + std::to_string(m) + ": " + set.error().message);
    auto owned = std::make_unique<SkinDiffusionPass>(std::move(*pass));
    scene_.setDiffusedIrradiance(m, owned->diffusedIrradiance(), owned->sampler());
    textureSpaceSkins_.push_back({m, std::move(owned)});
  }
  if (textureSpaceSkins_.empty()) return {};
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshData& mesh = scene.meshes[i];
    diffusionMeshes_.emplace_back();
    if (mesh.dynamic || mesh.uvs.empty() || mesh.normals.empty()) continue;
    auto uploaded = SkinDiffusionMesh::create(*device_, mesh);
    if (!uploaded) return fail("mesh " + std::to_string(i) + ": " + uploaded.error().message);
    diffusionMeshes_.back() = std::move(*uploaded);
  }
  return {};
}

Result<void> Renderer::setSkinnedMeshes(const StaticScene& scene) {
  skinned_.clear();
  // Built aside and kept only whole: a scene whose skinning failed has none, not some.
  std::vector<SkinnedMesh> built(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const MeshData& mesh = scene.meshes[m];
    if (mesh.skinning == nullptr) continue;
    const std::string name = "mesh " + std::to_string(m);
    SkinningSettings settings{.vertexTargets = {scene_.skinnedVertexTarget(m)}};
    SkinnedMesh& skinned = built[m];
    for (std::size_t f = 0; f < furs_.size(); ++f) {
      if (furs_.mesh(f) != m) continue;
      skinned.furs.push_back(f);
      settings.vertexTargets.push_back(furs_.pass(f).vertexTarget());
    }
    if (m < diffusionMeshes_.size() && diffusionMeshes_[m])
      settings.vertexTargets.push_back(diffusionMeshes_[m]->vertexTarget());
    if (settings.vertexTargets.size() > SkinningPass::kMaxVertexTargets)
      return fail(name + ": a skinned mesh can grow one fur and have one texture-space skin copy at most");
    // The furs' fins and shadows are found on the CPU, from the deformed vertices.
    settings.hostReadable = !skinned.furs.empty();
    auto pass = SkinningPass::create(*device_, *mesh.skinning, settings);
    if (!pass) return fail(name + ": " + pass.error().message);
    skinned.pass = std::move(*pass);
  }
  skinned_ = std::move(built);
  return {};
}

Result<void> Renderer::updateSkinning(std::size_t mesh, std::span<const glm::mat4> jointMatrices,
                                      std::span<const float> morphWeights) {
  const std::string name = "updateSkinning: mesh " + std::to_string(mesh);
  if (mesh >= skinned_.size() || !skinned_[mesh].pass)
    return fail(name + " is not a skinned mesh of the scene (MeshData::skinning)");
  if (auto updated = skinned_[mesh].pass->update(jointMatrices, morphWeights); !updated)
    return fail(name + ": " + updated.error().message);
  skinned_[mesh].stale = true;
  return {};
}

Result<void> Renderer::poseSkinnedFurs() {
  const auto needsPose = [](const SkinnedMesh& mesh) { return mesh.pass && mesh.stale && !mesh.furs.empty(); };
  if (std::ranges::none_of(skinned_, needsPose)) return {};
  try {
    device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      for (const SkinnedMesh& mesh : skinned_)
        if (needsPose(mesh)) mesh.pass->record(commands);
    });
  } catch (const std::exception& error) {
    return fail(std::string("skinning the furred meshes failed: ") + error.what());
  }
  for (SkinnedMesh& mesh : skinned_) {
    if (!needsPose(mesh)) continue;
    mesh.stale = false;  // the frame draws what this wrote
    for (const std::size_t fur : mesh.furs)
      if (auto posed = furs_.setPose(fur, mesh.pass->mappedPositions(), mesh.pass->mappedNormals()); !posed)
        return posed;
  }
  return {};
}

void Renderer::addSkinning() {
  for (SkinnedMesh& mesh : skinned_) {
    if (!mesh.pass || !mesh.stale) continue;
    const SkinningPass* pass = mesh.pass.get();
    graph_.addPass(
        PassName::kSkinning, [pass](FrameGraph::Builder& builder) { pass->declare(builder); },
        [pass](const vk::raii::CommandBuffer& c) { pass->execute(c); });
    mesh.stale = false;
  }
}

glm::vec3 Renderer::ambientRadiance(const FrameInput& frame) const {
  if (!environment_) return frame.ambient;
  return frame.ambient + sphereAverage(environment_->irradianceOverPi());
}

void Renderer::refreshShadowDescriptors() {
  scene_.refreshShadows();
  for (TextureSpaceSkin& skin : textureSpaceSkins_) skin.pass->refreshShadows();
  for (HairGroom& groom : hair_)
    if (groom.lighting) groom.lighting->refreshShadows();
  furs_.refreshShadows();
}

Result<void> Renderer::updateHair(std::size_t groom, std::span<const glm::vec3> guidePositions) {
  if (groom >= hair_.size())
    return fail("updateHair: no groom " + std::to_string(groom) + " (the scene has " + std::to_string(hair_.size()) +
                ")");
  HairGroom& hair = hair_[groom];
  if (auto updated = hair.strands->updateGuides(guidePositions); !updated)
    return fail("groom " + std::to_string(groom) + ": " + updated.error().message);
  // The guides' bounding sphere, widened by how far the dense strands stray from them.
  auto sphere = boundingSphere(guidePositions);
  if (!sphere) return fail("groom " + std::to_string(groom) + ": " + sphere.error().message);
  sphere->radius += hair.strayFromGuides * 1.001f;
  hair.centre = sphere->centre;
  hair.bounds = {.low = guidePositions.front(), .high = guidePositions.front()};
  for (const glm::vec3& guide : guidePositions) {
    hair.bounds.low = glm::min(hair.bounds.low, guide);
    hair.bounds.high = glm::max(hair.bounds.high, guide);
  }
  hair.bounds.low -= hair.strayFromGuides;
  hair.bounds.high += hair.strayFromGuides;
  if (auto bounded = shadows_->setBounds(groom, *sphere); !bounded) return bounded;
  // Guide middles, the keys the strands are sorted by when drawn (render/hair_order.hpp).
  const std::size_t perGuide = guidePositions.size() / hair.strands->guideCount();
  hair.guideMiddles.resize(hair.strands->guideCount());
  for (std::size_t g = 0; g < hair.guideMiddles.size(); ++g)
    hair.guideMiddles[g] = guidePositions[g * perGuide + perGuide / 2];
  if (!hair.hasGuides) {
    hair.hasGuides = true;
    refreshShadowDescriptors();  // the groom's slot now binds its map
  }
  return {};
}

void Renderer::record(const vk::raii::CommandBuffer& commands, const FrameInput& frame) {
  using Builder = FrameGraph::Builder;
  using Commands = vk::raii::CommandBuffer;
  graph_.reset();
  FramePlan& plan = plan_;

  // Skinned meshes first: every pass after this draws their deformed vertices.
  addSkinning();

  // Dense strands first (compute), then their shadow maps and their shading, so the surfaces
  // and the ribbons can read them inside the main pass.
  bool hair = false;
  for (const HairGroom& groom : hair_) {
    if (!groom.hasGuides) continue;
    const StrandInterpolationPass* strands = groom.strands.get();
    graph_.addPass(
        PassName::kStrands, [&](Builder& pass) { strands->declare(pass); },
        [strands](const Commands& c) { strands->execute(c); });
    hair = true;
  }
  if (hairDensity_) addHairDensity();
  // The first light casts the hair and fur shadows; without lights nothing is lit, any direction does.
  const bool fur = std::ranges::any_of(frame.instances, [&](const MeshInstance& i) { return furs_.draws(i, frame); });
  if ((hair || fur) && shadows_->mapCount() > 0) {
    shadows_->prepare(frame.lights.empty() ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::normalize(frame.lights[0].direction));
    graph_.addPass(
        PassName::kHairShadows, [this](Builder& pass) { shadows_->declare(pass); },
        [this](const Commands& c) { shadows_->execute(c); });
  }
  furs_.setShadowUniforms(shadows_->uniforms());
  // A groom is shaded where its lighting took, and drawn where its view and order took as well.
  plan.shaded.assign(hair_.size(), false);
  plan.drawn.assign(hair_.size(), false);
  if (hair) {
    const glm::mat4 viewProjection = frame.camera.projection(target_.aspect()) * frame.camera.view();
    const glm::vec4 eye = hairEye(viewProjection);
    for (std::size_t g = 0; g < hair_.size(); ++g) {
      const HairGroom& groom = hair_[g];
      plan.shaded[g] =
          groom.hasGuides &&
          groom.lighting->update(viewProjection, frame.lights, frame.ambient, shadows_->uniforms()).has_value();
      const float strandPixels =
          groom.settings.width *
          pixelsPerMetreAt(viewProjection, glm::vec2(target_.extent().width, target_.extent().height), groom.centre);
      const float keptShare = keptStrandShare(strandPixels, groom.settings.lodPixelWidth);
      plan.drawn[g] = plan.shaded[g] && groom.ribbons->update(frame, target_.extent(), groom.settings, keptShare) &&
                      groom.ribbons->setDrawOrder(groom.order->backToFront(groom.guideMiddles, eye));
    }
  }
  // Before the skin diffusion, which reads it too.
  if (frame.surfaceShadows) {
    surfaceShadows_.prepare(frame, scene_);
    if (surfaceShadows_.drawsAnything())
      graph_.addPass(
          PassName::kSurfaceShadows, [this](Builder& pass) { surfaceShadows_.declare(pass); },
          [this](const Commands& c) { surfaceShadows_.record(c); });
  }
  const bool surfaceShadows = frame.surfaceShadows && surfaceShadows_.drawsAnything();
  if (!textureSpaceSkins_.empty()) {
    // Skin lit in UV space (light 0 through the hair's and the surfaces' shadows) and blurred,
    // before the surfaces sample it.
    bool diffused = false;
    for (const TextureSpaceSkin& skin : textureSpaceSkins_) {
      const MeshInstance* instance = diffusionInstance(skin, frame);
      if (!instance) continue;
      graph_.addPass(
          PassName::kSkinDiffusion,
          [&](Builder& pass) {
            skin.pass->declare(pass);
            if (surfaceShadows) surfaceShadows_.declareReads(pass, vk::PipelineStageFlagBits2::eFragmentShader);
          },
          [this, &frame, &skin, instance, surfaceShadows](const Commands& c) {
            skin.pass->record(c, *diffusionMeshes_[instance->mesh],
                              {.model = instance->model,
                               .lights = frame.lights,
                               .ambient = ambientRadiance(frame),
                               .surfaceShadows = surfaceShadows});
          });
      diffused = true;
    }
    if (!diffused) addEmptyPass(PassName::kSkinDiffusion);
  }
  if (translucency_.drawsTranslucency(frame, scene_)) {
    translucency_.prepareLightDepth(frame, scene_);
    graph_.addPass(
        PassName::kTranslucencyDepth, [this](Builder& pass) { translucency_.declareLightDepth(pass); },
        [this](const Commands& c) { translucency_.recordLightDepth(c); });
  }
  scene_.update(frame, target_.aspect());
  if (ocean_) {
    graph_.addPass(
        PassName::kOcean, [this](Builder& pass) { ocean_->declareGrid(pass); },
        [this](const Commands& c) { ocean_->recordGrid(c); });
    graph_.addPass(
        PassName::kOcean, [this](Builder& pass) { ocean_->declareFoam(pass); },
        [this](const Commands& c) { ocean_->recordFoam(c); });
  }

  // The skin's G-buffer and depth first where it is deferred
  // (render/passes/deferred_skin_pass.hpp); the main pass lights it before anything else. With
  // hair, the strands are then hidden behind the skin's depth alone, chosen and shaded before the
  // main pass, which draws them last: one pass, in which a timestamp after the surfaces makes
  // lavapipe rasterize them on its raster threads while this thread bins the hair's lines
  // (GpuTimer::handOff): the two overlap instead of running one after the other
  // (docs/lavapipe.md#raster-threads-and-binning). Without the G-buffer, the main pass stops after
  // the surfaces and furs, whose depth then hides the strands (render/passes/hair_pass.hpp, "Hidden
  // strands").
  plan.skinDeferred = deferredSkin_.defersSkin(frame);
  plan.hairBeforeMainPass = hair && plan.skinDeferred;
  plan.scene = hair && !plan.hairBeforeMainPass ? RenderTarget::ScenePart::kOpaque : RenderTarget::ScenePart::kWhole;
  plan.background = glm::vec4(frame.background, 1.0f);
  if (plan.skinDeferred)
    graph_.addPass(
        plan.hairBeforeMainPass ? PassName::kSkinGBuffer : PassName::kSurfaces,
        [this](Builder& pass) { target_.declareSkinGBuffer(pass); },
        [this, &frame](const Commands& c) {
          target_.beginSkinGBuffer(c);
          deferredSkin_.drawGBuffer(c, frame);
          c.endRendering();
        });
  if (plan.hairBeforeMainPass) addHairLighting();
  // Main pass: previous contents are discarded and cleared (but the deferred skin's depth).
  graph_.addPass(
      plan.hairBeforeMainPass ? PassName::kMainPass : PassName::kSurfaces,
      [&](Builder& pass) {
        target_.declareScene(pass, plan.scene, plan.skinDeferred);
        declareSurfaceReads(pass, frame);
        if (plan.hairBeforeMainPass) declareHairDraws(pass);
      },
      [this, &frame](const Commands& c) {
        const FramePlan& plan = plan_;
        target_.beginScenePart(c, plan.scene, plan.background, plan.skinDeferred);
        if (plan.skinDeferred) deferredSkin_.drawLighting(c, frame);
        // Nearest first, so that lavapipe's early depth test skips the blocks they hide: the
        // opaque surfaces, the sea, then the sky behind them all and the light discs in it.
        surfaces_.draw(c, frame, plan.skinDeferred);
        furs_.draw(c);
        if (ocean_) ocean_->draw(c, scene_.frameSet(), target_.extent());
        if (environment_) environment_->draw(c, frame.camera, target_.extent());
        discs_.draw(c, frame.camera, frame.lights, target_.extent());
        if (effects_) effects_->draw(c, scene_.frameSet(), target_.extent());
        if (plan.hairBeforeMainPass) {
          timer_.handOff(c);
          drawHair(c);
        }
        c.endRendering();
      });
  if (hair && !plan.hairBeforeMainPass) {
    addHairLighting();
    graph_.addPass(
        PassName::kHair,
        [this](Builder& pass) {
          target_.declareScene(pass, RenderTarget::ScenePart::kRest);
          declareHairDraws(pass);
        },
        [this](const Commands& c) {
          target_.beginScenePart(c, RenderTarget::ScenePart::kRest, glm::vec4(0.0f));
          drawHair(c);
          c.endRendering();
        });
  }

  if (!frame.lenses.empty()) {
    // Over everything the frame holds by now, which they refract.
    glasses_->prepare(frame, target_.aspect());
    graph_.addPass(
        PassName::kGlasses, [this](Builder& pass) { glasses_->declareCopy(pass); },
        [this](const Commands& c) { glasses_->recordCopy(c); });
    graph_.addPass(
        PassName::kGlasses, [this](Builder& pass) { glasses_->declareDraw(pass); },
        [this, &frame](const Commands& c) { glasses_->recordDraw(c, frame.lenses); });
  }

  addPost(frame);
  graph_.addPass(
      PassName::kOutput, [&](Builder& pass) { output_.declare(pass, target_, frame.post); },
      [this, &frame](const Commands& c) { output_.record(c, target_, frame.exposure, frame.post); });
  graph_.leaveAs(target_.output(), ResourceUse::transferSource());
  graph_.leaveAs(target_.hdr(), ResourceUse::transferSource());
  if (ocean_) ocean_->leaveFoam(graph_);
  for (std::size_t g = 0; g < hair_.size(); ++g)
    if (plan.drawn[g]) hair_[g].ribbons->leaveChoiceReadable(graph_);  // hairChoices reads it

  graph_.compile();
  timer_.reset(commands);
  graph_.execute(commands, &timer_);
}

const MeshInstance* Renderer::diffusionInstance(const TextureSpaceSkin& skin, const FrameInput& frame) const {
  for (const MeshInstance& instance : frame.instances)
    if (instance.material == skin.material && instance.mesh < diffusionMeshes_.size() &&
        diffusionMeshes_[instance.mesh])
      return &instance;
  return nullptr;
}

void Renderer::addEmptyPass(PassName name) {
  graph_.addPass(
      name, [](FrameGraph::Builder&) {}, [](const vk::raii::CommandBuffer&) {});
}

void Renderer::addHairLighting() {
  using Builder = FrameGraph::Builder;
  using Commands = vk::raii::CommandBuffer;
  // The hair's hiding (HairOcclusionPass), choice and shading, outside any rendering scope.
  bool any = false;
  if (hideOccludedHair_) {
    graph_.addPass(
        PassName::kHairLighting, [this](Builder& pass) { occlusion_.declare(pass); },
        [this](const Commands& c) { occlusion_.execute(c); });
    any = true;
  }
  for (std::size_t g = 0; g < hair_.size(); ++g) {
    if (plan_.drawn[g]) {  // first: it marks the vertices not to shade
      const HairPass* ribbons = hair_[g].ribbons.get();
      graph_.addPass(
          PassName::kHairLighting, [ribbons](Builder& pass) { ribbons->declare(pass); },
          [ribbons](const Commands& c) { ribbons->execute(c); });
      any = true;
    }
    if (plan_.shaded[g]) {
      const HairLightingPass* lighting = hair_[g].lighting.get();
      graph_.addPass(
          PassName::kHairLighting, [lighting](Builder& pass) { lighting->declare(pass); },
          [lighting](const Commands& c) { lighting->execute(c); });
      any = true;
    }
  }
  if (!any) addEmptyPass(PassName::kHairLighting);
}

void Renderer::addHairDensity() {
  using Builder = FrameGraph::Builder;
  using Commands = vk::raii::CommandBuffer;
  std::vector<HairBounds> bounds;
  for (const HairGroom& groom : hair_) bounds.push_back(groom.hasGuides ? groom.bounds : HairBounds{});
  hairDensity_->place(bounds);
  if (hairDensity_->placement().scale.w == 0.0f) return;  // no groom placed: nothing hidden
  const HairDensityPass* density = hairDensity_.get();
  graph_.addPass(
      PassName::kHairDensity, [density](Builder& pass) { density->declareClear(pass); },
      [density](const Commands& c) { density->executeClear(c); });
  graph_.addPass(
      PassName::kHairDensity, [density](Builder& pass) { density->declareSplat(pass); },
      [density](const Commands& c) { density->executeSplat(c); });
  graph_.addPass(
      PassName::kHairDensity, [density](Builder& pass) { density->declareVisibility(pass); },
      [density](const Commands& c) { density->executeVisibility(c); });
}

void Renderer::declareSurfaceReads(FrameGraph::Builder& pass, const FrameInput& frame) const {
  if (ocean_) ocean_->declareDrawReads(pass);
  if (hairDensity_) hairDensity_->declareReads(pass, vk::PipelineStageFlagBits2::eFragmentShader);
  shadows_->declareReads(pass, vk::PipelineStageFlagBits2::eFragmentShader);  // the surfaces' and the furs'
  if (translucency_.drawsTranslucency(frame, scene_)) translucency_.declareReads(pass);
  if (frame.surfaceShadows && surfaceShadows_.drawsAnything())
    surfaceShadows_.declareReads(pass, vk::PipelineStageFlagBits2::eFragmentShader);
  for (const TextureSpaceSkin& skin : textureSpaceSkins_)
    if (diffusionInstance(skin, frame)) skin.pass->declareReads(pass, vk::PipelineStageFlagBits2::eFragmentShader);
}

void Renderer::declareHairDraws(FrameGraph::Builder& pass) const {
  for (std::size_t g = 0; g < hair_.size(); ++g)
    if (plan_.drawn[g]) hair_[g].ribbons->declareDraw(pass);
}

void Renderer::drawHair(const vk::raii::CommandBuffer& commands) const {
  for (std::size_t g = 0; g < hair_.size(); ++g)
    if (plan_.drawn[g]) hair_[g].ribbons->draw(commands);
}

std::vector<HairPrimitiveChoice> Renderer::hairChoices() const {
  std::vector<HairPrimitiveChoice> choices;
  for (const HairGroom& groom : hair_)
    choices.push_back(groom.ribbons ? groom.ribbons->lastChoice() : HairPrimitiveChoice{});
  return choices;
}

void Renderer::addPost(const FrameInput& frame) {
  using Builder = FrameGraph::Builder;
  using Commands = vk::raii::CommandBuffer;
  if (!PostPass::runs(frame.post)) return;  // the default: the output pass alone
  const auto nothing = [](Builder&) {};
  graph_.addPass(
      PassName::kPostDownsample, [this](Builder& pass) { post_.declareDownsample(pass); },
      [this](const Commands& c) { post_.recordDownsample(c); });
  if (frame.post.autoGain)
    graph_.addPass(PassName::kAutoGain, nothing,
                   [this, &frame](const Commands& c) { post_.recordAutoGain(c, frame.post, frame.exposure); });
  if (frame.post.glowStrength > 0.0f)
    graph_.addPass(PassName::kGlow, nothing, [this](const Commands& c) { post_.recordGlow(c); });
  // God rays stream from their light's screen position; none when it is off screen or behind.
  const std::size_t rayLight = frame.post.godRayLight;
  plan_.rayLight = frame.post.godRays > 0.0f && rayLight < frame.lights.size()
                       ? godRayLightUv(frame.camera, frame.lights[rayLight].direction, target_.aspect())
                       : std::nullopt;
  if (plan_.rayLight)
    graph_.addPass(PassName::kGodRays, nothing,
                   [this, &frame](const Commands& c) { post_.recordGodRays(c, frame.post, *plan_.rayLight); });
  graph_.addPass(
      PassName::kPostOverlay, [this](Builder& pass) { post_.declareHandOff(pass); },
      [this, &frame](const Commands& c) { post_.recordHandOff(c, frame.post, frame.exposure); });
}

Result<void> Renderer::updateFurLeans(std::size_t fur, std::span<const glm::vec3> leans) {
  return furs_.setLeans(fur, leans);
}

Result<void> Renderer::updateMesh(std::size_t mesh, std::span<const glm::vec3> positions,
                                  std::span<const glm::vec3> normals) {
  if (!scene_.isDynamic(mesh)) return fail("mesh " + std::to_string(mesh) + " is not a dynamic mesh of the scene");
  const std::size_t count = scene_.vertexCount(mesh);
  if (positions.size() != count || (!normals.empty() && normals.size() != count))
    return fail("mesh " + std::to_string(mesh) + " has " + std::to_string(count) + " vertices; got " +
                std::to_string(positions.size()) + " positions and " + std::to_string(normals.size()) + " normals");
  scene_.updateVertices(mesh, positions, normals);
  return {};
}

Result<void> Renderer::replaceMesh(std::size_t mesh, const MeshData& data) {
  const std::string name = "mesh " + std::to_string(mesh);
  if (!scene_.hasMesh(mesh)) return fail("replaceMesh: the scene has no " + name);
  if (scene_.isDynamic(mesh))
    return fail("replaceMesh: " + name + " is dynamic: its vertices change with updateMesh, its triangles stay");
  if (scene_.isSkinned(mesh) || data.skinning != nullptr)
    return fail("replaceMesh: " + name + " or its replacement is skinned; skinned meshes come with setScene only");
  if (data.dynamic) return fail("replaceMesh: the new " + name + " is marked dynamic; only static meshes are replaced");
  if (auto valid = validateMesh(data, name); !valid) return valid;
  // Texture-space skin draws its irradiance over its own copy of the mesh (setTextureSpaceSkins).
  std::optional<SkinDiffusionMesh> diffusion;
  if (mesh < diffusionMeshes_.size() && !data.uvs.empty() && !data.normals.empty()) {
    auto uploaded = SkinDiffusionMesh::create(*device_, data);
    if (!uploaded) return fail(name + ": " + uploaded.error().message);
    diffusion = std::move(*uploaded);
  }
  try {
    scene_.replaceMesh(mesh, data);
    translucency_.replaceMesh(mesh, data);
  } catch (const std::exception& error) {
    return fail("replaceMesh: uploading " + name + " failed: " + error.what());
  }
  if (mesh < diffusionMeshes_.size()) diffusionMeshes_[mesh] = std::move(diffusion);
  return {};
}

Result<std::vector<PassTiming>> Renderer::render(const FrameInput& frame) {
  for (std::size_t i = 0; i < frame.lights.size(); ++i) {
    const float length = glm::length(frame.lights[i].direction);
    if (!(std::isfinite(length) && length > 0.0f))
      return fail("light " + std::to_string(i) + "'s direction is not finite and non-zero");
  }
  for (std::size_t i = 0; i < frame.instances.size(); ++i) {
    const MeshInstance& instance = frame.instances[i];
    if (!scene_.canDraw(instance))
      return fail("instance " + std::to_string(i) + " names mesh " + std::to_string(instance.mesh) + " and material " +
                  std::to_string(instance.material) + ", which the scene does not have");
    for (const TextureSpaceSkin& skin : textureSpaceSkins_)
      if (instance.material == skin.material && !diffusionMeshes_[instance.mesh])
        return fail("instance " + std::to_string(i) + ": texture-space skin needs a static mesh with uvs and normals");
    if (frame.furShells && scene_.isFur(instance) && !furs_.draws(instance, frame))
      return fail("instance " + std::to_string(i) + " draws mesh " + std::to_string(instance.mesh) +
                  " with a fur material, but the scene grows no fur (StaticScene::furs) on that pair");
  }
  if (auto valid = validate(frame.post); !valid) return std::unexpected(valid.error());
  for (std::size_t i = 0; i < frame.lenses.size(); ++i) {
    if (auto valid = validateLens(frame.lenses[i]); !valid)
      return fail("lens " + std::to_string(i) + ": " + valid.error().message);
  }
  if (!frame.lenses.empty() && !glasses_) {
    try {
      glasses_ = std::make_unique<GlassesPass>(*device_, scene_, target_);
    } catch (const std::exception& error) {
      return fail(std::string("creating the glasses pass failed: ") + error.what());
    }
  }
  if (frame.post.godRays > 0.0f && frame.post.godRayLight > 0 && frame.post.godRayLight >= frame.lights.size())
    return fail("the god rays stream from light " + std::to_string(frame.post.godRayLight) + ", but the frame has " +
                std::to_string(frame.lights.size()) + " lights");
  for (std::size_t i = 0; i < frame.lights.size(); ++i) {
    if (!(frame.lights[i].discRadius >= 0.0f && frame.lights[i].discRadius < 0.5f * std::numbers::pi_v<float>))
      return fail("light " + std::to_string(i) + "'s disc radius is not in [0, π/2) radians");
    if (!(frame.lights[i].discRadiance >= 0.0f && std::isfinite(frame.lights[i].discRadiance)))
      return fail("light " + std::to_string(i) + "'s disc radiance is not a finite number >= 0");
  }
  if (auto prepared = translucency_.prepareThickness(frame, scene_); !prepared)
    return std::unexpected(prepared.error());
  if (ocean_) {
    if (auto prepared = ocean_->prepare(frame, target_.aspect()); !prepared) return std::unexpected(prepared.error());
  }
  if (!frame.effects.empty() && !effects_) {
    auto effects = EffectsPass::create(
        *device_,
        {.color = RenderTarget::kHdrFormat, .depth = RenderTarget::kDepthFormat, .samples = target_.samples()},
        scene_.frameLayout());
    if (!effects) return std::unexpected(effects.error());
    effects_ = std::move(*effects);
  }
  if (effects_) {
    if (auto prepared = effects_->prepare(frame, target_.extent().height); !prepared)
      return std::unexpected(prepared.error());
  }
  if (auto posed = poseSkinnedFurs(); !posed) return std::unexpected(posed.error());
  if (auto updated =
          furs_.update(frame, frame.ambient, environment_ ? environment_->irradianceOverPi() : SphericalHarmonics9{},
                       target_.extent(), target_.aspect());
      !updated)
    return std::unexpected(updated.error());
  // Drawn furs cast shadows from where they are now (their slots follow the grooms'); the others
  // cast none.
  for (std::size_t f = 0; f < furs_.size(); ++f) {
    if (!furs_.drawn(f)) {
      shadows_->clearBounds(hair_.size() + f);
      continue;
    }
    if (auto bounded = shadows_->setBounds(hair_.size() + f, furs_.shadowBounds(f)); !bounded)
      return std::unexpected(bounded.error());
    if (auto widened = shadows_->setStrandWidth(hair_.size() + f, furs_.shadowColumnWidth(f)); !widened)
      return std::unexpected(widened.error());
    if (!furShadowsBound_[f]) {
      furShadowsBound_[f] = true;
      refreshShadowDescriptors();  // the fur's slot now binds its map
    }
  }
  try {
    device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) { record(commands, frame); });
  } catch (const std::exception& error) {
    return fail(std::string("rendering the frame failed: ") + error.what());
  }
  return timer_.results();
}

Result<std::vector<std::uint8_t>> Renderer::readOutput() const {
  try {
    const auto bytes = readBack(*device_, target_.output(), 4);
    std::vector<std::uint8_t> rgba(bytes.size());
    std::memcpy(rgba.data(), bytes.data(), bytes.size());
    return rgba;
  } catch (const std::exception& error) {
    return fail(std::string("reading the frame back failed: ") + error.what());
  }
}

Result<std::vector<std::uint16_t>> Renderer::readHdrOutput() const {
  try {
    const auto bytes = readBack(*device_, target_.hdr(), 4 * sizeof(std::uint16_t));
    std::vector<std::uint16_t> rgba(bytes.size() / sizeof(std::uint16_t));
    std::memcpy(rgba.data(), bytes.data(), bytes.size());
    return rgba;
  } catch (const std::exception& error) {
    return fail(std::string("reading the HDR frame back failed: ") + error.what());
  }
}

}  // namespace mane::render
