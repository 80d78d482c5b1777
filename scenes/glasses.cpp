#include "scenes/glasses.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace mane::scenes {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr int kTubeSides = 12;
constexpr int kRimPoints = 64;
constexpr float kRimWidth = 1.4e-3f;    // metres: the rim's half width across the outline
constexpr float kRimOverlap = 0.6e-3f;  // metres: how far the rim's middle lies outside the lens's outline
constexpr float kRimCover = 0.5e-3f;    // metres: how far the rim reaches past the lens's faces
constexpr float kWireRadius = 1.1e-3f;  // metres: the bridge's and temples' section
// How far the temples slope down from the front towards the ears, which lie below the hinges.
constexpr float kTempleDropDegrees = 10.0f;

// A tube along `path` whose section is an ellipse of radii radii[i].x along across[i] and
// radii[i].y along the direction perpendicular to it and to the path; open tubes get flat caps.
void appendTube(Mesh& mesh, std::span<const glm::vec3> path, std::span<const glm::vec3> across,
                std::span<const glm::vec2> radii, bool closed) {
  const std::size_t count = path.size();
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  const auto tangentAt = [&](std::size_t i) {
    const std::size_t before = i > 0 ? i - 1 : (closed ? count - 1 : 0);
    const std::size_t after = i + 1 < count ? i + 1 : (closed ? 0 : count - 1);
    return glm::normalize(path[after] - path[before]);
  };
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3 tangent = tangentAt(i);
    const glm::vec3 a = glm::normalize(across[i] - glm::dot(across[i], tangent) * tangent);
    const glm::vec3 b = glm::cross(tangent, a);
    for (int k = 0; k < kTubeSides; ++k) {
      const float phi = 2.0f * kPi * float(k) / float(kTubeSides);
      const float c = std::cos(phi), s = std::sin(phi);
      mesh.positions.push_back(path[i] + radii[i].x * c * a + radii[i].y * s * b);
      mesh.normals.push_back(glm::normalize(c / radii[i].x * a + s / radii[i].y * b));
      mesh.uvs.emplace_back(float(i) / float(count), float(k) / float(kTubeSides));
    }
  }
  // Counter-clockwise seen from outside: (a, b, tangent) is right-handed.
  const std::size_t rings = closed ? count : count - 1;
  for (std::size_t i = 0; i < rings; ++i)
    for (int k = 0; k < kTubeSides; ++k) {
      const auto at = [&](std::size_t ring, int side) {
        return first + std::uint32_t((ring % count) * kTubeSides + std::size_t(side % kTubeSides));
      };
      mesh.indices.insert(mesh.indices.end(), {at(i, k), at(i, k + 1), at(i + 1, k + 1)});
      mesh.indices.insert(mesh.indices.end(), {at(i, k), at(i + 1, k + 1), at(i + 1, k)});
    }
  if (closed) return;
  for (const bool start : {true, false}) {
    const std::size_t ring = start ? 0 : count - 1;
    const glm::vec3 outward = start ? -tangentAt(0) : tangentAt(count - 1);
    const auto centre = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.push_back(path[ring]);
    mesh.normals.push_back(outward);
    mesh.uvs.emplace_back(start ? 0.0f : 1.0f, 0.0f);
    for (int k = 0; k < kTubeSides; ++k) {  // own vertices, for the cap's flat normal
      mesh.positions.push_back(mesh.positions[first + ring * kTubeSides + std::size_t(k)]);
      mesh.normals.push_back(outward);
      mesh.uvs.emplace_back(start ? 0.0f : 1.0f, 0.0f);
    }
    for (int k = 0; k < kTubeSides; ++k) {
      const std::uint32_t here = centre + 1 + std::uint32_t(k), next = centre + 1 + std::uint32_t((k + 1) % kTubeSides);
      if (start)
        mesh.indices.insert(mesh.indices.end(), {centre, next, here});
      else
        mesh.indices.insert(mesh.indices.end(), {centre, here, next});
    }
  }
}

// The point of a lens's outline (half axes `half`, centred at x = `centreX`) at angle θ, with its
// outward unit normal in the lens's plane.
struct OutlinePoint {
  glm::vec2 position;
  glm::vec2 outward;
};
OutlinePoint outlineAt(glm::vec2 half, float centreX, float theta) {
  const glm::vec2 onEllipse(half.x * std::cos(theta), half.y * std::sin(theta));
  return {{centreX + onEllipse.x, onEllipse.y},
          glm::normalize(glm::vec2(onEllipse.x / (half.x * half.x), onEllipse.y / (half.y * half.y)))};
}

// The middle and half thickness of the lens's edge at distance r from its axis (lens frame z).
glm::vec2 edgeAt(const render::LensShape& lens, float r) {
  const float front = -render::lensSag(lens.frontCurvature, r);
  const float back = -lens.centreThickness - render::lensSag(lens.backCurvature, r);
  return {0.5f * (front + back), 0.5f * (front - back)};
}

void appendRim(Mesh& mesh, const render::LensShape& lens, float centreX) {
  std::vector<glm::vec3> path, across;
  std::vector<glm::vec2> radii;
  for (int i = 0; i < kRimPoints; ++i) {
    const OutlinePoint point = outlineAt(lens.halfAperture, 0.0f, 2.0f * kPi * float(i) / float(kRimPoints));
    const glm::vec2 edge = edgeAt(lens, glm::length(point.position));
    const glm::vec2 middle = point.position + kRimOverlap * point.outward;
    path.emplace_back(centreX + middle.x, middle.y, edge.x);
    across.emplace_back(point.outward, 0.0f);
    // Deep enough that its section, kRimOverlap inwards of its middle, still covers the edge.
    const float coverShare = std::sqrt(1.0f - (kRimOverlap / kRimWidth) * (kRimOverlap / kRimWidth));
    radii.emplace_back(kRimWidth, (edge.y + kRimCover) / coverShare);
  }
  appendTube(mesh, path, across, radii, true);
}

void appendWire(Mesh& mesh, std::span<const glm::vec3> path, glm::vec3 up) {
  const std::vector<glm::vec3> across(path.size(), up);
  const std::vector<glm::vec2> radii(path.size(), glm::vec2(kWireRadius));
  appendTube(mesh, path, across, radii, false);
}

}  // namespace

Result<GlassesModel> buildGlasses(const Glasses& glasses) {
  auto shape = render::spectacleLens(glasses.powerDioptres, 0.5f * glm::vec2(glasses.lensWidth, glasses.lensHeight),
                                     glasses.ior);
  if (!shape) return fail("glasses '" + glasses.name + "': " + shape.error().message);
  shape->transmittance = glasses.tint;
  const render::LensShape& lens = *shape;
  const float centreX = 0.5f * (glasses.bridge + glasses.lensWidth);
  GlassesModel model;
  model.frame.name = glasses.name;
  for (const float side : {-1.0f, 1.0f}) {
    model.lenses[side < 0.0f ? 0 : 1] = {lens, glm::translate(glm::mat4(1.0f), glm::vec3(side * centreX, 0.0f, 0.0f))};
    appendRim(model.frame, lens, side * centreX);
  }
  // The bridge: an arch between the rims' upper inner sides, 3 mm high.
  {
    const OutlinePoint inner = outlineAt(lens.halfAperture, centreX, kPi - 0.5f);
    const glm::vec2 edge = edgeAt(lens, glm::length(inner.position - glm::vec2(centreX, 0.0f)));
    const float x = inner.position.x + inner.outward.x * kRimOverlap;  // the rim's middle
    std::vector<glm::vec3> arch;
    for (int i = 0; i <= 12; ++i) {
      const float s = float(i) / 12.0f * 2.0f - 1.0f;
      arch.emplace_back(s * x, inner.position.y + 3e-3f * (1.0f - s * s), edge.x + 1e-3f * (1.0f - s * s));
    }
    appendWire(model.frame, arch, {0.0f, 0.0f, 1.0f});
  }
  // The temples: from a hinge on each rim's outer side, back, down and out to half the temple
  // width, then down over the ear.
  if (glasses.templeLength > 0.0f) {
    const OutlinePoint outer = outlineAt(lens.halfAperture, centreX, 0.35f);
    const glm::vec2 edge = edgeAt(lens, glm::length(outer.position - glm::vec2(centreX, 0.0f)));
    const glm::vec2 hinge = outer.position + outer.outward * (kRimOverlap + kRimWidth);
    const float frameHalfWidth = hinge.x + kWireRadius;
    const float endHalfWidth = glasses.templeWidth > 0.0f ? 0.5f * glasses.templeWidth : frameHalfWidth + 0.005f;
    const float length = glasses.templeLength;
    const float drop = length * std::tan(kTempleDropDegrees * kPi / 180.0f);
    for (const float side : {-1.0f, 1.0f}) {
      std::vector<glm::vec3> temple;
      const float z0 = edge.x - 2e-3f;  // behind the rim
      temple.emplace_back(side * hinge.x, hinge.y, edge.x);
      for (int i = 0; i <= 10; ++i) {
        const float s = float(i) / 10.0f;
        temple.emplace_back(side * (hinge.x + (endHalfWidth - hinge.x) * s), hinge.y - s * drop, z0 - s * length);
      }
      // Over the ear: a quarter turn of radius 1.5 cm towards −y.
      for (int i = 1; i <= 6; ++i) {
        const float a = 0.5f * kPi * float(i) / 6.0f;
        temple.emplace_back(side * endHalfWidth, hinge.y - drop - 0.015f * (1.0f - std::cos(a)),
                            z0 - length - 0.015f * std::sin(a));
      }
      appendWire(model.frame, temple, {0.0f, 1.0f, 0.0f});
    }
  }
  return model;
}

}  // namespace mane::scenes
