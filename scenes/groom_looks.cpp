#include "scenes/groom_looks.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>

namespace mane::scenes {
namespace {

/// `value` clamped to [0, 1]; `fallback` where it is not a number at all.
float unit(float value, float fallback) {
  return std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : fallback;
}

glm::vec3 unit(const glm::vec3& colour) {
  return {unit(colour.r, 1.0f), unit(colour.g, 1.0f), unit(colour.b, 1.0f)};
}

/// The look the scene alone gives a strand: every factor 1, its colour where it gives one.
render::HairStrandLook sceneLook(const GroomRendering& rendering) {
  render::HairStrandLook look;
  if (rendering.colour) look.colour = *rendering.colour;
  return look;
}

/// A file's root width in metres as the factor of the groom's width it makes, where usable.
void applyWidth(float metres, const GroomRendering& rendering, render::HairStrandLook& look, GuideLooks& looks) {
  if (std::isfinite(metres) && metres > 0.0f && metres <= kMaxFileStrandWidth) {
    look.widthScale = metres / rendering.settings.width;
    return;
  }
  if (looks.unusableWidths++ == 0) looks.firstUnusableWidth = metres;
}

/// A `.hair` strand: thickness (file units), transparency and colour per point, from the arrays
/// or, where the file has none, the header's defaults.
render::HairStrandLook hairStrandLook(const StrandSet& file, std::size_t s, const GroomRendering& rendering,
                                      float metresPerUnit, GuideLooks& looks) {
  const StrandSet::HairDefaults& defaults = *file.hairDefaults;
  render::HairStrandLook look = sceneLook(rendering);
  const float root = file.thickness.empty() ? defaults.thickness : file.thickness[s].front();
  const float tip = file.thickness.empty() ? defaults.thickness : file.thickness[s].back();
  // 0 or less: no width given (NaN is not, and goes on to be unusable).
  if (!(root <= 0.0f)) {
    if (!rendering.given.width) applyWidth(root * metresPerUnit, rendering, look, looks);
    if (!rendering.given.tipWidthScale && std::isfinite(root)) look.tipWidthScale = unit(tip / root, 1.0f);
  }
  if (!rendering.given.opacity) {
    if (file.transparency.empty()) {
      look.opacityScale = unit(1.0f - defaults.transparency, 1.0f);
    } else {
      double sum = 0.0;
      for (float transparency : file.transparency[s]) sum += unit(1.0f - transparency, 1.0f);
      look.opacityScale = static_cast<float>(sum / static_cast<double>(file.transparency[s].size()));
    }
  }
  if (!rendering.colour) {
    if (file.colours.empty()) {
      look.colour = unit(defaults.colour);
    } else {
      glm::dvec3 sum(0.0);
      for (const glm::vec3& colour : file.colours[s]) sum += glm::dvec3(unit(colour));
      look.colour = glm::vec3(sum / static_cast<double>(file.colours[s].size()));
    }
  }
  return look;
}

bool plain(const render::HairStrandLook& look) {
  return look.widthScale == 1.0f && look.tipWidthScale == 1.0f && look.opacityScale == 1.0f &&
         look.colour == glm::vec3(1.0f);
}

}  // namespace

std::string GuideLooks::note() const {
  if (unusableWidths == 0) return {};
  char width[32];
  std::snprintf(width, sizeof width, "%g", static_cast<double>(firstUnusableWidth));
  return std::to_string(unusableWidths) + (unusableWidths == 1 ? " strand" : " strands") +
         " of its files give a width (first: " + width +
         " m) that is not a strand width in (0, 0.01] m (the file's units?): drawn at the groom's width instead "
         "(\"width\" in its \"render\" block sets that width for every strand)";
}

void appendFileLooks(const StrandSet& file, const GroomRendering& rendering, float metresPerUnit, GuideLooks& looks) {
  for (std::size_t s = 0; s < file.strands.size(); ++s) {
    if (file.hairDefaults) {
      looks.guides.push_back(hairStrandLook(file, s, rendering, metresPerUnit, looks));
      continue;
    }
    render::HairStrandLook look = sceneLook(rendering);
    // TressFX: a factor of the groom's width; 0 or less gives none.
    if (!rendering.given.width && !file.strandThickness.empty() && !(file.strandThickness[s] <= 0.0f))
      applyWidth(file.strandThickness[s] * rendering.settings.width, rendering, look, looks);
    looks.guides.push_back(look);
  }
}

void appendSceneLooks(std::size_t count, const GroomRendering& rendering, GuideLooks& looks) {
  looks.guides.insert(looks.guides.end(), count, sceneLook(rendering));
}

std::vector<render::HairStrandLook> denseStrandLooks(const DenseStrandLayout& layout,
                                                     std::span<const render::HairStrandLook> guideLooks) {
  assert(guideLooks.size() == layout.guideCount && "one look per guide of the layout");
  if (std::all_of(guideLooks.begin(), guideLooks.end(), plain)) return {};
  std::vector<render::HairStrandLook> looks(layout.strands.size());
  for (std::size_t d = 0; d < layout.strands.size(); ++d) {
    const DenseStrand& strand = layout.strands[d];
    if (strand.guideCount == 1) {
      looks[d] = guideLooks[strand.guides[0]];
      continue;
    }
    render::HairStrandLook& look = looks[d];
    look.widthScale = look.tipWidthScale = look.opacityScale = 0.0f;
    look.colour = glm::vec3(0.0f);
    for (std::uint32_t k = 0; k < strand.guideCount; ++k) {
      const render::HairStrandLook& guide = guideLooks[strand.guides[k]];
      const float w = strand.weights[k];
      look.widthScale += w * guide.widthScale;
      look.tipWidthScale += w * guide.tipWidthScale;
      look.opacityScale += w * guide.opacityScale;
      look.colour += w * guide.colour;
    }
    // The weights sum to 1 within 1e-5: keep the blend inside the ranges the renderer checks.
    look.tipWidthScale = unit(look.tipWidthScale, 1.0f);
    look.opacityScale = unit(look.opacityScale, 1.0f);
    look.colour = unit(look.colour);
  }
  return looks;
}

}  // namespace mane::scenes
