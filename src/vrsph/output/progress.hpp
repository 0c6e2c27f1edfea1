// The progress line shown on a terminal while a run goes:
//   "\r  t = 0.0123 / 0.2000 s  step 1234  540 steps/s  ETA 00:01:23"
// redrawn at most 4 times per second. The caller decides whether to show it
// (enabled = !quiet && isatty(stdout)); when disabled every call does nothing.
// Off a terminal (a batch job, a pipe) a run prints instead one line per output time,
// output_time_line(), which also goes to run.log.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace vrsph {

// What the line of an output time shows.
struct OutputTimeState {
  double t = 0.0;         // s
  double end_time = 0.0;  // s
  long step = 0;
  double dt = 0.0;  // s, the last step
  std::size_t particles = 0;
  double wall_seconds = 0.0;  // of the run so far, earlier parts of a resumed run included
  double eta_seconds = -1.0;  // < 0: not known yet
};

// "t = 0.0050 / 0.0200 s  step 43  dt = 1.163e-04 s  1937 particles  wall 0.6 s  ETA 00:00:02"
// (wall in hh:mm:ss beyond a minute)
std::string output_time_line(const OutputTimeState& s);

class Progress {
 public:
  Progress(double end_time, bool enabled, std::FILE* out = stdout);

  // Records the current state; redraws the line if 0.25 s have passed since the last redraw
  // (the first call always draws). The ETA comes from the simulated time advanced per wall
  // second since the first call.
  void update(double t, long step, double steps_per_sec);
  // Draws the last state once more and ends the line (only if anything was drawn).
  void finish();

  // The text of the line for a state (no "\r"); exposed for tests.
  std::string line(double t, long step, double steps_per_sec, double eta_seconds) const;

 private:
  using Clock = std::chrono::steady_clock;
  void draw(Clock::time_point now);
  double eta_seconds(Clock::time_point now) const;

  double end_time_;
  bool enabled_;
  std::FILE* out_;
  int decimals_;  // digits after the point for times, enough to show end_time to 3 digits
  bool started_ = false;
  bool drawn_ = false;
  Clock::time_point start_wall_{};
  Clock::time_point last_draw_{};
  double start_t_ = 0.0;
  double t_ = 0.0;
  long step_ = 0;
  double steps_per_sec_ = 0.0;
  std::size_t last_length_ = 0;  // to blank out leftovers of a longer previous line
};

}  // namespace vrsph
