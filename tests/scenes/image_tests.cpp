// Image loading: sizes from the assets README, decoded values checked where a file format
// fixes them, and errors that carry stb_image's reason.

#include <gtest/gtest.h>

#include "scenes/image.hpp"
#include "test_support.hpp"

namespace mane::scenes {
namespace {

TEST(Image, LoadsPngAndJpegAssetsAtTheirReadmeSizes) {
  struct Case {
    const char* name;
    int width;
    int height;
  };
  for (const Case& c :
       {Case{"fur/chelsea_cat_CC0.png", 451, 300}, Case{"fur/grass_CC0.png", 512, 512},
        Case{"fur/chelsea_forehead_fur_crop_110x80.png", 110, 80}, Case{"head/LeePerrySmith/Map-COL.jpg", 1024, 1024},
        Case{"head/LeePerrySmith/Infinite-Level_02_Tangent_SmoothUV.jpg", 1024, 1024}}) {
    SCOPED_TRACE(c.name);
    MANE_RESOLVE_OR_SKIP(file, c.name);
    auto image = loadImage(file);
    ASSERT_TRUE(image.has_value()) << image.error().message;
    EXPECT_EQ(image->width, c.width);
    EXPECT_EQ(image->height, c.height);
    EXPECT_EQ(image->rgba.size(), static_cast<std::size_t>(c.width * c.height * 4));
  }
}

TEST(Image, GreyscalePngRepeatsGreyAndIsOpaque) {
  MANE_RESOLVE_OR_SKIP(file, "fur/grass_CC0.png");  // README: greyscale
  auto image = loadImage(file);
  ASSERT_TRUE(image.has_value()) << image.error().message;
  for (std::size_t i = 0; i < image->rgba.size(); i += 4) {
    ASSERT_EQ(image->rgba[i], image->rgba[i + 1]);
    ASSERT_EQ(image->rgba[i], image->rgba[i + 2]);
    ASSERT_EQ(image->rgba[i + 3], 255);
  }
}

TEST(Image, CorruptFileGivesStbReasonAndFileName) {
  testing::ScratchDir dir;
  auto image = loadImage(dir.write("fake.png", "this is not a png"));
  ASSERT_FALSE(image.has_value());
  EXPECT_NE(image.error().message.find("fake.png"), std::string::npos);
  EXPECT_NE(image.error().message.find("cannot decode image: "), std::string::npos);
  // stb's reason follows the colon; whatever its wording, it is not empty.
  EXPECT_GT(image.error().message.size(), image.error().message.find("cannot decode image: ") + 21);
}

// Found by tests/fuzz/fuzz_image: stb_image decodes this PNM header as 2 x 0 pixels and
// returns a non-null, empty buffer; an image without pixels is an error, not a success.
TEST(Image, HeaderWithAZeroDimensionIsAnError) {
  testing::ScratchDir dir;
  const std::string bytes("P6\n2\x9d\x03\x03\x04\x0b\x06\x07\x08\x09\x0a\x0b", 15);
  auto image = loadImage(dir.write("zero.ppm", bytes));
  ASSERT_FALSE(image.has_value());
  EXPECT_NE(image.error().message.find("zero.ppm: cannot decode image: it has no pixels"), std::string::npos)
      << image.error().message;
}

// Found by tests/fuzz/fuzz_image: a 16-bit PGM (maxval 256) made stb_image 2.27 read past
// its buffer when asked for RGBA. It decodes now, 16-bit values scaled to 8 bits.
TEST(Image, SixteenBitPgmDecodesToOpaqueGrey) {
  testing::ScratchDir dir;
  const std::string bytes("P5 1 2 256\n\x00\x40\x80\xff", 15);
  auto image = loadImage(dir.write("grey16.pgm", bytes));
  ASSERT_TRUE(image.has_value()) << image.error().message;
  ASSERT_EQ(image->width, 1);
  ASSERT_EQ(image->height, 2);
  ASSERT_EQ(image->rgba.size(), 8u);
  for (int pixel = 0; pixel < 2; ++pixel) {
    const std::uint8_t* p = &image->rgba[static_cast<std::size_t>(pixel) * 4];
    EXPECT_EQ(p[0], p[1]);
    EXPECT_EQ(p[0], p[2]);
    EXPECT_EQ(p[3], 255);
  }
}

// Found by tests/fuzz/fuzz_image: a GIF header declaring 20050 x 18261 pixels made
// stb_image allocate and clear 1.4 GiB for a 110-byte file. The size is checked first.
TEST(Image, HugeDeclaredSizeIsRefusedBeforeDecoding) {
  testing::ScratchDir dir;
  std::string gif("GIF89a", 6);
  gif += std::string("\x52\x4e\x55\x47\x80\x00\x00", 7);  // 20050 x 18261, 2-colour table
  gif += std::string("\x00\x00\x00\xff\xff\xff", 6);
  gif += std::string(",\x00\x00\x00\x00\x02\x00\x02\x00\x00\x02\x02\x4c\x01\x00;", 16);
  auto image = loadImage(dir.write("huge.gif", gif));
  ASSERT_FALSE(image.has_value());
  EXPECT_EQ(image.error().message, (dir.path() / "huge.gif").string() +
                                       ": image too large: 20050 x 18261 pixels (at most 16384 on a side and "
                                       "67108864 in all)");
}

TEST(Image, NonExistentFile) {
  auto image = loadImage("/nonexistent/mane/albedo.png");
  ASSERT_FALSE(image.has_value());
  EXPECT_EQ(image.error().message, "/nonexistent/mane/albedo.png: file not found");
}

}  // namespace
}  // namespace mane::scenes
