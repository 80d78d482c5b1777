#include "app/sim_outputs.hpp"

#include <cctype>
#include <cinttypes>
#include <string>

#include "scenes/groom_writer.hpp"
#include "scenes/sim_state.hpp"

namespace mane::app {

Result<StateTrace> StateTrace::open(const std::filesystem::path& file) {
  std::error_code error;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), error);
  StateTrace trace;
  trace.path_ = file;
  trace.file_.reset(std::fopen(file.c_str(), "w"));
  if (!trace.file_) return fail("--trace " + file.string() + ": cannot open the file for writing");
  return trace;
}

Result<void> StateTrace::record(std::uint64_t step, std::uint64_t stateHash) {
  if (std::fprintf(file_.get(), "%" PRIu64 " %016" PRIx64 "\n", step, stateHash) < 0)
    return fail("--trace " + path_.string() + ": cannot write the file");
  return {};
}

Result<void> StateTrace::close() {
  if (std::fclose(file_.release()) != 0) return fail("--trace " + path_.string() + ": cannot write the file");
  return {};
}

std::filesystem::path savedStatePath(const std::filesystem::path& file, std::uint64_t step) {
  char number[32];
  std::snprintf(number, sizeof number, "_%06" PRIu64, step);
  const std::string extension = file.has_extension() ? file.extension().string() : ".msim";
  return file.parent_path() / (file.stem().string() + number + extension);
}

Result<std::vector<std::filesystem::path>> saveState(const scenes::World& world, std::uint64_t step,
                                                     const std::filesystem::path& file) {
  const scenes::SimulatedState state = scenes::captureSimulatedState(world, step);
  const std::filesystem::path statePath = savedStatePath(file, step);
  std::vector<std::filesystem::path> written;
  if (auto saved = scenes::writeSimulatedState(statePath, state); !saved) return std::unexpected(saved.error());
  written.push_back(statePath);
  for (const scenes::GroomState& groom : state.grooms) {
    std::string name = groom.name;
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    const std::filesystem::path hairPath = statePath.parent_path() / (statePath.stem().string() + "_" + name + ".hair");
    const std::string info = "mane sim: groom " + groom.name + ", step " + std::to_string(step) + ", metres, world";
    if (auto saved = scenes::writeCyHair(hairPath, groom.pointsPerStrand, groom.positions, info); !saved)
      return std::unexpected(saved.error());
    written.push_back(hairPath);
  }
  return written;
}

}  // namespace mane::app
