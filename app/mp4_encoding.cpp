#include "app/mp4_encoding.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern char** environ;

namespace mane::app {

std::optional<std::filesystem::path> findOnPath(std::string_view program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr || program.empty()) return std::nullopt;
  const std::string_view directories(path);
  for (std::size_t begin = 0; begin <= directories.size();) {
    std::size_t end = directories.find(':', begin);
    if (end == std::string_view::npos) end = directories.size();
    // An empty entry means the current directory (POSIX).
    const std::filesystem::path directory =
        end == begin ? std::filesystem::path(".") : std::filesystem::path(directories.substr(begin, end - begin));
    const std::filesystem::path candidate = directory / program;
    std::error_code error;
    if (std::filesystem::is_regular_file(candidate, error) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    begin = end + 1;
  }
  return std::nullopt;
}

Result<void> encodeMp4(const std::filesystem::path& ffmpeg, const std::filesystem::path& framePattern, int frames,
                       double fps, const std::filesystem::path& mp4) {
  char rate[32];
  std::snprintf(rate, sizeof(rate), "%.6g", fps);
  // -frames:v: a folder that holds a longer earlier sequence must not add its extra frames.
  std::vector<std::string> arguments{ffmpeg.string(),
                                     "-nostdin",
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-framerate",
                                     rate,
                                     "-start_number",
                                     "0",
                                     "-i",
                                     framePattern.string(),
                                     "-frames:v",
                                     std::to_string(frames),
                                     "-vf",
                                     "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                     "-c:v",
                                     "libx264",
                                     "-pix_fmt",
                                     "yuv420p",
                                     "-movflags",
                                     "+faststart",
                                     mp4.string()};
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);

  pid_t child = 0;
  if (const int error = ::posix_spawn(&child, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ); error != 0)
    return fail("cannot run " + ffmpeg.string() + ": " + std::strerror(error));
  int status = 0;
  while (::waitpid(child, &status, 0) < 0)
    if (errno != EINTR) return fail("waiting for " + ffmpeg.string() + " failed: " + std::strerror(errno));
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  const std::string how = WIFEXITED(status) ? "exited with status " + std::to_string(WEXITSTATUS(status))
                                            : "was stopped by signal " + std::to_string(WTERMSIG(status));
  return fail("ffmpeg " + how + " while encoding " + framePattern.string() + " into " + mp4.string());
}

}  // namespace mane::app
