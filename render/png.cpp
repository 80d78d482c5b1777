#include "render/png.hpp"

#include <system_error>

#include "stb_image_write.h"

namespace mane::render {

Result<void> writePng(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                      std::span<const std::uint8_t> rgba) {
  if (rgba.size() != std::size_t(width) * height * 4)
    return fail(path.string() + ": " + std::to_string(rgba.size()) + " bytes given for a " + std::to_string(width) +
                "x" + std::to_string(height) + " RGBA image");
  std::error_code error;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), error);
  if (error) return fail(path.parent_path().string() + ": cannot create the folder: " + error.message());
  if (!stbi_write_png(path.c_str(), int(width), int(height), 4, rgba.data(), int(width) * 4))
    return fail(path.string() + ": cannot write the PNG file");
  return {};
}

}  // namespace mane::render
