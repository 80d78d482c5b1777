#include "scenes/image.hpp"

#include <memory>
#include <string>

#include "stb_image.h"

namespace mane::scenes {

Result<Image> loadImage(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return fail(name + ": file not found");
  int width = 0;
  int height = 0;
  int channelsInFile = 0;
  // stbi_load is reentrant apart from its failure-reason string, which is per thread only
  // with STBI_THREAD_LOCAL; good enough for a message.
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load(name.c_str(), &width, &height, &channelsInFile, 4), &stbi_image_free);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    return fail(name + ": cannot decode image: " + (reason ? reason : "unknown error"));
  }
  Image image;
  image.width = width;
  image.height = height;
  const std::size_t size = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
  image.rgba.assign(pixels.get(), pixels.get() + size);
  return image;
}

}  // namespace mane::scenes
