#include "app/commands.hpp"

#include <iostream>

#include "render/device.hpp"

namespace mane::app {
namespace {
int gExitCode = 0;
}

void succeed() {
  gExitCode = 0;
}

void failWith(const std::string& reason) {
  std::string line = reason;
  for (char& c : line)
    if (c == '\n') c = ' ';
  std::cerr << "mane: " << line << '\n';
  gExitCode = 1;
}

int exitCode() {
  return gExitCode;
}

bool checkValidation(const render::Device& device) {
  const auto messages = device.validationMessages();
  for (const std::string& message : messages) std::cerr << message << '\n';
  if (messages.empty()) return true;
  failWith(std::to_string(messages.size()) + " Vulkan validation messages");
  return false;
}

}  // namespace mane::app
