#pragma once
// One HTTP(S) or file:// download with libcurl. Private to scenes/.

#include <filesystem>
#include <string>

#include "common/error.hpp"

namespace mane::scenes::detail {

/// Limits that keep an offline machine from hanging: the connection (DNS + TCP + TLS)
/// must be up within `connectTimeoutSeconds`, and the transfer is abandoned when it runs
/// slower than 1 KiB/s for `stallTimeoutSeconds` or longer than `totalTimeoutSeconds`.
struct DownloadLimits {
  long connectTimeoutSeconds = 5;
  long stallTimeoutSeconds = 10;
  long totalTimeoutSeconds = 120;
};

/// Downloads `url` to `destination` (overwritten). On failure the destination is removed
/// and the error names the URL and curl's reason (or the HTTP status).
[[nodiscard]] Result<void> downloadFile(const std::string& url, const std::filesystem::path& destination,
                                        const DownloadLimits& limits);

}  // namespace mane::scenes::detail
