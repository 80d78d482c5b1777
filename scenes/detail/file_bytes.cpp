#include "scenes/detail/file_bytes.hpp"

#include <fstream>
#include <iterator>
#include <string>

namespace mane::scenes::detail {

Result<std::vector<unsigned char>> readFileBytes(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return fail(name + ": file not found");
  std::ifstream in(file, std::ios::binary);
  if (!in) return fail(name + ": cannot open the file");
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace mane::scenes::detail
