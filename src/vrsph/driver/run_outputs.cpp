#include "vrsph/driver/run_outputs.hpp"

#include <fmt/format.h>

#include <limits>

#include "vrsph/analysis/laplace.hpp"
#include "vrsph/core/to_vec.hpp"
#include "vrsph/driver/fluid_samples.hpp"
#include "vrsph/driver/level_samples.hpp"
#include "vrsph/driver/run_checkpoint.hpp"
#include "vrsph/output/build_info.hpp"
#include "vrsph/output/line_profile.hpp"
#include "vrsph/output/summary.hpp"
#include "vrsph/setup/case_keys.hpp"
#include "vrsph/setup/geometry.hpp"

namespace vrsph {
namespace {

SeriesWriter open_series(const std::filesystem::path& path, bool fresh, double t,
                         std::vector<std::string> extra) {
  return fresh ? SeriesWriter(path, std::move(extra))
               : SeriesWriter::resume(path, t, std::move(extra));
}

PvdCollection open_pvd(const std::filesystem::path& path, bool fresh, double t) {
  return fresh ? PvdCollection(path) : PvdCollection::load(path, t);
}

// Surface-tension and shifting fields as extra particle columns: lambda, normal, curvature
// (recomputed on the current state) and the last shifting displacement; levels one after the
// other, in the order of the merged snapshot.
template <int D>
std::vector<ExtraField> surface_extras(Simulation<D>& sim) {
  std::vector<ExtraField> out;
  if (!sim.has_surface_fields()) return out;
  ExtraField lambda{"lambda", 1, {}};
  ExtraField normal{"normal", D, {}};
  ExtraField curvature{"curvature", 1, {}};
  ExtraField shift{"shift", D, {}};
  sim.update_surface_fields();
  for (std::size_t l = 0; l < sim.level_count(); ++l) {
    const SurfaceFields<D>& sf = sim.surface_fields(l);
    const auto& ps = sim.level(l).ps;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      lambda.values.push_back(sf.lambda[i]);
      curvature.values.push_back(sf.curvature.empty() ? 0.0 : sf.curvature[i]);
      for (int k = 0; k < D; ++k) {
        normal.values.push_back(sf.normal.empty() ? 0.0 : sf.normal[i][k]);
        shift.values.push_back(ps.keeps_shift ? ps.shift[i][k] : 0.0);
      }
    }
  }
  out.push_back(std::move(lambda));
  out.push_back(std::move(normal));
  out.push_back(std::move(curvature));
  out.push_back(std::move(shift));
  return out;
}

// With analysis.laplace_pressure and a line: the summary's Laplace figures at every output, so
// that a run's RMSE can be followed in time (at one instant it moves with the drop's shape
// oscillations).
bool has_laplace(const CaseSpec& spec) { return spec.laplace_pressure && !spec.lines.empty(); }

// Series columns added with variable resolution: per-level counts, fluid masses and the mass
// held by the level's mass points (accumulated from the flux, not yet a particle), and the
// particles created and deleted at the interfaces so far.
void add_level_columns(std::vector<SeriesExtraColumn>& c, std::size_t levels) {
  if (levels < 2) return;
  for (std::size_t l = 0; l < levels; ++l) {
    c.push_back({fmt::format("n_fluid_L{}", l),
                 [l](const SeriesInputs& in) { return double(in.levels[l].n_fluid); }});
    c.push_back({fmt::format("n_buffer_L{}", l),
                 [l](const SeriesInputs& in) { return double(in.levels[l].n_buffer); }});
    c.push_back({fmt::format("mass_fluid_L{}", l),
                 [l](const SeriesInputs& in) { return in.levels[l].mass_fluid; }});
    c.push_back({fmt::format("mass_stored_L{}", l),
                 [l](const SeriesInputs& in) { return in.mass_stored[l]; }});
  }
  c.push_back({"created", [](const SeriesInputs& in) { return double(in.counters->created); }});
  c.push_back({"deleted", [](const SeriesInputs& in) { return double(in.counters->deleted); }});
  c.push_back({"created_mass", [](const SeriesInputs& in) { return in.counters->created_mass; }});
  c.push_back({"deleted_mass", [](const SeriesInputs& in) { return in.counters->deleted_mass; }});
}

// The Laplace figures, NaN when no particle lies on the line.
double laplace_value(const SeriesInputs& in, double LaplaceError::*f) {
  return in.laplace.n_points > 0 ? in.laplace.*f : std::numeric_limits<double>::quiet_NaN();
}

// The interpolated line's Laplace figures, NaN when no point of the line lies in the fluid.
double laplace_interp_value(const SeriesInputs& in, double LaplaceError::*f) {
  return in.laplace_interp.n_points > 0 ? in.laplace_interp.*f
                                        : std::numeric_limits<double>::quiet_NaN();
}

// wall<N>_fx, wall<N>_fy[, wall<N>_fz]: the fluid's force on each wall block.
void add_wall_columns(std::vector<SeriesExtraColumn>& c, std::size_t blocks, int dim) {
  for (std::size_t b = 0; b < blocks; ++b) {
    for (int k = 0; k < dim; ++k) {
      c.push_back({fmt::format("wall{}_f{}", b, "xyz"[k]), [b, k](const SeriesInputs& in) {
                     return in.wall_forces[b][static_cast<std::size_t>(k)];
                   }});
    }
  }
}

std::vector<SeriesExtraColumn> extra_columns(const CaseSpec& spec) {
  std::vector<SeriesExtraColumn> c;
  // With surface tension: a drop's shape oscillation and parasitic currents, whether it moves or
  // not (kinetic_energy also holds its translation).
  if (spec.fluid.surface_tension > 0.0)
    c.push_back({"kinetic_energy_cm", [](const SeriesInputs& in) { return in.kinetic_energy_cm; }});
  add_level_columns(c, spec.refinements.size() + 1);
  add_wall_columns(c, spec.wall_blocks.size(), spec.dimension);
  if (has_laplace(spec)) {
    c.push_back({"laplace_mean_interior", [](const SeriesInputs& in) {
                   return laplace_value(in, &LaplaceError::mean_interior);
                 }});
    c.push_back({"laplace_rmse",
                 [](const SeriesInputs& in) { return laplace_value(in, &LaplaceError::rmse); }});
    c.push_back({"laplace_interp_mean_interior", [](const SeriesInputs& in) {
                   return laplace_interp_value(in, &LaplaceError::mean_interior);
                 }});
    c.push_back({"laplace_interp_rmse", [](const SeriesInputs& in) {
                   return laplace_interp_value(in, &LaplaceError::rmse);
                 }});
  }
  return c;
}

template <int D>
std::vector<ProbeWriter<D>> open_probes(const CaseSpec& spec, const std::filesystem::path& dir,
                                        bool fresh, double t) {
  std::vector<ProbeWriter<D>> out;
  for (const OutputProbe& p : spec.probes) {
    const std::filesystem::path path = dir / probe_file_name(p.name);
    out.push_back(fresh ? ProbeWriter<D>(path) : ProbeWriter<D>::resume(path, t));
  }
  return out;
}

std::vector<std::string> column_names(const std::vector<SeriesExtraColumn>& columns) {
  std::vector<std::string> names;
  for (const SeriesExtraColumn& c : columns) names.push_back(c.name);
  return names;
}

// The Laplace error on the first line (summary.json's `laplace`).
template <int D>
LaplaceError first_line_laplace(const Simulation<D>& sim, const CaseSpec& spec) {
  return levels_laplace_error(sim, spec.lines.front(), *spec.laplace_pressure);
}

// The same on the first line's interpolated points.
template <int D>
LaplaceError first_line_interp_laplace(const Simulation<D>& sim, const CaseSpec& spec) {
  const auto points = interpolate_line(sim, spec.lines.front());
  return interp_laplace_error<D>(sim, points, *spec.laplace_pressure);
}

// summary.json's `laplace`: the particle strip's figures, then the interpolated line's.
template <int D>
nlohmann::json laplace_json(const Simulation<D>& sim, const CaseSpec& spec) {
  const LaplaceError e = first_line_laplace(sim, spec);
  const LaplaceError ei = first_line_interp_laplace(sim, spec);
  return {{"expected", e.expected},
          {"mean_interior", e.mean_interior},
          {"rmse", e.rmse},
          {"nrmse", e.nrmse},
          {"rmse_all", e.rmse_all},
          {"n_points", e.n_points},
          {"line", spec.lines.front().name},
          {"interp_mean_interior", ei.mean_interior},
          {"interp_rmse", ei.rmse},
          {"interp_nrmse", ei.nrmse},
          {"interp_rmse_all", ei.rmse_all},
          {"interp_n_points", ei.n_points}};
}

// The particle sets of every level, in level order.
template <int D>
std::vector<const ParticleSet<D>*> level_sets(const Simulation<D>& sim) {
  std::vector<const ParticleSet<D>*> sets;
  for (std::size_t l = 0; l < sim.level_count(); ++l) sets.push_back(&sim.level(l).ps);
  return sets;
}

}  // namespace

template <int D>
RunOutputs<D>::RunOutputs(const CaseSpec& spec, std::filesystem::path dir, bool fresh, double t)
    : spec_(spec),
      dir_(std::move(dir)),
      case_text_(physical_case_text(spec)),
      pvd_(open_pvd(dir_ / "particles.pvd", fresh, t)),
      extras_(extra_columns(spec)),
      series_(open_series(dir_ / "series.csv", fresh, t, column_names(extras_))),
      probes_(open_probes<D>(spec, dir_, fresh, t)) {}

template <int D>
void RunOutputs<D>::write(Simulation<D>& sim, int index) {
  write_snapshot(sim, index);
  SeriesInputs in;
  write_lines(sim, index, in);
  for (std::size_t k = 0; k < probes_.size(); ++k)
    probes_[k].append(sim.time(), sample_fluid(sim, to_vec<D>(spec_.probes[k].position)));
  append_series(sim, in);
  write_checkpoint(sim, index);
}

// All levels in one snapshot (the `level` column tells them apart).
template <int D>
void RunOutputs<D>::write_snapshot(Simulation<D>& sim, int index) {
  const std::size_t nl = sim.level_count();
  MergedLevels<D> merged;
  if (nl > 1) merged = merge_levels<D>(level_sets(sim));
  const ParticleSet<D>& ps = nl > 1 ? merged.particles : sim.particles();
  const std::span<const std::uint8_t> level(merged.level);  // empty: single level, all 0
  const std::vector<ExtraField> extra_fields = surface_extras(sim);
  const TaitEos& eos = sim.params().eos;  // one EOS for all levels (sim/level_setup.cpp)
  const std::span<const ExtraField> extras(extra_fields);
  SnapshotFormat format;
  format.float32 = spec_.output_precision == OutputPrecision::float32;
  format.zlib = spec_.output_compression == OutputCompression::zlib;
  if (spec_.write_vtp) {
    const std::string name = snapshot_file_name(index, "vtp");
    write_vtp<D>(dir_ / name, ps, eos, extras, level, format);
    pvd_.add(sim.time(), name);
    pvd_.write();
  }
  if (spec_.write_csv)
    write_particles_csv<D>(dir_ / snapshot_file_name(index, "csv"), ps, eos, extras, level, format);
}

template <int D>
void RunOutputs<D>::write_lines(const Simulation<D>& sim, int index, SeriesInputs& in) const {
  for (std::size_t k = 0; k < spec_.lines.size(); ++k) {
    const OutputLine& line = spec_.lines[k];
    const auto samples = sample_levels(sim, line);
    write_line_samples<D>(dir_ / line_file_name(line.name, index), samples);
    const auto points = interpolate_line(sim, line);
    write_line_interp<D>(dir_ / line_interp_file_name(line.name, index), points);
    if (k > 0 || !has_laplace(spec_)) continue;
    in.laplace = levels_laplace_error(sim, line, *spec_.laplace_pressure);
    in.laplace_interp = interp_laplace_error<D>(sim, points, *spec_.laplace_pressure);
  }
}

// The series row: the fixed columns summed over levels, then the extra columns in list order.
template <int D>
void RunOutputs<D>::append_series(const Simulation<D>& sim, SeriesInputs& in) {
  in.counters = &sim.counters();
  for (const Vec<D>& f : sim.wall_block_forces()) {
    std::array<double, 3> a{};
    for (int k = 0; k < D; ++k) a[static_cast<std::size_t>(k)] = f[k];
    in.wall_forces.push_back(a);
  }
  in.kinetic_energy_cm = centre_of_mass_kinetic_energy<D>(level_sets(sim));
  SeriesRow row;
  for (std::size_t l = 0; l < sim.level_count(); ++l) {
    double stored = 0.0;
    for (const MassPoint<D>& p : sim.link(l).mass_points) stored += p.mass;
    in.mass_stored.push_back(stored);
    in.levels.push_back(compute_series_row<D>(sim.level(l).ps, sim.time(),
                                              static_cast<long>(sim.step_count()), sim.dt_last()));
    if (l == 0)
      row = in.levels[0];
    else
      accumulate_series_row(row, in.levels[l]);
  }
  for (const SeriesExtraColumn& c : extras_) row.extra.push_back(c.value(in));
  series_.append(row);
}

// Everything needed to continue bit for bit from this state.
template <int D>
void RunOutputs<D>::write_checkpoint(const Simulation<D>& sim, int index) const {
  Checkpoint ck = make_checkpoint(sim, index);
  put_case(ck, case_text_);
  ck.save(dir_ / "checkpoint.bin");
}

template <int D>
nlohmann::json RunOutputs<D>::summary(const Simulation<D>& sim, bool completed, double wall_seconds,
                                      int threads, const std::string& error) const {
  const RunCounters& c = sim.counters();
  nlohmann::json j;
  j["completed"] = completed;
  if (!error.empty()) j["error"] = error;
  j["version"] = std::string(program_version());
  j["git_commit"] = std::string(git_commit());
  j["case"] = spec_.name;
  j["dimension"] = D;
  j["steps"] = sim.step_count();
  j["sim_time"] = sim.time();
  j["wall_seconds"] = wall_seconds;
  j["particle_steps_per_second"] = wall_seconds > 0 ? c.particle_steps / wall_seconds : 0.0;
  j["pair_interactions_per_second"] = wall_seconds > 0 ? c.pairs / wall_seconds : 0.0;
  j["threads"] = threads;
  j["n_particles"] = {{"fluid", sim.count(Kind::fluid)},
                      {"wall", sim.count(Kind::wall)},
                      {"buffer", sim.count(Kind::buffer)}};
  if (sim.level_count() > 1) {
    nlohmann::json levels = nlohmann::json::array();
    for (std::size_t l = 0; l < sim.level_count(); ++l) {
      const auto& L = sim.level(l);
      levels.push_back({{"dp", L.prm.dp},
                        {"h", L.prm.h},
                        {"fluid", L.ps.count(Kind::fluid)},
                        {"buffer", L.ps.count(Kind::buffer)},
                        {"wall", L.ps.count(Kind::wall)}});
    }
    j["levels"] = levels;
    j["vres"] = {{"created", c.created},
                 {"deleted", c.deleted},
                 {"created_mass", c.created_mass},
                 {"deleted_mass", c.deleted_mass}};
  }
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
                       {"update", t.update}, {"checks", t.checks},   {"coupling", t.coupling}};
  if (has_laplace(spec_)) j["laplace"] = laplace_json(sim, spec_);
  return j;
}

template class RunOutputs<2>;
template class RunOutputs<3>;

}  // namespace vrsph
