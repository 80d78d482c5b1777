#pragma once
// The SPIR-V of every shader in shaders/, compiled by glslang at build time and linked in.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace mane::shaders {

/// The SPIR-V words of the shader whose source file is `name` (e.g. "lambert.frag"),
/// or nothing when no such shader was built.
std::optional<std::span<const std::uint32_t>> findSpirv(std::string_view name);

/// The file names of all embedded shaders, in build order.
std::vector<std::string_view> embeddedShaderNames();

}  // namespace mane::shaders
