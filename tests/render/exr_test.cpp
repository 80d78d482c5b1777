// OpenEXR frames and panoramas (render/exr.hpp): every finite fp16 value survives a write and a
// read bit for bit; files the library writes in other shapes (float channels beyond fp16's range,
// luminance only, a shifted data window, tiles) read as the values written; damaged files and
// files without colour give errors that name the file and the problem.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/exr.hpp"

namespace mane::render {
namespace {

class ExrFiles : public ::testing::Test {
protected:
  ExrFiles() {
    dir_ = std::filesystem::temp_directory_path() /
           ("mane-exr-test-" + std::to_string(std::random_device{}()) + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(dir_);
  }
  ~ExrFiles() override {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }

  std::filesystem::path file(const std::string& name) const { return dir_ / name; }

  static std::vector<unsigned char> bytesOf(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  Result<ExrImage> decode(const std::filesystem::path& path) const { return decodeExr(bytesOf(path), path.string()); }

  /// A file of float channels named `channels`, channel c of texel i holding value(i, c), over
  /// the data window `window` (the display window being `width` × `height` at the origin).
  template <class Value>
  void writeFloatFile(const std::filesystem::path& path, const Imath::Box2i& window,
                      const std::vector<std::string>& channels, Value value, bool tiled = false) const {
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    Imf::Header header(Imath::Box2i({0, 0}, {width - 1, height - 1}), window);
    std::vector<std::vector<float>> planes(channels.size(), std::vector<float>(std::size_t(width * height)));
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < channels.size(); ++c) {
      for (int i = 0; i < width * height; ++i) planes[c][std::size_t(i)] = value(i, int(c));
      header.channels().insert(channels[c], Imf::Channel(Imf::FLOAT));
      frame.insert(channels[c], Imf::Slice::Make(Imf::FLOAT, planes[c].data(), window));
    }
    if (tiled) {
      header.setTileDescription(Imf::TileDescription(16, 8));
      Imf::TiledOutputFile out(path.c_str(), header);
      out.setFrameBuffer(frame);
      out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
    } else {
      Imf::OutputFile out(path.c_str(), header);
      out.setFrameBuffer(frame);
      out.writePixels(height);
    }
  }

private:
  std::filesystem::path dir_;
};

TEST_F(ExrFiles, EveryFiniteHalfSurvivesAWriteAndARead) {
  // Every finite fp16 bit pattern (both signs, subnormals, zeros, ±65504), then random ones.
  constexpr std::uint32_t kWidth = 181, kHeight = 97;
  std::vector<std::uint16_t> rgba(std::size_t(kWidth) * kHeight * 4);
  std::mt19937 random(7);
  std::uint32_t next = 0;
  for (std::uint16_t& value : rgba) {
    std::uint16_t bits = 0;
    do {
      bits = next < 0x10000 ? std::uint16_t(next++) : std::uint16_t(random());
    } while ((bits & 0x7c00) == 0x7c00);  // infinities and NaNs
    value = bits;
  }
  const auto path = file("frames/frame.exr");  // the folder is created
  ASSERT_TRUE(writeExr(path, kWidth, kHeight, rgba).has_value());
  auto image = decode(path);
  ASSERT_TRUE(image.has_value()) << image.error().message;
  ASSERT_EQ(image->width, int(kWidth));
  ASSERT_EQ(image->height, int(kHeight));
  for (std::size_t i = 0; i < image->texels.size(); ++i) {
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(glm::packHalf1x16(image->texels[i][c]), rgba[4 * i + std::size_t(c)])
          << "texel " << i << " channel " << c;
    ASSERT_EQ(image->texels[i].a, 1.0f);  // a frame is written opaque
  }
}

TEST_F(ExrFiles, FloatChannelsKeepValuesBeyondHalfsRange) {
  const auto path = file("float.exr");
  const auto value = [](int i, int c) { return std::ldexp(1.0f + float(i % 7) / 8.0f, 20 - 3 * c) * (c == 3 ? 0 : 1); };
  writeFloatFile(path, Imath::Box2i({0, 0}, {7, 3}), {"R", "G", "B"}, value);
  auto image = decode(path);
  ASSERT_TRUE(image.has_value()) << image.error().message;
  ASSERT_EQ(image->texels.size(), 32u);
  for (int i = 0; i < 32; ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(image->texels[std::size_t(i)][c], value(i, c)) << i << ", " << c;
  EXPECT_GT(image->texels[0].r, 65504.0f);
}

TEST_F(ExrFiles, LuminanceAloneReadsAsGrey) {
  const auto path = file("grey.exr");
  writeFloatFile(path, Imath::Box2i({0, 0}, {3, 1}), {"Y"}, [](int i, int) { return 0.25f * float(i); });
  auto image = decode(path);
  ASSERT_TRUE(image.has_value()) << image.error().message;
  for (int i = 0; i < 8; ++i) EXPECT_EQ(image->texels[std::size_t(i)], glm::vec4(glm::vec3(0.25f * float(i)), 1.0f));
}

TEST_F(ExrFiles, AShiftedDataWindowAndTilesReadInRowOrder) {
  const auto value = [](int i, int c) { return float(i) + 0.25f * float(c); };
  const Imath::Box2i window({-3, 5}, {36, 24});  // 40 × 20, not a multiple of the tiles
  for (const bool tiled : {false, true}) {
    SCOPED_TRACE(tiled ? "tiled" : "scanlines");
    const auto path = file(tiled ? "tiled.exr" : "shifted.exr");
    writeFloatFile(path, window, {"R", "G", "B", "A"}, value, tiled);
    auto image = decode(path);
    ASSERT_TRUE(image.has_value()) << image.error().message;
    ASSERT_EQ(image->width, 40);
    ASSERT_EQ(image->height, 20);
    for (int i = 0; i < 800; ++i)
      ASSERT_EQ(image->texels[std::size_t(i)], glm::vec4(value(i, 0), value(i, 1), value(i, 2), value(i, 3))) << i;
  }
}

TEST_F(ExrFiles, DamagedAndColourlessFilesGiveErrorsNamingTheFile) {
  const auto messageOf = [&](const std::filesystem::path& path) {
    auto image = decode(path);
    return image ? std::string("decoded") : image.error().message;
  };
  const auto depth = file("depth.exr");
  writeFloatFile(depth, Imath::Box2i({0, 0}, {3, 1}), {"Z"}, [](int, int) { return 1.0f; });
  EXPECT_EQ(messageOf(depth), depth.string() + ": no colour channels (R, G, B or Y); the file has Z");

  const auto whole = file("whole.exr");
  writeFloatFile(whole, Imath::Box2i({0, 0}, {63, 31}), {"R", "G", "B"}, [](int i, int) { return float(i); });
  const std::vector<unsigned char> bytes = bytesOf(whole);
  for (const std::size_t kept : {std::size_t(3), std::size_t(40), bytes.size() / 2, bytes.size() - 1}) {
    SCOPED_TRACE(kept);
    auto image = decodeExr(std::span(bytes).first(kept), "cut.exr");
    ASSERT_FALSE(image.has_value());
    EXPECT_EQ(image.error().message.rfind("cut.exr: ", 0), 0u) << image.error().message;
  }
  const std::vector<unsigned char> text = {'#', '?', 'R', 'A', 'D', 'I', 'A', 'N', 'C', 'E'};
  auto image = decodeExr(text, "sky.hdr");
  ASSERT_FALSE(image.has_value());
  EXPECT_EQ(image.error().message, "sky.hdr: not an OpenEXR file (it must begin with the bytes 76 2f 31 01)");
}

TEST_F(ExrFiles, AHugeDeclaredImageIsRefusedBeforeItsPixelsAreRead) {
  const auto path = file("huge.exr");
  writeFloatFile(path, Imath::Box2i({0, 0}, {1, 0}), {"R", "G", "B"}, [](int, int) { return 1.0f; });
  // The data window's x max, written as four little-endian bytes after its name and type.
  std::vector<unsigned char> bytes = bytesOf(path);
  const std::string key = "dataWindow";
  auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  ASSERT_NE(at, bytes.end());
  const std::size_t maxX = std::size_t(at - bytes.begin()) + key.size() + 1 + std::string("box2i").size() + 1 + 4 + 8;
  bytes[maxX] = 0x00, bytes[maxX + 1] = 0x00, bytes[maxX + 2] = 0x01, bytes[maxX + 3] = 0x00;  // 65536
  auto image = decodeExr(bytes, "huge.exr");
  ASSERT_FALSE(image.has_value());
  EXPECT_EQ(image.error().message.rfind("huge.exr: ", 0), 0u) << image.error().message;
  // Refused by the header's size limit (limitHeaderSizes), before any pixel is allocated.
  EXPECT_NE(image.error().message.find("exceeds the maximum width of 16384"), std::string::npos)
      << image.error().message;
}

TEST_F(ExrFiles, WritingRefusesAMismatchedSize) {
  const std::vector<std::uint16_t> three(3);
  auto written = writeExr(file("bad.exr"), 1, 1, three);
  ASSERT_FALSE(written.has_value());
  EXPECT_NE(written.error().message.find("3 values given for a 1x1 RGBA image"), std::string::npos);
}

}  // namespace
}  // namespace mane::render
