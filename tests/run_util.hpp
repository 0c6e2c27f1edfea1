// Stepping helpers for tests that drive a Simulation directly.
#pragma once

#include "vrsph/sim/simulation.hpp"

namespace vrsph::test {

// Steps to time t exactly (the last step shortened to land on it), as a CLI run lands on its
// outputs.
template <int D>
void run_to(Simulation<D>& sim, double t) {
  while (sim.time() < t) {
    sim.set_stop_time(t);
    sim.step();
  }
}

}  // namespace vrsph::test
