#pragma once
// SHA-256 of a file, for the asset manifest's integrity check. Private to scenes/.

#include <filesystem>
#include <string>

#include "common/error.hpp"

namespace mane::scenes::detail {

/// Lower-case hex SHA-256 of the file's bytes (OpenSSL EVP). Errors name the file.
[[nodiscard]] Result<std::string> sha256OfFile(const std::filesystem::path& file);

}  // namespace mane::scenes::detail
