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
  for (const Case& c : {Case{"fur/chelsea_cat_CC0.png", 451, 300},
                        Case{"fur/grass_CC0.png", 512, 512},
                        Case{"fur/chelsea_forehead_fur_crop_110x80.png", 110, 80},
                        Case{"head/LeePerrySmith/Map-COL.jpg", 1024, 1024},
                        Case{"head/LeePerrySmith/Infinite-Level_02_Tangent_SmoothUV.jpg", 1024,
                             1024}}) {
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
  EXPECT_GT(image.error().message.size(),
            image.error().message.find("cannot decode image: ") + 21);
}

TEST(Image, NonExistentFile) {
  auto image = loadImage("/nonexistent/mane/albedo.png");
  ASSERT_FALSE(image.has_value());
  EXPECT_EQ(image.error().message, "/nonexistent/mane/albedo.png: file not found");
}

}  // namespace
}  // namespace mane::scenes
