#include "vrsph/driver/run_checkpoint.hpp"

#include <fmt/format.h>

#include <string>
#include <type_traits>
#include <vector>

#include "vrsph/driver/fnv_hash.hpp"
#include "vrsph/setup/case_keys.hpp"
#include "vrsph/setup/case_parser.hpp"

namespace vrsph {

void put_run_state(Checkpoint& ck, const RunState& s) {
  for_each_record(s, [&ck](const std::string& name, const auto& v) { ck.put_value(name, v); });
}

RunState get_run_state(const Checkpoint& ck) {
  RunState s;
  for_each_record(s, [&ck](const std::string& name, auto& v) {
    v = ck.value<std::decay_t<decltype(v)>>(name);
  });
  return s;
}

void put_case(Checkpoint& ck, const std::string& physical_text) {
  ck.put("case.physical_keys",
         std::vector<std::uint8_t>(physical_text.begin(), physical_text.end()));
  ck.put_value("case.hash", fnv1a64(physical_text));
}

void check_case(const Checkpoint& ck, const CaseSpec& spec, const std::filesystem::path& path) {
  const std::string text = physical_case_text(spec);
  if (fnv1a64(text) == ck.value<std::uint64_t>("case.hash")) return;
  const auto& stored = ck.u8("case.physical_keys");
  const std::string changes = describe_key_changes(
      parse_case_text(text), parse_case_text(std::string(stored.begin(), stored.end())),
      "checkpoint");
  throw CheckpointError(fmt::format(
      "{}: the case differs from the checkpointed run: {}: a resumed run may change only "
      "case.end_time and the output keys",
      path.string(), changes.empty() ? "its hash does not match" : changes));
}

namespace {

// The capillary refresh's held acceleration ("levelN.acc_st", D values per particle), the last
// refresh's value and its rate ("levelN.acc_ref", "levelN.acc_rate"; SurfaceFields::extrapolate)
// and the time of the last refresh of each clock: without them a resumed run would refresh at
// once where the uninterrupted run did not. Where acc_ref is set, the next evaluation forms
// acc_st anew from it (the acc_st written then is out of order and read by nothing). With local
// time stepping also the held lambda, normal and curvature ("levelN.lambda", "levelN.normal",
// "levelN.curvature"), which the other levels' buffers read between this level's refreshes.
template <int D>
void put_held_fields(Checkpoint& ck, const Simulation<D>& sim) {
  std::vector<double> last;
  for (const RefreshClock& c : sim.refresh_clocks()) last.push_back(c.last());
  ck.put("surface.refresh_times", last);
  for (std::size_t l = 0; l < sim.level_count(); ++l) {
    const auto& sf = sim.level(l).sf;
    ck.put_vectors<D>(fmt::format("level{}.acc_st", l), sf.acc_st);
    ck.put_vectors<D>(fmt::format("level{}.acc_ref", l), sf.acc_ref);
    ck.put_vectors<D>(fmt::format("level{}.acc_rate", l), sf.acc_rate);
    if (!sf.held_geometry) continue;
    ck.put(fmt::format("level{}.lambda", l), sf.lambda);
    ck.put_vectors<D>(fmt::format("level{}.normal", l), sf.normal);
    ck.put(fmt::format("level{}.curvature", l), sf.curvature);
  }
}

// A checkpoint without them (written with refresh = "every_step" before) refreshes at once.
template <int D>
void get_held_fields(const Checkpoint& ck, Simulation<D>& sim) {
  if (!ck.has("surface.refresh_times")) return;
  const auto& last = ck.f64("surface.refresh_times");
  if (last.size() != sim.refresh_clocks().size())
    throw CheckpointError(fmt::format("surface.refresh_times: {} clocks for {} levels", last.size(),
                                      sim.refresh_clocks().size()));
  for (std::size_t l = 0; l < sim.level_count(); ++l) {
    auto& L = sim.level(l);
    const std::size_t n = L.ps.size();
    const std::string acc_st = fmt::format("level{}.acc_st", l);
    if (ck.f64(acc_st).empty()) continue;  // no refresh yet
    ck.get_vectors<D>(acc_st, n, L.sf.acc_st);
    ck.get_vectors<D>(fmt::format("level{}.acc_ref", l), n, L.sf.acc_ref);
    ck.get_vectors<D>(fmt::format("level{}.acc_rate", l), n, L.sf.acc_rate);
    ck.get_values(fmt::format("level{}.lambda", l), n, L.sf.lambda);
    ck.get_vectors<D>(fmt::format("level{}.normal", l), n, L.sf.normal);
    ck.get_values(fmt::format("level{}.curvature", l), n, L.sf.curvature);
  }
  for (std::size_t k = 0; k < last.size(); ++k) sim.restore_refresh(k, last[k]);
}

}  // namespace

template <int D>
Checkpoint make_checkpoint(const Simulation<D>& sim, std::int64_t output_index) {
  const std::size_t nl = sim.level_count();
  RunState s;
  s.time = sim.time();
  s.dt_next = sim.dt_next();
  s.dt_last = sim.dt_last();
  s.step = sim.step_count();
  s.output_index = output_index;
  s.levels = static_cast<std::int64_t>(nl);
  s.initial_fluid = sim.initial_fluid();
  s.counters = sim.counters();
  Checkpoint ck;
  put_run_state(ck, s);
  if (sim.holds_surface_fields()) put_held_fields(ck, sim);
  if (sim.local_time_stepping()) ck.put("lts.level_dt", sim.level_dts());
  for (std::size_t l = 0; l < nl; ++l) {
    ck.put_particles<D>(static_cast<int>(l), sim.level(l).ps);
    if (nl > 1) {
      std::vector<double> masses;
      for (const auto& mp : sim.link(l).mass_points) masses.push_back(mp.mass);
      ck.put(fmt::format("level{}.point_mass", l), masses);
    }
  }
  return ck;
}

template <int D>
RunState restore_checkpoint(Simulation<D>& sim, const Checkpoint& ck) {
  const RunState s = get_run_state(ck);
  const auto levels = static_cast<std::size_t>(s.levels);
  if (levels != sim.level_count()) {
    throw CaseError(fmt::format(
        "--resume: the checkpoint holds {} level(s) but the case makes {} ([[refinement]] changed)",
        levels, sim.level_count()));
  }
  for (std::size_t l = 0; l < levels; ++l) {
    auto& L = sim.level(l);
    ck.get_particles<D>(static_cast<int>(l), L.ps);
    sim.keep_optional_arrays(l);
    if (levels > 1) {
      const auto& m = ck.f64(fmt::format("level{}.point_mass", l));
      if (m.size() != sim.link(l).mass_points.size())
        throw CaseError(
            "--resume: the checkpoint's mass points do not match the case's refinement boxes");
      for (std::size_t q = 0; q < m.size(); ++q) sim.link(l).mass_points[q].mass = m[q];
    }
  }
  sim.restore(s.time, s.step, s.dt_next, s.counters, s.initial_fluid);
  if (sim.holds_surface_fields()) get_held_fields(ck, sim);  // before the sort, which carries them
  if (sim.local_time_stepping()) sim.restore_level_dts(ck.f64("lts.level_dt"));
  sim.resort();
  return s;
}

template Checkpoint make_checkpoint<2>(const Simulation<2>&, std::int64_t);
template Checkpoint make_checkpoint<3>(const Simulation<3>&, std::int64_t);
template RunState restore_checkpoint<2>(Simulation<2>&, const Checkpoint&);
template RunState restore_checkpoint<3>(Simulation<3>&, const Checkpoint&);

}  // namespace vrsph
