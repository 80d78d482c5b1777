// The implementations of the header-only parsers the loaders call, built here with coverage
// and sanitizers (the normal build links Debian's libtinygltf, libtinyobjloader and libstb).
// Same headers, same versions: what the fuzzer finds in them is what the normal build runs.

#define STB_IMAGE_IMPLEMENTATION
#include "stb_image.h"
#define STB_IMAGE_WRITE_IMPLEMENTATION  // tinygltf's default image writer needs it to link
#include "stb_image_write.h"

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE  // both included above, with their implementations
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
