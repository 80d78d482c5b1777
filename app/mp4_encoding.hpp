#pragma once
// `mane render --mp4`: the PNG frames of a sequence encoded as H.264 in an MP4 file by ffmpeg,
// which is an optional, run-time dependency (Debian: `sudo apt-get install ffmpeg`).

#include <filesystem>
#include <optional>
#include <string_view>

#include "common/error.hpp"

namespace mane::app {

/// The first executable regular file named `program` in a directory of $PATH, or none.
std::optional<std::filesystem::path> findOnPath(std::string_view program);

/// Frames `framePattern` (a printf pattern such as out/nalu_%04d.png) numbered 0 to frames − 1,
/// shown at `fps` frames per second, encoded with `ffmpeg` into `mp4` (replaced if it exists):
/// H.264, yuv420p (what players accept), odd sizes padded by a black row or column. ffmpeg's own
/// errors go to stderr; the error returned names its exit status.
Result<void> encodeMp4(const std::filesystem::path& ffmpeg, const std::filesystem::path& framePattern, int frames,
                       double fps, const std::filesystem::path& mp4);

}  // namespace mane::app
