#include "render/exr.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <mutex>
#include <system_error>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>

namespace mane::render {
namespace {

/// An OpenEXR input stream over bytes already in memory.
class MemoryStream final : public Imf::IStream {
public:
  MemoryStream(std::span<const unsigned char> bytes, const std::string& name)
      : Imf::IStream(name.c_str()), bytes_(bytes) {}

  bool read(char destination[], int count) override {
    if (count < 0 || static_cast<std::uint64_t>(count) > bytes_.size() - at_)
      throw std::runtime_error("the file is cut short");
    std::memcpy(destination, bytes_.data() + at_, static_cast<std::size_t>(count));
    at_ += static_cast<std::uint64_t>(count);
    return at_ < bytes_.size();
  }
  std::uint64_t tellg() override { return at_; }
  void seekg(std::uint64_t position) override {
    if (position > bytes_.size()) throw std::runtime_error("a seek past the end of the file");
    at_ = position;
  }
  void clear() override {}

private:
  std::span<const unsigned char> bytes_;
  std::uint64_t at_ = 0;
};

/// The library checks every header it reads against these, refusing a huge declared image before
/// allocating for it (a process-wide setting).
void limitHeaderSizes() {
  static std::once_flag once;
  std::call_once(once, [] {
    Imf::Header::setMaxImageSize(kMaxExrSide, kMaxExrSide);
    Imf::Header::setMaxTileSize(kMaxExrSide, kMaxExrSide);
  });
}

std::string channelNames(const Imf::ChannelList& channels) {
  std::string names;
  for (auto channel = channels.begin(); channel != channels.end(); ++channel)
    names += (names.empty() ? "" : ", ") + std::string(channel.name());
  return names.empty() ? "none" : names;
}

}  // namespace

Result<ExrImage> decodeExr(std::span<const unsigned char> bytes, const std::string& name) {
  constexpr unsigned char kMagic[] = {0x76, 0x2f, 0x31, 0x01};
  if (bytes.size() < sizeof kMagic || !std::equal(std::begin(kMagic), std::end(kMagic), bytes.begin()))
    return fail(name + ": not an OpenEXR file (it must begin with the bytes 76 2f 31 01)");
  limitHeaderSizes();
  try {
    MemoryStream stream(bytes, name);
    Imf::InputFile file(stream);
    const Imf::Header& header = file.header();
    if (header.hasType() && Imf::isDeepData(header.type()))
      return fail(name + ": holds deep data; only flat images are read");
    const Imath::Box2i window = header.dataWindow();
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0)
      return fail(name + ": the data window is empty (" + std::to_string(width) + " x " + std::to_string(height) + ")");
    if (width > kMaxExrSide || height > kMaxExrSide || width * height > kMaxExrPixels)
      return fail(name + ": the image is too large: " + std::to_string(width) + " x " + std::to_string(height) +
                  " pixels (at most " + std::to_string(kMaxExrSide) + " on a side and " +
                  std::to_string(kMaxExrPixels) + " in all)");

    const Imf::ChannelList& channels = header.channels();
    const bool rgb = channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
    const bool grey = !rgb && channels.findChannel("Y");
    if (!rgb && !grey)
      return fail(name + ": no colour channels (R, G, B or Y); the file has " + channelNames(channels));
    for (const char* channelName : {"R", "G", "B", "A", "Y"})
      if (const Imf::Channel* channel = channels.findChannel(channelName);
          channel && (channel->xSampling != 1 || channel->ySampling != 1))
        return fail(name + ": channel " + channelName + " is sub-sampled; only full-resolution channels are read");

    ExrImage image{.width = static_cast<int>(width), .height = static_cast<int>(height)};
    image.texels.resize(static_cast<std::size_t>(width * height));
    auto* first = reinterpret_cast<char*>(image.texels.data());
    constexpr std::size_t kTexel = sizeof(glm::vec4), kChannel = sizeof(float);
    const std::size_t row = kTexel * static_cast<std::size_t>(width);
    Imf::FrameBuffer frame;
    const auto slice = [&](int component, double fill) {
      return Imf::Slice::Make(Imf::FLOAT, first + component * kChannel, window, kTexel, row, 1, 1, fill);
    };
    if (grey) {
      frame.insert("Y", slice(0, 0.0));
    } else {
      frame.insert("R", slice(0, 0.0));
      frame.insert("G", slice(1, 0.0));
      frame.insert("B", slice(2, 0.0));
    }
    frame.insert("A", slice(3, 1.0));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    if (grey)
      for (glm::vec4& texel : image.texels) texel.g = texel.b = texel.r;
    return image;
  } catch (const std::exception& error) {
    return fail(name + ": cannot decode the OpenEXR file: " + error.what());
  }
}

Result<void> writeExr(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                      std::span<const std::uint16_t> rgbaHalf) {
  if (width == 0 || height == 0 || rgbaHalf.size() != std::size_t(width) * height * 4)
    return fail(path.string() + ": " + std::to_string(rgbaHalf.size()) + " values given for a " +
                std::to_string(width) + "x" + std::to_string(height) + " RGBA image");
  std::error_code error;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), error);
  if (error) return fail(path.parent_path().string() + ": cannot create the folder: " + error.message());
  try {
    Imf::Header header(static_cast<int>(width), static_cast<int>(height));
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    // Imath's half is the IEEE binary16 bit pattern, as the GPU's R16G16B16A16_SFLOAT stores it.
    auto* first = const_cast<char*>(reinterpret_cast<const char*>(rgbaHalf.data()));
    constexpr std::size_t kTexel = 4 * sizeof(std::uint16_t);
    for (int c = 0; c < 3; ++c) {
      const char* channel = c == 0 ? "R" : c == 1 ? "G" : "B";
      header.channels().insert(channel, Imf::Channel(Imf::HALF));
      frame.insert(channel, Imf::Slice(Imf::HALF, first + c * sizeof(std::uint16_t), kTexel, kTexel * width));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(static_cast<int>(height));
  } catch (const std::exception& error) {
    return fail(path.string() + ": cannot write the OpenEXR file: " + error.what());
  }
  return {};
}

}  // namespace mane::render
