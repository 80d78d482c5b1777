// The `mane` command-line program: one subcommand per file (info, render, sim, view).

#include <CLI/CLI.hpp>
#include <exception>
#include <string>

#include "app/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mane: hair, fur and cloth simulation with a Vulkan renderer for skin, fur and hair"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show the help of every subcommand");

  mane::app::addInfoCommand(app);
  mane::app::addRenderCommand(app);
  mane::app::addSimCommand(app);
  mane::app::addViewCommand(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  } catch (const std::exception& error) {
    // Modules return errors as values; this is the last resort for what slipped through.
    mane::app::failWith(std::string("internal error: ") + error.what());
  }
  return mane::app::exitCode();
}
