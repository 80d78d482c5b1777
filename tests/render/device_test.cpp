// The Vulkan device: lavapipe is found and chosen when asked for, and the validation callback
// really turns API misuse into a recorded message (so a clean test run means something).

#include <cstdlib>

#include <gtest/gtest.h>

#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

TEST(Device, LavapipeIsChosenWhenAskedFor) {
  auto device = Device::create({.preference = DevicePreference::kLavapipe, .validation = true});
  ASSERT_TRUE(device.has_value()) << device.error().message;
  const DeviceInfo& info = (*device)->info();
  EXPECT_TRUE(info.software);
  // Mesa names its CPU device "llvmpipe (LLVM ...)" and the driver "llvmpipe".
  EXPECT_NE(info.name.find("llvmpipe"), std::string::npos) << info.name;
  EXPECT_GE(info.apiVersion.substr(0, 3), std::string("1.3"));
  EXPECT_TRUE((*device)->validationMessages().empty());
}

TEST(Device, ReportsTheFeaturesTheRendererUses) {
  auto device = Device::create({.preference = DevicePreference::kLavapipe});
  ASSERT_TRUE(device.has_value()) << device.error().message;
  const auto& features = (*device)->info().features;
  ASSERT_FALSE(features.empty());
  for (const auto& feature : features) {
    // lavapipe 22.3 has every feature mane uses (docs/lavapipe.md#features); validation is off
    // here.
    if (feature.name == "validation layers") continue;
    EXPECT_TRUE(feature.present) << feature.name;
  }
}

TEST(Device, ValidationCallbackRecordsMisuse) {
  auto device = Device::create({.preference = DevicePreference::kLavapipe, .validation = true});
  ASSERT_TRUE(device.has_value()) << device.error().message;
  // A buffer with no usage flags breaks VUID-VkBufferCreateInfo-usage-requiredbitmask; the
  // driver itself tolerates it, so only the layer notices.
  { const vk::raii::Buffer buffer((*device)->device(), vk::BufferCreateInfo{.size = 64, .usage = {}}); }
  const auto messages = (*device)->validationMessages();
  ASSERT_FALSE(messages.empty());
  EXPECT_NE(messages.front().find("usage"), std::string::npos) << messages.front();
}

TEST(Device, EnvironmentSelectsLavapipe) {
  ::setenv("MANE_DEVICE", "lavapipe", 1);
  const DeviceSettings settings = deviceSettingsFromEnvironment();
  ::unsetenv("MANE_DEVICE");
  EXPECT_EQ(settings.preference, DevicePreference::kLavapipe);
}

}  // namespace
}  // namespace mane::render
