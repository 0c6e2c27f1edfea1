// SIGINT (Ctrl-C) and SIGTERM (kill, a batch system's time limit) during a run. The handler only
// records the signal; the time loop looks between steps and, when one came, writes a checkpoint
// and summary.json (completed = false) and ends with status 128 + the signal number, as a shell
// reports a command killed by it. A second signal of the same kind ends the process at once (the
// handler is reset after the first), leaving the last checkpoint.
#pragma once

#include <csignal>

namespace vrsph {

class StopSignals {
 public:
  // Installs the handlers of SIGINT and SIGTERM; the destructor puts the previous ones back.
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  // The signal received since construction (SIGINT or SIGTERM), 0 when none.
  int received() const;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

// "SIGINT", "SIGTERM", or "a signal".
const char* stop_signal_name(int sig);

}  // namespace vrsph
