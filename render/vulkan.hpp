#pragma once
// The one place mane includes Vulkan-Hpp. Its RAII layer (vk::raii) owns every Vulkan object
// we create, so no handle is ever destroyed by hand. Exceptions from Vulkan-Hpp stay inside
// render/: public entry points catch them and return mane::Error.

#define VULKAN_HPP_NO_CONSTRUCTORS  // designated initialisers for Vulkan structs
#include <vulkan/vulkan_raii.hpp>
