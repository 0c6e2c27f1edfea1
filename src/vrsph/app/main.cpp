// The `vrsph` command: run, check and bench a case file (README "Using it"; docs/cases.md,
// docs/outputs.md).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "vrsph/driver/data_dir.hpp"
#include "vrsph/driver/run.hpp"
#include "vrsph/exec/launch_tuner.hpp"
#include "vrsph/setup/case_parser.hpp"

namespace {

using namespace vrsph;

// Applies the --set overrides in order to a case table and validates it.
CaseSpec parse_with_sets(toml::table tbl, const std::string& path,
                         const std::vector<std::string>& sets) {
  for (const std::string& s : sets) apply_override(tbl, s);
  return parse_case(tbl, path);
}

// Reads a case file, applies the --set overrides in order and validates it.
CaseSpec load_case(const std::string& path, const std::vector<std::string>& sets) {
  return parse_with_sets(load_case_table(path), path, sets);
}

// Keys vrsph writes into a run folder's case.toml only when they differ from the value runs had
// before the key existed (so that older folders still resume): a folder's case without one ran
// with that value, whatever the default for case files.
struct LegacyDefault {
  const char* key;       // dotted path
  const char* override;  // the --set line that restores the value
};
constexpr LegacyDefault kLegacyDefaults[] = {
    {"numerics.precision", "numerics.precision=\"double\""},
    {"numerics.surface_tension.refresh", "numerics.surface_tension.refresh=\"every_step\""},
};

// The resolved case of a run folder: its case.toml with the legacy values of the keys it lacks,
// then the --set overrides.
CaseSpec load_run_case(const std::string& path, const std::vector<std::string>& sets) {
  toml::table tbl = load_case_table(path);
  for (const LegacyDefault& d : kLegacyDefaults)
    if (!tbl.at_path(d.key)) apply_override(tbl, d.override);
  return parse_with_sets(std::move(tbl), path, sets);
}

// A case named on the command line: found from the current folder, or else among the shipped
// data (data_dir.hpp), which is said in one line.
CaseSpec load_given_case(const std::string& given, const std::vector<std::string>& sets) {
  const std::string path = find_case_file(given).string();
  if (path != given) fmt::print("vrsph: {} is not in this folder: reading {}\n", given, path);
  return load_case(path, sets);
}

// A resumed run may change how long it runs and how often it writes: case.end_time and
// output.interval. Other output keys would change the files being continued and are refused
// here; a physical key reaches the checkpoint's case check, which refuses a changed value naming
// the key (so resetting a key to the value it has is harmless).
void check_resume_overrides(const std::vector<std::string>& sets) {
  for (const std::string& s : sets) {
    std::string key = s.substr(0, s.find('='));
    const auto first = key.find_first_not_of(" \t");
    const auto last = key.find_last_not_of(" \t");
    key = first == std::string::npos ? std::string() : key.substr(first, last - first + 1);
    if ((key == "output" || key.starts_with("output.")) && key != "output.interval") {
      throw CaseError(fmt::format(
          "--set {}: cannot change {} when resuming (of the output keys only output.interval)", s,
          key));
    }
  }
}

// Everything the command line can set.
struct CliArgs {
  std::string case_path, out_dir, resume_dir, json_out;
  std::vector<std::string> sets;
  int threads = 0, cells = 0, block = 0, halt_after = -1;  // cells, block 0: by dimension
  bool quiet = false, force = false;
  double bench_time = 0.05;
  double max_particles = 0.0;  // 0: no limit
};

// --max-particles N: refuse a case whose set-up estimate exceeds N particles.
void add_max_particles(CLI::App* cmd, CliArgs& a) {
  cmd->add_option("--max-particles", a.max_particles,
                  "refuse the case when the set-up would make more than N particles")
      ->check(CLI::PositiveNumber);
}

SetupOrigin origin_of(const CliArgs& a, const std::string& source) {
  SetupOrigin o{source, std::nullopt};
  if (a.max_particles > 0.0) o.max_particles = a.max_particles;
  return o;
}

CLI::App* add_run_command(CLI::App& app, CliArgs& a) {
  CLI::App* run = app.add_subcommand("run", "run a case (or resume a stopped run)");
  run->add_option("case", a.case_path, "case file (TOML)");
  run->add_option("--out", a.out_dir, "output folder (default out/<case name>)");
  run->add_option("--resume", a.resume_dir, "continue the run in this folder from its checkpoint");
  run->add_option("--threads", a.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 4096).description("an integer >= 1"));
  run->add_option("--set", a.sets, "override a case key: KEY=VALUE (repeatable)");
  run->add_flag("--quiet", a.quiet, "no progress line and no start/end summaries");
  run->add_flag("--force", a.force, "overwrite an earlier run in the output folder");
  run->add_option("--cells-per-support", a.cells,
                  "neighbour cells per 2h (1 full, 2 half; default 1 in 2D, 2 in 3D)")
      ->check(CLI::Range(1, 4));
  run->add_option(
         "--cells-per-block", a.block,
         "cells of a row over which surface pass 2 bounds lambda (default 1 in 2D, 2 in 3D)")
      ->check(CLI::Range(1, 8));
  run->add_option("--halt-after-output", a.halt_after,
                  "testing aid: stop abruptly right after writing snapshot K (as a kill would)")
      ->group("");  // hidden from --help
  add_max_particles(run, a);
  return run;
}

CLI::App* add_check_command(CLI::App& app, CliArgs& a) {
  CLI::App* check =
      app.add_subcommand("check", "validate a case and report particle counts and dt");
  check->add_option("case", a.case_path, "case file (TOML)")->required();
  check->add_option("--set", a.sets, "override a case key: KEY=VALUE (repeatable)");
  add_max_particles(check, a);
  return check;
}

CLI::App* add_bench_command(CLI::App& app, CliArgs& a) {
  CLI::App* bench =
      app.add_subcommand("bench", "time a case without outputs (default: the benchmark case)");
  bench->add_option("case", a.case_path,
                    "case file (default cases/bench_dam_break_2d.toml of the shipped data)");
  bench->add_option("--time", a.bench_time, "simulated time in s")->check(CLI::PositiveNumber);
  bench->add_option("--threads", a.threads, "OpenMP threads")
      ->check(CLI::Range(1, 4096).description("an integer >= 1"));
  bench->add_option("--set", a.sets, "override a case key: KEY=VALUE (repeatable)");
  bench->add_option("--json", a.json_out, "also write the figures to this JSON file");
  bench
      ->add_option("--cells-per-support", a.cells,
                   "neighbour cells per 2h (1 full, 2 half; default 1 in 2D, 2 in 3D)")
      ->check(CLI::Range(1, 4));
  bench
      ->add_option(
          "--cells-per-block", a.block,
          "cells of a row over which surface pass 2 bounds lambda (default 1 in 2D, 2 in 3D)")
      ->check(CLI::Range(1, 8));
  return bench;
}

int run_command(const CliArgs& a) {
  RunOptions ro;
  ro.threads = a.threads;
  ro.quiet = a.quiet;
  ro.force = a.force;
  ro.cells = {a.cells, a.block};
  ro.halt_after_output = a.halt_after;
  if (!a.resume_dir.empty()) {
    if (!a.case_path.empty())
      throw CaseError("run: give either a case file or --resume DIR, not both");
    if (!a.out_dir.empty())
      throw CaseError("run: --out cannot be combined with --resume (the run continues in DIR)");
    check_resume_overrides(a.sets);
    ro.resume = true;
    ro.out_dir = a.resume_dir;
    const std::string path = (std::filesystem::path(a.resume_dir) / "case.toml").string();
    ro.origin = origin_of(a, path);
    return run_case(load_run_case(path, a.sets), ro);
  }
  if (a.case_path.empty()) throw CaseError("run: a case file (or --resume DIR) is required");
  CaseSpec spec = load_given_case(a.case_path, a.sets);
  ro.origin = origin_of(a, a.case_path);
  ro.out_dir = a.out_dir.empty() ? std::filesystem::path("out") / spec.name
                                 : std::filesystem::path(a.out_dir);
  return run_case(std::move(spec), ro);
}

int bench_command(const CliArgs& a) {
  const std::string path = a.case_path.empty()
                               ? (data_dir() / "cases" / "bench_dam_break_2d.toml").string()
                               : a.case_path;
  if (a.case_path.empty() && !std::filesystem::exists(path)) {
    throw CaseError(fmt::format(
        "bench: the benchmark case {} is missing (the data folder is found from VRSPH_DATA_DIR, "
        "then ../share/vrsph beside the executable, then the source tree)",
        path));
  }
  BenchOptions bo;
  bo.sim_time = a.bench_time;
  bo.threads = a.threads;
  bo.cells = {a.cells, a.block};
  bo.origin = origin_of(a, path);
  if (!a.json_out.empty()) bo.json_out = a.json_out;
  return bench_case(load_given_case(path, a.sets), bo);
}

int dispatch(int argc, char** argv) {
  CLI::App app{"vrsph: weakly compressible SPH with surface tension and variable resolution"};
  app.set_version_flag("--version", std::string(VRSPH_VERSION));
  app.require_subcommand(1);
  CliArgs args;
  add_run_command(app, args);
  CLI::App* check = add_check_command(app, args);
  CLI::App* bench = add_bench_command(app, args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    fmt::print(stderr, "vrsph: {}\n", e.what());
    return kExitBadInput;
  }
  if (const char* launch = std::getenv("VRSPH_LAUNCH")) {  // exec/launch_tuner.hpp
    const auto policy = exec::launch_policy_named(launch);
    if (!policy) {
      fmt::print(stderr, "vrsph: VRSPH_LAUNCH = '{}': not one of tuned, team, alone\n", launch);
      return kExitBadInput;
    }
    exec::set_launch_policy(*policy);
  }
  if (*check) {
    return check_case(load_given_case(args.case_path, args.sets), origin_of(args, args.case_path));
  }
  if (*bench) return bench_command(args);
  return run_command(args);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return dispatch(argc, argv);
  } catch (const vrsph::CaseError& e) {  // CheckpointError and a held lock included
    fmt::print(stderr, "vrsph: {}\n", e.what());
    return vrsph::kExitBadInput;
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "vrsph: {}\n", e.what());
    return vrsph::kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "vrsph: error: {}\n", e.what());
    return vrsph::kExitIoError;
  }
}
