#include "vrsph/driver/run_outputs.hpp"

#include <fmt/format.h>

#include "vrsph/analysis/laplace.hpp"
#include "vrsph/driver/checkpoint.hpp"
#include "vrsph/output/line_profile.hpp"
#include "vrsph/output/summary.hpp"
#include "vrsph/setup/geometry.hpp"

namespace vrsph {
namespace {

SeriesWriter open_series(const std::filesystem::path& path, bool fresh, double t) {
  return fresh ? SeriesWriter(path) : SeriesWriter::resume(path, t);
}

PvdCollection open_pvd(const std::filesystem::path& path, bool fresh, double t) {
  return fresh ? PvdCollection(path) : PvdCollection::load(path, t);
}

// Surface-tension and shifting fields as extra particle columns: lambda, normal, curvature
// (recomputed on the current state) and the last shifting displacement.
template <int D>
std::vector<ExtraField> surface_extras(Simulation<D>& sim) {
  std::vector<ExtraField> out;
  if (!sim.has_surface_fields()) return out;
  const SurfaceFields<D>& sf = sim.surface_fields_now();
  const auto& ps = sim.particles();
  const std::size_t n = ps.size();
  ExtraField lambda{"lambda", 1, sf.lambda};
  ExtraField normal{"normal", D, std::vector<double>(n * D)};
  ExtraField curvature{"curvature", 1, sf.curvature};
  ExtraField shift{"shift", D, std::vector<double>(n * D)};
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) {
      normal.values[i * D + k] = sf.normal[i][k];
      shift.values[i * D + k] = ps.shift[i][k];
    }
  out.push_back(std::move(lambda));
  out.push_back(std::move(normal));
  out.push_back(std::move(curvature));
  out.push_back(std::move(shift));
  return out;
}

}  // namespace

template <int D>
RunOutputs<D>::RunOutputs(const CaseSpec& spec, std::filesystem::path dir, bool fresh, double t)
    : spec_(spec),
      dir_(std::move(dir)),
      pvd_(open_pvd(dir_ / "particles.pvd", fresh, t)),
      series_(open_series(dir_ / "series.csv", fresh, t)) {}

template <int D>
void RunOutputs<D>::write(Simulation<D>& sim, int index) {
  sim.update_pressure();
  const ParticleSet<D>& ps = sim.particles();
  const std::span<const std::uint8_t> level;  // single level: all 0
  const std::vector<ExtraField> extra_fields = surface_extras(sim);
  const std::span<const ExtraField> extras(extra_fields);
  if (spec_.write_vtp) {
    const std::string name = snapshot_file_name(index, "vtp");
    write_vtp<D>(dir_ / name, ps, extras, level);
    pvd_.add(sim.time(), name);
    pvd_.write();
  }
  if (spec_.write_csv) write_particles_csv<D>(dir_ / snapshot_file_name(index, "csv"), ps, extras, level);
  for (const OutputLine& line : spec_.lines) {
    write_line_profile<D>(dir_ / line_file_name(line.name, index), ps, level, to_vec<D>(line.from),
                          to_vec<D>(line.to), 0.5 * spec_.dp);
  }
  series_.append(compute_series_row<D>(ps, sim.time(), static_cast<long>(sim.step_count()),
                                       sim.dt_last()));
  // Checkpoint: everything needed to continue bit for bit from this output time.
  Checkpoint ck;
  ck.put_scalar("time", sim.time());
  ck.put_scalar("dt_next", sim.dt_next());
  ck.put_scalar("dt_last", sim.dt_last());
  ck.put("step", std::vector<std::int64_t>{sim.step_count()});
  ck.put("output_index", std::vector<std::int64_t>{index});
  const RunCounters& c = sim.counters();
  ck.put("counters", std::vector<std::uint64_t>{c.particle_steps, c.pairs, c.lost_fluid,
                                                c.dt_limit_counts[0], c.dt_limit_counts[1],
                                                c.dt_limit_counts[2], c.dt_limit_counts[3],
                                                sim.initial_fluid()});
  ck.put_scalar("wall_seconds", c.wall_seconds);
  ck.put("levels", std::vector<std::int64_t>{1});
  ck.put_particles<D>(0, ps);
  ck.save(dir_ / "checkpoint.bin");
}

template <int D>
nlohmann::json RunOutputs<D>::summary(const Simulation<D>& sim, bool completed,
                                      double wall_seconds, int threads,
                                      const std::string& error) const {
  const RunCounters& c = sim.counters();
  const ParticleSet<D>& ps = sim.particles();
  nlohmann::json j;
  j["completed"] = completed;
  if (!error.empty()) j["error"] = error;
  j["case"] = spec_.name;
  j["dimension"] = D;
  j["steps"] = sim.step_count();
  j["sim_time"] = sim.time();
  j["wall_seconds"] = wall_seconds;
  j["particle_steps_per_second"] = wall_seconds > 0 ? c.particle_steps / wall_seconds : 0.0;
  j["pair_interactions_per_second"] = wall_seconds > 0 ? c.pairs / wall_seconds : 0.0;
  j["threads"] = threads;
  j["n_particles"] = {{"fluid", ps.count(Kind::fluid)},
                      {"wall", ps.count(Kind::wall)},
                      {"buffer", ps.count(Kind::buffer)}};
  j["lost_fluid"] = c.lost_fluid;
  nlohmann::json limits;
  for (std::size_t k = 0; k < kDtLimitNames.size(); ++k) {
    limits[std::string(kDtLimitNames[k])] = c.dt_limit_counts[k];
  }
  j["dt_limits"] = limits;
  j["c0"] = sim.setup().c0;
  j["h"] = sim.params().h;
  j["dp"] = spec_.dp;
  const PassTimes& t = sim.pass_times();
  j["pass_seconds"] = {{"sort", t.sort},     {"surface", t.surface}, {"forces", t.forces},
                       {"update", t.update}, {"checks", t.checks}};
  if (spec_.laplace_pressure && !spec_.lines.empty()) {
    const OutputLine& line = spec_.lines.front();
    const LaplaceError e = line_laplace_error<D>(ps, line, *spec_.laplace_pressure,
                                                 sim.params().h, spec_.dp);
    j["laplace"] = {{"expected", e.expected}, {"mean_interior", e.mean_interior},
                    {"rmse", e.rmse},         {"nrmse", e.nrmse},
                    {"rmse_all", e.rmse_all}, {"n_points", e.n_points},
                    {"line", line.name}};
  }
  return j;
}

template class RunOutputs<2>;
template class RunOutputs<3>;

}  // namespace vrsph
