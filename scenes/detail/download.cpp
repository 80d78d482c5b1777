#include "scenes/detail/download.hpp"

#include <cstdio>
#include <memory>
#include <mutex>

#include <curl/curl.h>

namespace mane::scenes::detail {
namespace {

std::size_t writeToFile(char* data, std::size_t size, std::size_t count, void* user) {
  return std::fwrite(data, size, count, static_cast<std::FILE*>(user)) * size;
}

}  // namespace

Result<void> downloadFile(const std::string& url, const std::filesystem::path& destination,
                          const DownloadLimits& limits) {
  // curl_global_init is not thread-safe; do it once.
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });

  std::unique_ptr<CURL, void (*)(CURL*)> curl(curl_easy_init(), &curl_easy_cleanup);
  if (!curl) return fail("cannot download " + url + ": curl_easy_init failed");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(destination.c_str(), "wb"), &std::fclose);
  if (!out) return fail("cannot download " + url + ": cannot write " + destination.string());

  char errorBuffer[CURL_ERROR_SIZE] = {};
  curl_easy_setopt(curl.get(), CURLOPT_URL, url.c_str());
  curl_easy_setopt(curl.get(), CURLOPT_WRITEFUNCTION, &writeToFile);
  curl_easy_setopt(curl.get(), CURLOPT_WRITEDATA, out.get());
  curl_easy_setopt(curl.get(), CURLOPT_ERRORBUFFER, errorBuffer);
  curl_easy_setopt(curl.get(), CURLOPT_FOLLOWLOCATION, 1L);
  curl_easy_setopt(curl.get(), CURLOPT_MAXREDIRS, 5L);
  curl_easy_setopt(curl.get(), CURLOPT_FAILONERROR, 1L);
  curl_easy_setopt(curl.get(), CURLOPT_NOSIGNAL, 1L);  // no SIGALRM from DNS timeouts
  curl_easy_setopt(curl.get(), CURLOPT_CONNECTTIMEOUT, limits.connectTimeoutSeconds);
  curl_easy_setopt(curl.get(), CURLOPT_TIMEOUT, limits.totalTimeoutSeconds);
  curl_easy_setopt(curl.get(), CURLOPT_LOW_SPEED_LIMIT, 1024L);
  curl_easy_setopt(curl.get(), CURLOPT_LOW_SPEED_TIME, limits.stallTimeoutSeconds);
  curl_easy_setopt(curl.get(), CURLOPT_USERAGENT, "mane-asset-resolver/0.1");

  const CURLcode code = curl_easy_perform(curl.get());
  const bool flushed = std::fflush(out.get()) == 0;
  out.reset();
  if (code != CURLE_OK || !flushed) {
    std::error_code ec;
    std::filesystem::remove(destination, ec);
    long status = 0;
    curl_easy_getinfo(curl.get(), CURLINFO_RESPONSE_CODE, &status);
    std::string reason = errorBuffer[0] != '\0' ? errorBuffer : curl_easy_strerror(code);
    if (!flushed) reason = "could not write " + destination.string();
    if (status >= 400) reason += " (HTTP " + std::to_string(status) + ")";
    return fail("cannot download " + url + ": " + reason);
  }
  return {};
}

}  // namespace mane::scenes::detail
