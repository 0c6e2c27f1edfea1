// `vrsph check` (set-up report without a run) and `vrsph bench` (timed run without outputs).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "vrsph/driver/run.hpp"
#include "vrsph/driver/setup_limits.hpp"
#include "vrsph/exec/parallel.hpp"
#include "vrsph/output/summary.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {
namespace {

// The estimate made before filling (preflight), with the memory it is checked against.
void print_estimate(const SetupEstimate& e, const SetupOrigin& origin) {
  const auto mem = available_memory_bytes();
  const double mib = 1024.0 * 1024.0;
  fmt::print(
      "  estimate before filling: about {:.0f} particles, {:.0f} MiB of memory ({}{})\n",
      e.particles, e.bytes / mib,
      mem ? fmt::format("{:.0f} MiB available", *mem / mib) : "memory available unknown",
      origin.max_particles ? fmt::format(", --max-particles {:.0f}", *origin.max_particles) : "");
  if (e.levels.size() < 2) return;
  for (std::size_t k = 0; k < e.levels.size(); ++k) {
    fmt::print("    level {} fills the case at dp = {:g} m: about {:.0f} fluid + {:.0f} wall\n", k,
               e.levels[k].dp, e.levels[k].fluid, e.levels[k].wall);
  }
}

// The particle counts: all levels together, then (with refinement) each level's fluid, buffer
// and wall particles and mass points.
template <int D>
void print_particle_counts(const Simulation<D>& sim, const CaseSpec& spec) {
  const std::size_t nl = sim.level_count();
  if (nl == 1) {
    const auto& ps = sim.particles();
    fmt::print("  particles: {} fluid, {} wall ({} in all)\n", ps.count(Kind::fluid),
               ps.count(Kind::wall), ps.size());
  } else {
    fmt::print("  particles: {} fluid, {} buffer, {} wall ({} in all, {} levels)\n",
               sim.count(Kind::fluid), sim.count(Kind::buffer), sim.count(Kind::wall),
               sim.total_particles(), nl);
  }
  fmt::print("  dp = {:g} m, h = {:g} m ({:g} dp), particle mass = {:g} kg\n", spec.dp,
             sim.params().h, spec.h_over_dp, sim.params().mass);
  if (nl == 1) return;
  for (std::size_t l = 0; l < nl; ++l) {
    const auto& L = sim.level(l);
    const std::string where =
        l == 0 ? std::string("base level")
               : fmt::format("inside refinement box, parent level {}", sim.link(l).region.parent);
    fmt::print(
        "  level {} ({}): dp = {:g} m, h = {:g} m, {} fluid, {} buffer, {} wall, "
        "{} mass points\n",
        l, where, L.prm.dp, L.prm.h, L.ps.count(Kind::fluid), L.ps.count(Kind::buffer),
        L.ps.count(Kind::wall), sim.link(l).mass_points.size());
  }
}

template <int D>
int check_impl(CaseSpec& spec, const SetupOrigin& origin) {
  const SetupEstimate estimate = preflight_case(spec, origin);
  Simulation<D> sim(spec);
  const auto& grid = sim.grid();
  fmt::print("case {} ({}D) is valid\n", spec.name, D);
  print_estimate(estimate, origin);
  print_particle_counts(sim, spec);
  fmt::print("  c0 = {:.6g} m/s (max_speed {:.6g} m/s), B = {:.6g} Pa\n", sim.setup().c0,
             sim.setup().max_speed, sim.params().eos.b);
  fmt::print("  first dt = {:.6g} s, about {:.0f} steps to t = {:g} s at that dt\n", sim.dt_next(),
             spec.end_time / sim.dt_next(), spec.end_time);
  std::string lo, hi;
  for (int k = 0; k < D; ++k) {
    lo += fmt::format("{}{:g}", k ? ", " : "", grid.domain_min()[k]);
    hi += fmt::format("{}{:g}", k ? ", " : "", grid.domain_max()[k]);
  }
  fmt::print("  domain [{}] .. [{}] m, {} cells of {:g} m\n", lo, hi, grid.cell_count(),
             grid.cell_size());
  return kExitOk;
}

// A field of /proc/self/status in bytes (VmRSS: resident now, VmHWM: the peak), 0 if unknown.
std::uint64_t status_bytes(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(field + ":", 0) == 0) return std::stoull(line.substr(field.size() + 1)) * 1024;
  }
  return 0;
}

template <int D>
int bench_impl(CaseSpec& spec, const BenchOptions& opt) {
  spec.end_time = opt.sim_time;
  preflight_case(spec, opt.origin);
  const std::uint64_t rss_before = status_bytes("VmRSS");
  Simulation<D> sim(spec, opt.cells);
  const int threads = exec::thread_count();
  const auto t0 = std::chrono::steady_clock::now();
  while (sim.time() < opt.sim_time * (1 - 1e-9)) sim.step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const RunCounters& c = sim.counters();
  const PassTimes& t = sim.pass_times();
  const double accounted = t.sort + t.surface + t.forces + t.update + t.checks;
  nlohmann::json j;
  j["case"] = spec.name;
  j["particles"] = sim.total_particles();
  j["threads"] = threads;
  j["sim_time"] = sim.time();
  j["steps"] = sim.step_count();
  j["wall_seconds"] = wall;
  j["steps_per_second"] = sim.step_count() / wall;
  j["particle_steps_per_second"] = c.particle_steps / wall;
  j["pair_interactions_per_second"] = c.pairs / wall;
  j["pairs_per_particle_step"] =
      static_cast<double>(c.pairs) / static_cast<double>(c.particle_steps);
  j["pass_share"] = {
      {"sort", t.sort / wall},       {"forces", t.forces / wall},
      {"surface", t.surface / wall}, {"update", t.update / wall},
      {"checks", t.checks / wall},   {"other", std::max(0.0, wall - accounted) / wall}};
  j["cells_per_support"] = sim.grid().reach();  // as resolved for the dimension
  j["cells_per_block"] = sim.grid().block_width();
  // Memory of the simulation: the peak resident size less what the program held before building
  // it (code, libraries, the case), per particle.
  const std::uint64_t peak = status_bytes("VmHWM");
  const double bytes_per_particle =
      peak > rss_before ? static_cast<double>(peak - rss_before) / sim.total_particles() : 0.0;
  j["peak_rss_bytes"] = peak;
  j["bytes_per_particle"] = bytes_per_particle;
  fmt::print("bench {}: {} particles, {} steps to t = {:g} s on {} thread(s) in {:.2f} s\n",
             spec.name, sim.total_particles(), sim.step_count(), sim.time(), threads, wall);
  // A speed means something only against another code run on the same machine (see
  // docs/validation.md), so no ratio to a figure taken elsewhere is printed.
  fmt::print("  {:.3f} M particle-steps/s, {:.1f} M pair interactions/s, {:.1f} steps/s\n",
             c.particle_steps / wall / 1e6, c.pairs / wall / 1e6, sim.step_count() / wall);
  fmt::print(
      "  time per pass: forces {:.1f}%, surface {:.1f}%, sort {:.1f}%, update {:.1f}%, "
      "checks {:.1f}%, other {:.1f}%\n",
      100 * t.forces / wall, 100 * t.surface / wall, 100 * t.sort / wall, 100 * t.update / wall,
      100 * t.checks / wall, 100 * std::max(0.0, wall - accounted) / wall);
  fmt::print("  {:.2f} pairs per particle-step, {:.0f} bytes per particle (peak resident)\n",
             j["pairs_per_particle_step"].get<double>(), bytes_per_particle);
  fmt::print("{}\n", j.dump());
  if (opt.json_out) write_summary_json(*opt.json_out, j);
  return kExitOk;
}

}  // namespace

int check_case(CaseSpec spec, const SetupOrigin& origin) {
  return spec.dimension == 2 ? check_impl<2>(spec, origin) : check_impl<3>(spec, origin);
}

int bench_case(CaseSpec spec, const BenchOptions& opt) {
  if (opt.threads > 0) exec::set_thread_count(opt.threads);
  return spec.dimension == 2 ? bench_impl<2>(spec, opt) : bench_impl<3>(spec, opt);
}

}  // namespace vrsph
