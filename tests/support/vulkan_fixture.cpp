#include "tests/support/vulkan_fixture.hpp"

namespace mane::testing {

void VulkanTest::SetUp() {
  render::DeviceSettings settings = render::deviceSettingsFromEnvironment();
  settings.validation = true;
  auto device = render::Device::create(settings);
  ASSERT_TRUE(device.has_value()) << device.error().message;
  device_ = std::move(*device);
}

void VulkanTest::TearDown() {
  if (!device_) return;
  device_->device().waitIdle();
  for (const auto& message : device_->validationMessages()) ADD_FAILURE() << message;
}

}  // namespace mane::testing
