// What a run tells and where. run.log (in the output folder) always gets every line. On stdout:
// the start and end lines unless --quiet; on a terminal the redrawn progress line, off a
// terminal (batch jobs, pipes) one line per output time instead; notices (a stale lock taken
// over, leftover temporary files removed) always. Failures and stops go to stderr.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>

#include "vrsph/output/progress.hpp"
#include "vrsph/output/run_log.hpp"

namespace vrsph {

class RunReport {
 public:
  // fresh: start run.log, otherwise append to it.
  RunReport(const std::filesystem::path& dir, bool fresh, bool quiet, double end_time);

  void notice(const std::string& text);  // stdout and run.log, even with --quiet
  // The start line (stdout unless --quiet, and run.log) at simulated time t.
  void start(const std::string& text, double t);
  void end(const std::string& text);      // the same, after the progress line
  void failure(const std::string& text);  // stderr and run.log
  void record(const std::string& text);   // run.log only

  // At an output time: the line of output_time_line (ETA from the simulated time advanced per
  // wall second since the start line).
  void output(OutputTimeState s);
  // After each step: the progress line, on a terminal only.
  void step(double t, long step, double steps_per_sec);

 private:
  using Clock = std::chrono::steady_clock;
  RunLog log_;
  bool quiet_;
  bool terminal_;
  Progress progress_;
  void line(const std::string& text);  // stdout unless --quiet, and run.log
  Clock::time_point start_wall_ = Clock::now();
  double start_t_ = 0.0;
};

}  // namespace vrsph
