#pragma once
// Strand level of detail (render/passes/hair_pass.hpp, "Level of detail"): as a groom shrinks on
// screen, only a share of its dense strands is drawn, each wider, so that it keeps its coverage.
//
// The share. A groom whose strands are w pixels wide at its centre, with a level-of-detail width
// of W pixels, keeps f = w / W of its strands (all of them when w ≥ W, never fewer than
// kLeastKeptStrands): strands thinner than W are drawn as 1/f as many, as wide as W.
//
// Which strands. Strand s is kept when its rank, the bit reversal of s over 2³² (van der Corput's
// sequence), is below f. Any 2^m consecutive strands hold one of each rank interval of 2^−m, so a
// share f keeps close to f of any run of consecutive strands; dense layouts number each guide's
// strands consecutively (physics/interpolation.hpp), so the kept ones spread over the scalp.
// As f falls, strands leave one at a time and never come back before it rises again.
//
// The width. The kept strands are drawn 1 / f times as wide (shaders/hair_uniforms.glsl,
// hairRibbon), so the groom's summed width × opacity, what thin strands cover of a pixel on
// average, stays the same. Scaling the width so that each kept strand darkens a pixel as 1 / f
// thin strands at independent places would, 1 − (1 − a)^(1/f) for a thin strand's a, falls
// short: a strand near a pixel wide spreads over two pixels, each darkened less than that.
// Over 512 random strands a quarter pixel wide that cover about half of each pixel, a quarter
// of them drawn 4 times as wide covers 1.6 % more than the whole groom, the other rule 18 % less
// (tests/render/hair_pass_test.cpp).

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace mane::render {

/// The smallest share of a groom's strands drawn, however small it is on screen.
inline constexpr float kLeastKeptStrands = 1.0f / 16.0f;

/// The share of a groom's strands drawn when they are `strandPixels` wide on screen and its
/// level-of-detail width is `lodPixels` (0: every strand), in [kLeastKeptStrands, 1].
[[nodiscard]] float keptStrandShare(float strandPixels, float lodPixels);

/// Pixels per metre across the view at `point` (world metres) for `viewProjection` (any world →
/// clip matrix, Vulkan clip space) and a viewport of `viewport` pixels: how many pixels a metre
/// perpendicular to the line of sight spans there. 0 where the point is not in front of the
/// eye.
[[nodiscard]] float pixelsPerMetreAt(const glm::mat4& viewProjection, glm::vec2 viewport, glm::vec3 point);

}  // namespace mane::render
