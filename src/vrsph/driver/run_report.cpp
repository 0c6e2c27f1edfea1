// stdout, stderr and run.log of a run (see run_report.hpp).
#include "vrsph/driver/run_report.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace vrsph {

RunReport::RunReport(const std::filesystem::path& dir, bool fresh, bool quiet, double end_time)
    : log_(dir, fresh),
      quiet_(quiet),
      terminal_(::isatty(STDOUT_FILENO) != 0),
      progress_(end_time, !quiet && terminal_) {}

void RunReport::notice(const std::string& text) {
  log_.line(text);
  fmt::print("vrsph: {}\n", text);
  std::fflush(stdout);
}

void RunReport::start(const std::string& text, double t) {
  start_wall_ = Clock::now();
  start_t_ = t;
  line(text);
}

void RunReport::line(const std::string& text) {
  log_.line(text);
  if (quiet_) return;
  fmt::print("vrsph: {}\n", text);
  std::fflush(stdout);
}

void RunReport::end(const std::string& text) {
  progress_.finish();
  line(text);
}

void RunReport::failure(const std::string& text) {
  progress_.finish();
  log_.line(text);
  fmt::print(stderr, "vrsph: {}\n", text);
}

void RunReport::record(const std::string& text) { log_.line(text); }

void RunReport::output(OutputTimeState s) {
  const double wall = std::chrono::duration<double>(Clock::now() - start_wall_).count();
  if (s.t > start_t_ && wall > 0.0) s.eta_seconds = (s.end_time - s.t) * wall / (s.t - start_t_);
  const std::string text = output_time_line(s);
  log_.line(text);
  if (quiet_ || terminal_) return;
  fmt::print("  {}\n", text);
  std::fflush(stdout);
}

void RunReport::step(double t, long step, double steps_per_sec) {
  progress_.update(t, step, steps_per_sec);
}

}  // namespace vrsph
