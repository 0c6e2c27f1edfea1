// Micro-benchmarks of the two hot passes on the benchmark geometry (cases/bench_dam_break_2d.toml
// at t = 0): one force evaluation and one cell sort + reorder. For the whole-run figures that
// are compared with DualSPHysics use `vrsph bench`.
//   ./build/release/bench/vrsph_microbench [--benchmark_filter=Forces]
#include <benchmark/benchmark.h>

#include "vrsph/setup/case_parser.hpp"
#include "vrsph/sim/simulation.hpp"
#include "vrsph/solver/forces.hpp"

namespace {

using namespace vrsph;

Simulation<2>& bench_simulation() {
  static CaseSpec spec = [] {
    return parse_case(
        load_case_table(std::string(VRSPH_SOURCE_DIR) + "/cases/bench_dam_break_2d.toml"),
        "bench_dam_break_2d.toml");
  }();
  static Simulation<2> sim(spec);
  return sim;
}

void Forces(benchmark::State& state) {
  Simulation<2>& sim = bench_simulation();
  ParticleSet<2> ps = sim.particles();
  ForceWorkspace<2> ws;
  std::uint64_t pairs = 0;
  for (auto _ : state) pairs += compute_forces(sim.params(), ps, sim.grid(), ws).pairs;
  state.counters["particles/s"] = benchmark::Counter(static_cast<double>(ps.size()),
                                                     benchmark::Counter::kIsIterationInvariantRate);
  state.counters["pairs/s"] =
      benchmark::Counter(static_cast<double>(pairs), benchmark::Counter::kIsRate);
}
BENCHMARK(Forces)->Unit(benchmark::kMillisecond)->UseRealTime();

void Sort(benchmark::State& state) {
  Simulation<2>& sim = bench_simulation();
  ParticleSet<2> ps = sim.particles();
  CellGrid<2> grid = sim.grid();
  for (auto _ : state) grid.sort(ps);
  state.counters["particles/s"] = benchmark::Counter(static_cast<double>(ps.size()),
                                                     benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(Sort)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
