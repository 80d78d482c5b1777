#pragma once
// Registration of the subcommands. Each adds itself to the CLI11 app with a callback; the
// callback runs the command and records its exit code.

#include <string>

namespace CLI {
class App;
}
namespace mane::render {
class Device;
}

namespace mane::app {

void addInfoCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addSimCommand(CLI::App& app);
void addViewCommand(CLI::App& app);

/// Records the outcome of the command that ran: 0, or 1 after printing `mane: <reason>` as a
/// single line on stderr.
void succeed();
void failWith(const std::string& reason);
int exitCode();

/// Prints the validation layer's messages (MANE_VALIDATION=1 or a debug build) on stderr and
/// fails the command when there were any; returns whether there were none.
bool checkValidation(const render::Device& device);

}  // namespace mane::app
