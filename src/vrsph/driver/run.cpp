#include "vrsph/driver/run.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "vrsph/driver/run_checkpoint.hpp"
#include "vrsph/driver/run_outputs.hpp"
#include "vrsph/driver/setup_limits.hpp"
#include "vrsph/exec/parallel.hpp"
#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/boxes_vtp.hpp"
#include "vrsph/output/progress.hpp"
#include "vrsph/output/summary.hpp"
#include "vrsph/setup/case_parser.hpp"

namespace vrsph {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The first output time after t: the next multiple of output.interval (or the end time when the
// interval is 0), never past the end time. Computed from the time, not from a snapshot count, so
// a resumed run may change the interval.
double next_output_time(const CaseSpec& spec, double t) {
  if (spec.output_interval <= 0.0) return spec.end_time;
  const double k = std::floor(t / spec.output_interval * (1.0 + 1e-12) + 1e-9) + 1.0;
  return std::min(k * spec.output_interval, spec.end_time);
}

// A fresh run refuses to overwrite an earlier run unless forced; forced, it removes the files a
// run writes (and nothing else) so no stale snapshot survives.
void prepare_out_dir(const std::filesystem::path& dir, bool force) {
  namespace fs = std::filesystem;
  if (fs::exists(dir / "case.toml") || fs::exists(dir / "checkpoint.bin")) {
    if (!force) {
      throw CaseError(
          fmt::format("--out {}: holds an earlier run (case.toml): use --force to overwrite it or "
                      "--resume to continue it",
                      dir.string()));
    }
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string n = e.path().filename().string();
      const bool ours = n.starts_with("particles_") || n.starts_with("line_") ||
                        n == "particles.pvd" || n == "series.csv" || n == "summary.json" ||
                        n == "case.toml" || n == "checkpoint.bin" || n == "refinement_boxes.vtp";
      if (ours && e.is_regular_file()) fs::remove(e.path());
    }
  }
  fs::create_directories(dir);
}

// The refinement boxes and both buffer edges of each, for ParaView.
template <int D>
void write_refinement_boxes(const Simulation<D>& sim, const std::filesystem::path& path) {
  std::vector<OutlineBox> boxes;
  auto outline = [&](const Box<D>& b, int level, int role) {
    OutlineBox o;
    for (int k = 0; k < D; ++k) {
      o.lo[static_cast<std::size_t>(k)] = b.lo[k];
      o.hi[static_cast<std::size_t>(k)] = b.hi[k];
    }
    o.level = level;
    o.role = role;
    boxes.push_back(o);
  };
  for (std::size_t l = 1; l < sim.level_count(); ++l) {
    const auto& r = sim.link(l).region;
    outline(r.box, static_cast<int>(l), 0);
    outline(r.box.grown(r.width), static_cast<int>(l), 1);
    for (const auto& c : sim.link(static_cast<std::size_t>(r.parent)).region.children)
      if (c.level == static_cast<int>(l)) outline(c.box.grown(-c.width), r.parent, 2);
  }
  write_boxes_vtp(path, boxes, D);
}

// The start and end lines of a run (not with --quiet).
template <int D>
void print_start(const CaseSpec& spec, const Simulation<D>& sim, const RunOptions& opt,
                 int threads) {
  fmt::print(
      "vrsph: {} ({}D): {} fluid + {} wall particles, dp = {:g} m, h = {:g} m, c0 = {:.4g} m/s, "
      "{} thread(s), output in {}{}\n",
      spec.name, D, sim.count(Kind::fluid), sim.count(Kind::wall), spec.dp, sim.params().h,
      sim.setup().c0, threads, opt.out_dir.string(),
      opt.resume ? fmt::format(" (resumed at t = {:g} s)", sim.time()) : "");
  std::fflush(stdout);
}

template <int D>
void print_end(const Simulation<D>& sim, double wall) {
  const RunCounters& c = sim.counters();
  fmt::print(
      "vrsph: done: t = {:g} s in {} steps, {:.1f} s wall, {:.3g} M particle-steps/s, "
      "{:.3g} M pair interactions/s\n",
      sim.time(), sim.step_count(), wall, c.particle_steps / wall / 1e6, c.pairs / wall / 1e6);
}

template <int D>
int run_impl(CaseSpec& spec, const RunOptions& opt) {
  Simulation<D> sim(spec, opt.cells_per_support);  // fills spec.max_speed when derived
  int index = 0;
  if (opt.resume) {
    const RunState state =
        restore_checkpoint(sim, Checkpoint::load(opt.out_dir / "checkpoint.bin"));
    index = static_cast<int>(state.output_index) + 1;
    if (sim.time() >= spec.end_time) {
      throw CaseError(fmt::format(
          "case.end_time = {}: the run in {} already reached t = {} s (raise it with --set "
          "case.end_time=T)",
          spec.end_time, opt.out_dir.string(), sim.time()));
    }
  }
  write_file_atomic(opt.out_dir / "case.toml", case_to_toml(spec));
  if (sim.level_count() > 1) write_refinement_boxes(sim, opt.out_dir / "refinement_boxes.vtp");
  RunOutputs<D> out(spec, opt.out_dir, !opt.resume, sim.time());
  const int threads = exec::thread_count();
  if (!opt.quiet) print_start(spec, sim, opt, threads);
  const auto t0 = std::chrono::steady_clock::now();
  const double wall_before = sim.counters().wall_seconds;
  if (!opt.resume) {
    out.write(sim, index);
    if (index++ == opt.halt_after_output) std::_Exit(kExitHalted);
  }
  Progress progress(spec.end_time, !opt.quiet && isatty(STDOUT_FILENO));
  std::string error;
  try {
    double t_out = next_output_time(spec, sim.time());
    while (sim.time() < spec.end_time) {
      sim.set_stop_time(t_out);
      sim.step();
      const double elapsed = seconds_since(t0);
      sim.counters().wall_seconds = wall_before + elapsed;
      if (sim.time() >= t_out) {
        out.write(sim, index);
        if (index++ == opt.halt_after_output) std::_Exit(kExitHalted);
        t_out = next_output_time(spec, sim.time());
      }
      progress.update(sim.time(), static_cast<long>(sim.step_count()),
                      elapsed > 0 ? sim.step_count() / elapsed : 0.0);
    }
  } catch (const InstabilityError& e) {
    error = e.what();
  }
  progress.finish();
  const double wall = wall_before + seconds_since(t0);
  write_summary_json(opt.out_dir / "summary.json",
                     out.summary(sim, error.empty(), wall, threads, error));
  if (!error.empty()) {
    fmt::print(stderr, "vrsph: {} (outputs up to snapshot {} kept in {})\n", error, index - 1,
               opt.out_dir.string());
    return kExitUnstable;
  }
  if (!opt.quiet) print_end(sim, wall);
  return kExitOk;
}

}  // namespace

int run_case(CaseSpec spec, const RunOptions& opt) {
  if (opt.threads > 0) exec::set_thread_count(opt.threads);
  preflight_case(spec, opt.origin);  // before the output folder and any particle
  if (!opt.resume) prepare_out_dir(opt.out_dir, opt.force);
  return spec.dimension == 2 ? run_impl<2>(spec, opt) : run_impl<3>(spec, opt);
}

}  // namespace vrsph
