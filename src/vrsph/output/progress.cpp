// Terminal progress line (see progress.hpp).
#include "vrsph/output/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace vrsph {
namespace {

constexpr double kRedrawSeconds = 0.25;

// "hh:mm:ss", or "--:--:--" when unknown.
std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "--:--:--";
  const long s = std::lround(seconds);
  return fmt::format("{:02d}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}

// "12.3 s" under a minute, "hh:mm:ss" beyond.
std::string duration_text(double seconds) {
  return seconds < 59.95 ? fmt::format("{:.1f} s", seconds) : clock_text(seconds);
}

int time_decimals(double end_time) {
  if (!(end_time > 0.0)) return 4;
  return std::clamp(static_cast<int>(std::ceil(-std::log10(end_time))) + 3, 4, 12);
}

}  // namespace

std::string output_time_line(const OutputTimeState& s) {
  const int decimals = time_decimals(s.end_time);
  return fmt::format(
      "t = {:.{}f} / {:.{}f} s  step {}  dt = {:.3e} s  {} particles  wall {}  ETA {}", s.t,
      decimals, s.end_time, decimals, s.step, s.dt, s.particles, duration_text(s.wall_seconds),
      clock_text(s.eta_seconds));
}

Progress::Progress(double end_time, bool enabled, std::FILE* out)
    : end_time_(end_time), enabled_(enabled), out_(out), decimals_(time_decimals(end_time)) {}

std::string Progress::line(double t, long step, double steps_per_sec, double eta) const {
  return fmt::format("  t = {:.{}f} / {:.{}f} s  step {}  {:.0f} steps/s  ETA {}", t, decimals_,
                     end_time_, decimals_, step, steps_per_sec, clock_text(eta));
}

double Progress::eta_seconds(Clock::time_point now) const {
  const double wall = std::chrono::duration<double>(now - start_wall_).count();
  const double advanced = t_ - start_t_;
  if (wall <= 0.0 || advanced <= 0.0) return -1.0;
  return std::max(0.0, end_time_ - t_) * wall / advanced;
}

void Progress::update(double t, long step, double steps_per_sec) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  if (!started_) {
    started_ = true;
    start_wall_ = now;
    start_t_ = t;
  }
  t_ = t;
  step_ = step;
  steps_per_sec_ = steps_per_sec;
  if (drawn_ && std::chrono::duration<double>(now - last_draw_).count() < kRedrawSeconds) return;
  draw(now);
}

void Progress::draw(Clock::time_point now) {
  const std::string text = line(t_, step_, steps_per_sec_, eta_seconds(now));
  const std::size_t pad = last_length_ > text.size() ? last_length_ - text.size() : 0;
  fmt::print(out_, "\r{}{:{}}", text, "", pad);
  std::fflush(out_);
  last_length_ = text.size();
  last_draw_ = now;
  drawn_ = true;
}

void Progress::finish() {
  if (!enabled_ || !started_) return;
  draw(Clock::now());
  fmt::print(out_, "\n");
  std::fflush(out_);
  drawn_ = false;
  started_ = false;
}

}  // namespace vrsph
