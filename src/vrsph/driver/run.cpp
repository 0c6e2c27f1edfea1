#include "vrsph/driver/run.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "vrsph/driver/run_checkpoint.hpp"
#include "vrsph/driver/run_outputs.hpp"
#include "vrsph/driver/run_report.hpp"
#include "vrsph/driver/setup_limits.hpp"
#include "vrsph/driver/stop_signals.hpp"
#include "vrsph/exec/parallel.hpp"
#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/boxes_vtp.hpp"
#include "vrsph/output/build_info.hpp"
#include "vrsph/output/run_lock.hpp"
#include "vrsph/output/summary.hpp"
#include "vrsph/setup/case_parser.hpp"

namespace vrsph {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The first output time after t: the next multiple of output.interval (or the end time when the
// interval is 0), never past the end time. Computed from the time, not from a snapshot count, so
// a resumed run may change the interval.
double next_output_time(const CaseSpec& spec, double t) {
  if (spec.output_interval <= 0.0) return spec.end_time;
  const double k = std::floor(t / spec.output_interval * (1.0 + 1e-12) + 1e-9) + 1.0;
  return std::min(k * spec.output_interval, spec.end_time);
}

// The files a run writes (and --force removes).
bool is_run_file(const std::string& n) {
  return n.starts_with("particles_") || n.starts_with("line_") || n.starts_with("probe_") ||
         n == "particles.pvd" || n == "series.csv" || n == "summary.json" || n == "case.toml" ||
         n == "checkpoint.bin" || n == "refinement_boxes.vtp" || n == RunLog::kFileName;
}

// A fresh run (its folder locked) refuses to overwrite an earlier run unless forced; forced, it
// removes the files a run writes (and nothing else) so no stale snapshot survives.
void prepare_out_dir(const fs::path& dir, bool force) {
  if (!fs::exists(dir / "case.toml") && !fs::exists(dir / "checkpoint.bin")) return;
  if (!force) {
    throw CaseError(
        fmt::format("--out {}: holds an earlier run (case.toml): use --force to overwrite it or "
                    "--resume to continue it",
                    dir.string()));
  }
  for (const auto& e : fs::directory_iterator(dir)) {
    if (is_run_file(e.path().filename().string()) && e.is_regular_file()) fs::remove(e.path());
  }
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

// The start and end lines of a run.
template <int D>
std::string start_text(const CaseSpec& spec, const Simulation<D>& sim, const RunOptions& opt,
                       int threads) {
  return fmt::format(
      "{} ({}D): {} fluid + {} wall particles, dp = {:g} m, h = {:g} m, c0 = {:.4g} m/s, "
      "{} thread(s), output in {}{}",
      spec.name, D, sim.count(Kind::fluid), sim.count(Kind::wall), spec.dp, sim.params().h,
      sim.setup().c0, threads, opt.out_dir.string(),
      opt.resume ? fmt::format(" (resumed at t = {:g} s)", sim.time()) : "");
}

template <int D>
std::string end_text(const Simulation<D>& sim, double wall) {
  const RunCounters& c = sim.counters();
  return fmt::format(
      "done: t = {:g} s in {} steps, {:.1f} s wall, {:.3g} M particle-steps/s, "
      "{:.3g} M pair interactions/s",
      sim.time(), sim.step_count(), wall, c.particle_steps / wall / 1e6, c.pairs / wall / 1e6);
}

// The checkpoint of a resumed run, checked against the case before anything is built.
Checkpoint load_resume_checkpoint(const CaseSpec& spec, const fs::path& dir) {
  const fs::path path = dir / "checkpoint.bin";
  Checkpoint ck = Checkpoint::load(path);
  check_case(ck, spec, path);
  return ck;
}

// Puts the checkpoint into `sim`; returns the index of the next snapshot.
template <int D>
int resume_from(Simulation<D>& sim, const Checkpoint& ck, const CaseSpec& spec,
                const fs::path& dir) {
  const RunState state = restore_checkpoint(sim, ck);
  if (sim.time() >= spec.end_time) {
    throw CaseError(fmt::format(
        "case.end_time = {}: the run in {} already reached t = {} s (raise it with --set "
        "case.end_time=T)",
        spec.end_time, dir.string(), sim.time()));
  }
  return static_cast<int>(state.output_index) + 1;
}

// The time loop of a built (or restored) simulation: outputs, the progress, stop signals and
// the summary at the end.
template <int D>
class TimeLoop {
 public:
  TimeLoop(const CaseSpec& spec, const RunOptions& opt, RunReport& report, Simulation<D>& sim,
           RunOutputs<D>& out, int index)
      : spec_(spec),
        opt_(opt),
        report_(report),
        sim_(sim),
        out_(out),
        index_(index),
        threads_(exec::thread_count()),
        wall_before_(sim.counters().wall_seconds) {}

  // Runs to the end time, an instability or a stop signal; returns the exit status.
  int run(const StopSignals& signals) {
    report_.start(start_text(spec_, sim_, opt_, threads_), sim_.time());
    if (!opt_.resume) write_output();
    std::string error;
    try {
      double t_out = next_output_time(spec_, sim_.time());
      while (sim_.time() < spec_.end_time) {
        if (const int sig = signals.received()) return stop(sig);
        sim_.set_stop_time(t_out);
        sim_.step();
        sim_.counters().wall_seconds = wall();
        if (sim_.time() >= t_out) {
          write_output();
          t_out = next_output_time(spec_, sim_.time());
        }
        const double elapsed = seconds_since(t0_);
        report_.step(sim_.time(), static_cast<long>(sim_.step_count()),
                     elapsed > 0 ? sim_.step_count() / elapsed : 0.0);
      }
    } catch (const InstabilityError& e) {
      error = e.what();
    }
    return finish(error);
  }

 private:
  double wall() const { return wall_before_ + seconds_since(t0_); }

  void write_output() {
    out_.write(sim_, index_);
    OutputTimeState s;
    s.t = sim_.time();
    s.end_time = spec_.end_time;
    s.step = static_cast<long>(sim_.step_count());
    s.dt = sim_.dt_last();
    for (std::size_t l = 0; l < sim_.level_count(); ++l) s.particles += sim_.level(l).ps.size();
    s.wall_seconds = wall();
    report_.output(s);
    if (index_++ == opt_.halt_after_output) std::_Exit(kExitHalted);
  }

  // A stop signal: the checkpoint of the current step and the summary, then 128 + signal.
  int stop(int sig) {
    out_.write_checkpoint(sim_, index_ - 1);
    nlohmann::json summary = out_.summary(sim_, false, wall(), threads_, "");
    summary["stopped_by"] = stop_signal_name(sig);
    write_summary_json(opt_.out_dir / "summary.json", summary);
    report_.failure(fmt::format(
        "stopped by {} at t = {:g} s, step {}: checkpoint.bin and summary.json (completed = "
        "false) written; continue with: vrsph run --resume {}",
        stop_signal_name(sig), sim_.time(), sim_.step_count(), opt_.out_dir.string()));
    return kExitSignalBase + sig;
  }

  int finish(const std::string& error) {
    const double w = wall();
    write_summary_json(opt_.out_dir / "summary.json",
                       out_.summary(sim_, error.empty(), w, threads_, error));
    if (!error.empty()) {
      report_.failure(fmt::format("{} (outputs up to snapshot {} kept in {})", error, index_ - 1,
                                  opt_.out_dir.string()));
      return kExitUnstable;
    }
    report_.end(end_text(sim_, w));
    return kExitOk;
  }

  const CaseSpec& spec_;
  const RunOptions& opt_;
  RunReport& report_;
  Simulation<D>& sim_;
  RunOutputs<D>& out_;
  int index_;  // of the next snapshot
  int threads_;
  double wall_before_;  // s, of the earlier parts of a resumed run
  Clock::time_point t0_ = Clock::now();
};

template <int D>
int run_impl(CaseSpec& spec, const RunOptions& opt, RunReport& report, const StopSignals& signals) {
  Checkpoint ck;
  if (opt.resume) ck = load_resume_checkpoint(spec, opt.out_dir);
  Simulation<D> sim(spec, opt.cells);  // fills spec.max_speed when derived
  const int index = opt.resume ? resume_from(sim, ck, spec, opt.out_dir) : 0;
  ck = Checkpoint{};
  write_file_atomic(opt.out_dir / "case.toml", case_to_toml(spec));
  if (sim.level_count() > 1) write_refinement_boxes(sim, opt.out_dir / "refinement_boxes.vtp");
  RunOutputs<D> out(spec, opt.out_dir, !opt.resume, sim.time());
  TimeLoop<D> loop(spec, opt, report, sim, out, index);
  return loop.run(signals);
}

// The notices of a locked folder: a stale lock taken over, leftovers of atomic writes removed.
void report_takeover(RunReport& report, const RunLock& lock, std::size_t temps,
                     const fs::path& dir) {
  if (!lock.stale_holder().empty()) {
    report.notice(fmt::format(
        "took over the stale lock of {}: that run is no longer running (killed or crashed)",
        lock.stale_holder()));
  }
  if (temps > 0) {
    report.notice(fmt::format("removed {} temporary file(s) left in {} by an interrupted write",
                              temps, dir.string()));
  }
}

}  // namespace

int run_case(CaseSpec spec, const RunOptions& opt) {
  if (opt.threads > 0) exec::set_thread_count(opt.threads);
  preflight_case(spec, opt.origin);  // before the output folder and any particle
  if (!opt.resume) fs::create_directories(opt.out_dir);
  const RunLock lock(opt.out_dir, opt.resume ? "--resume" : "--out");
  if (!opt.resume) prepare_out_dir(opt.out_dir, opt.force);
  const std::size_t temps = remove_temp_files(opt.out_dir);
  RunReport report(opt.out_dir, !opt.resume, opt.quiet, spec.end_time);
  report.record(fmt::format("vrsph {} (commit {}), pid {}: {}", program_version(), git_commit(),
                            ::getpid(), opt.resume ? "resume" : "run"));
  report_takeover(report, lock, temps, opt.out_dir);
  const StopSignals signals;
  try {
    return spec.dimension == 2 ? run_impl<2>(spec, opt, report, signals)
                               : run_impl<3>(spec, opt, report, signals);
  } catch (const std::exception& e) {
    report.record(fmt::format("failed: {}", e.what()));
    throw;
  }
}

}  // namespace vrsph
