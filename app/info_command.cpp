// `mane info`: which Vulkan device mane would use and whether it has what the renderer needs.

#include <CLI/CLI.hpp>
#include <iostream>

#include "app/commands.hpp"
#include "render/device.hpp"

namespace mane::app {

void addInfoCommand(CLI::App& app) {
  auto* command = app.add_subcommand("info", "Show the Vulkan device, driver, version and the features mane uses");
  command->callback([] {
    auto device = render::Device::create(render::deviceSettingsFromEnvironment());
    if (!device) return failWith(device.error().message);
    const render::DeviceInfo& info = (*device)->info();
    std::cout << "device:  " << info.name << (info.software ? "  (software: lavapipe)" : "  (hardware)") << '\n'
              << "driver:  " << info.driverName << ' ' << info.driverInfo << '\n'
              << "vulkan:  " << info.apiVersion << '\n'
              << "features:\n";
    for (const auto& feature : info.features)
      std::cout << "  [" << (feature.present ? "x" : " ") << "] " << feature.name << '\n';
    succeed();
  });
}

}  // namespace mane::app
