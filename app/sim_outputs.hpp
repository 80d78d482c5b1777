#pragma once
// What `mane sim` writes besides its summary: the per-step hash trace (--trace) and the saved
// states (--save FILE --at STEPS): the state file (scenes/sim_state.hpp) and each groom as a
// HAIR file (scenes/groom_writer.hpp).

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "common/error.hpp"
#include "scenes/world.hpp"

namespace mane::app {

/// `--trace FILE`: one line per step, "<step> <state hash, 16 hex digits>", step 0 the loaded
/// state; two runs' traces first differ on the first step whose state differs.
class StateTrace {
public:
  [[nodiscard]] static Result<StateTrace> open(const std::filesystem::path& file);
  [[nodiscard]] Result<void> record(std::uint64_t step, std::uint64_t stateHash);
  /// Flushes and closes; errors name the file.
  [[nodiscard]] Result<void> close();

private:
  struct Closer {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::filesystem::path path_;
  std::unique_ptr<std::FILE, Closer> file_;
};

/// Where --save FILE puts step `step`: FILE's stem + "_" + the step in six digits (more when
/// needed) + FILE's extension (".msim" when it has none).
[[nodiscard]] std::filesystem::path savedStatePath(const std::filesystem::path& file, std::uint64_t step);

/// Writes `world`'s state as step `step` to savedStatePath(file, step), and each simulated groom
/// beside it as "<that name without extension>_<groom>.hair" (world space, metres; characters of
/// the groom name other than letters, digits, '-' and '_' become '_'). Returns the files written.
[[nodiscard]] Result<std::vector<std::filesystem::path>> saveState(const scenes::World& world, std::uint64_t step,
                                                                   const std::filesystem::path& file);

}  // namespace mane::app
