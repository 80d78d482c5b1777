#pragma once
// A whole file read into memory, for the decoders that parse from memory. Private to scenes/.

#include <filesystem>
#include <vector>

#include "common/error.hpp"

namespace mane::scenes::detail {

/// The bytes of `file`. Errors: "<file>: file not found" (not a regular file), "<file>: cannot
/// open the file".
[[nodiscard]] Result<std::vector<unsigned char>> readFileBytes(const std::filesystem::path& file);

}  // namespace mane::scenes::detail
