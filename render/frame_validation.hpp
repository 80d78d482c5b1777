#pragma once
// The contracts of the plain data the renderer is given (render/frame.hpp), checked before
// anything reaches the GPU. Errors name the mesh, material or texture and say what was expected.

#include <string>

#include "common/error.hpp"
#include "render/frame.hpp"
#include "render/vulkan.hpp"

namespace mane::render {

/// MeshData's contract: as many normals, uvs and curvatures as positions (or none), whole
/// triangles, indices in range. `name` says which mesh.
[[nodiscard]] Result<void> validateMesh(const MeshData& mesh, const std::string& name);

/// Every mesh's contract, and every texture's: RGBA8 texels that fill its size, which the
/// device's limits allow.
[[nodiscard]] Result<void> validateScene(const StaticScene& scene, const vk::PhysicalDeviceLimits& limits);

}  // namespace mane::render
