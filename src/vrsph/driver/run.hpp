// The `vrsph run` / `vrsph check` / `vrsph bench` drivers: case -> simulation -> outputs.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/setup/case_spec.hpp"

namespace vrsph {

// Exit statuses of the command (docs/outputs.md, "On the terminal": 0 success, non-zero with a
// one-line reason).
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUnstable = 2;
inline constexpr int kExitIoError = 3;
inline constexpr int kExitHalted = 9;  // --halt-after-output (tests only)
// Stopped by SIGINT or SIGTERM (checkpoint and summary written): 128 + the signal number, 130 or
// 143, as a shell reports a command killed by the signal.
inline constexpr int kExitSignalBase = 128;

// The set-up limits of a command: where the case came from (error messages name it) and the
// user's --max-particles; the memory available is read from the machine (machine_limits).
struct SetupOrigin {
  std::string source;
  std::optional<double> max_particles;
};

struct RunOptions {
  SetupOrigin origin;
  std::filesystem::path out_dir;
  int threads = 0;  // 0: OpenMP default
  bool quiet = false;
  bool force = false;          // overwrite an existing run in out_dir
  bool resume = false;         // continue from out_dir/checkpoint.bin
  CellLayout cells;            // 0: the dimension's default (resolve_cell_layout)
  int halt_after_output = -1;  // testing aid: exit abruptly after snapshot K, as a kill would
};

// Runs a validated case (or resumes one) holding the output folder's lock (RunLock). Prints a
// one-line reason on stderr on failure and returns the exit status; bad input (CaseError, a live
// lock, a checkpoint that does not fit) is thrown.
int run_case(CaseSpec spec, const RunOptions& opt);

// Estimates the case (particles, memory, first dt: sim/preflight.hpp) and refuses it when it
// breaks a limit; then builds the particles and reports counts, h, c0, dt and the grid without
// running.
int check_case(CaseSpec spec, const SetupOrigin& origin);

struct BenchOptions {
  SetupOrigin origin;
  double sim_time = 0.05;
  int threads = 0;
  CellLayout cells;  // 0: the dimension's default (resolve_cell_layout)
  std::optional<std::filesystem::path> json_out;
};

// Runs a case for a fixed simulated time without outputs and prints particle-steps/s, pair
// interactions/s and the share of time per pass (text and JSON).
int bench_case(CaseSpec spec, const BenchOptions& opt);

}  // namespace vrsph
