#include "scenes/detail/sha256.hpp"

#include <array>
#include <fstream>
#include <memory>

#include <openssl/evp.h>

namespace mane::scenes::detail {

Result<std::string> sha256OfFile(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) return fail(file.string() + ": cannot open the file to check its sha256");
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> context(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1) {
    return fail(file.string() + ": OpenSSL could not start a sha256 digest");
  }
  std::array<char, 1 << 16> chunk{};
  while (stream) {
    stream.read(chunk.data(), chunk.size());
    const std::streamsize got = stream.gcount();
    if (got > 0 && EVP_DigestUpdate(context.get(), chunk.data(), static_cast<std::size_t>(got)) != 1) {
      return fail(file.string() + ": OpenSSL sha256 update failed");
    }
  }
  if (stream.bad()) return fail(file.string() + ": read error while computing its sha256");
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(context.get(), digest.data(), &length) != 1) {
    return fail(file.string() + ": OpenSSL sha256 finalisation failed");
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(length * 2);
  for (unsigned int i = 0; i < length; ++i) {
    hex.push_back(kHex[digest[i] >> 4]);
    hex.push_back(kHex[digest[i] & 0xF]);
  }
  return hex;
}

}  // namespace mane::scenes::detail
