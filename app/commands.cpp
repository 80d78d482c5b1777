#include "app/commands.hpp"

#include <iostream>

namespace mane::app {
namespace {
int gExitCode = 0;
}

void succeed() { gExitCode = 0; }

void failWith(const std::string& reason) {
  std::string line = reason;
  for (char& c : line)
    if (c == '\n') c = ' ';
  std::cerr << "mane: " << line << '\n';
  gExitCode = 1;
}

int exitCode() { return gExitCode; }

}  // namespace mane::app
