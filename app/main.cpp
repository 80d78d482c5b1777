// The `mane` command-line program: one subcommand per file (info, render, sim, view).

#include <CLI/CLI.hpp>
#include <exception>
#include <string>

#include "app/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mane: hair, fur and cloth simulation with a Vulkan renderer for skin, fur and hair"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show the help of every subcommand");
  app.set_version_flag("--version", std::string("mane ") + MANE_VERSION);

  mane::app::addInfoCommand(app);
  mane::app::addRenderCommand(app);
  mane::app::addSimCommand(app);
  mane::app::addViewCommand(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForVersion& version) {
    return app.exit(version);
  } catch (const CLI::ParseError& error) {
    // A usage error reads like every other failure: one line, status 1.
    mane::app::failWith(std::string(error.what()) + " (see mane --help)");
  } catch (const std::exception& error) {
    // Modules return errors as values; this is the last resort for what slipped through.
    mane::app::failWith(std::string("internal error: ") + error.what());
  }
  return mane::app::exitCode();
}
