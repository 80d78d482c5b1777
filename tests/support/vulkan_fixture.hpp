#pragma once
// A test fixture that owns a Vulkan device with the validation layers on and fails the test
// on any validation message (docs/design.md#testing: validation messages fail tests).

#include <memory>

#include <gtest/gtest.h>

#include "render/device.hpp"

namespace mane::testing {

class VulkanTest : public ::testing::Test {
protected:
  void SetUp() override;
  void TearDown() override;

  render::Device& device() { return *device_; }

private:
  std::unique_ptr<render::Device> device_;
};

}  // namespace mane::testing
