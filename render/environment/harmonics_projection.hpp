#pragma once
// The environment's radiance projected on nine spherical harmonics on the GPU, in a compute pass
// (shaders/environment_harmonics.comp): the same sum as projectRadiance
// (render/environment/spherical_harmonics.hpp), its CPU reference, over the fp16 cube the
// renderer draws and reflects, each texel's solid angle integrated by 2 × 2-point Gauss–Legendre
// quadrature.

#include "common/error.hpp"
#include "render/device.hpp"
#include "render/environment/spherical_harmonics.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// Σ radiance × Y × solid angle over level 0 of `cube` (six layers, SHADER_READ_ONLY, left so),
/// summed per row on the GPU and over the rows on the CPU in a fixed order; waits for the GPU.
/// Errors: a Vulkan failure.
[[nodiscard]] Result<SphericalHarmonics9> projectRadianceOnGpu(const Device& device, const Image& cube);

}  // namespace mane::render
