#pragma once
// The loaders under test take paths: each harness writes its input to one scratch file per
// process (in a fresh directory under $TMPDIR, removed at exit) and loads that.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace mane::fuzz {

class InputFile {
public:
  explicit InputFile(const std::string& fileName) {
    std::string pattern = (std::filesystem::temp_directory_path() / "mane-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) std::abort();
    directory_ = pattern;
    path_ = directory_ / fileName;
  }
  ~InputFile() {
    std::error_code ec;
    std::filesystem::remove_all(directory_, ec);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// Replaces the file's contents with `data` and returns its path.
  const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) const {
    std::ofstream stream(path_, std::ios::binary | std::ios::trunc);
    stream.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!stream) std::abort();
    return path_;
  }

private:
  std::filesystem::path directory_;
  std::filesystem::path path_;
};

}  // namespace mane::fuzz
