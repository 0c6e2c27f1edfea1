// What a run's checkpoint holds and how it is read back: the stepping state as one named record
// per value, the particles of every level, and the stored masses of the mass points. Saving and
// restoring walk the same lists (for_each_record here, ParticleSet's field list), so a value
// cannot be written under one name and read under another, or be forgotten by one side.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "vrsph/driver/checkpoint.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {

// The stepping state of a run besides its particles.
struct RunState {
  double time = 0.0;  // s
  double dt_next = 0.0;
  double dt_last = 0.0;
  std::int64_t step = 0;
  std::int64_t output_index = 0;  // the snapshot written with this checkpoint
  std::int64_t levels = 1;
  std::uint64_t initial_fluid = 0;
  RunCounters counters;
};

// Calls f(name, member) for every counter; S is RunCounters or const RunCounters.
template <class S, class F>
void for_each_counter(S& c, F&& f) {
  f(std::string("particle_steps"), c.particle_steps);
  f(std::string("pairs"), c.pairs);
  for (std::size_t k = 0; k < kDtLimitNames.size(); ++k)
    f("dt_limit." + std::string(kDtLimitNames[k]), c.dt_limit_counts[k]);
  f(std::string("lost_fluid"), c.lost_fluid);
  f(std::string("wall_seconds"), c.wall_seconds);
  f(std::string("created"), c.created);
  f(std::string("deleted"), c.deleted);
  f(std::string("created_mass"), c.created_mass);
  f(std::string("deleted_mass"), c.deleted_mass);
  f(std::string("next_id"), c.next_id);
}

// Calls f(record name, member) for every value of the state; S is RunState or const RunState.
template <class S, class F>
void for_each_record(S& s, F&& f) {
  f(std::string("time"), s.time);
  f(std::string("dt_next"), s.dt_next);
  f(std::string("dt_last"), s.dt_last);
  f(std::string("step"), s.step);
  f(std::string("output_index"), s.output_index);
  f(std::string("levels"), s.levels);
  f(std::string("initial_fluid"), s.initial_fluid);
  for_each_counter(s.counters,
                   [&f](const std::string& name, auto& v) { f("counters." + name, v); });
}

void put_run_state(Checkpoint& ck, const RunState& s);

// The physical keys of the case (physical_case_text) and their FNV-1a hash, as the records
// "case.physical_keys" and "case.hash".
void put_case(Checkpoint& ck, const std::string& physical_text);
// Throws CheckpointError naming `path` and every physical key whose value in `spec` differs from
// the checkpointed run's (case.end_time and the output keys may change on resume).
void check_case(const Checkpoint& ck, const CaseSpec& spec, const std::filesystem::path& path);
// Throws std::runtime_error naming the first missing record.
RunState get_run_state(const Checkpoint& ck);

// The checkpoint of the current state of `sim`, after snapshot `output_index`; the case records
// are the caller's (put_case).
template <int D>
Checkpoint make_checkpoint(const Simulation<D>& sim, std::int64_t output_index);

// Puts the state of `ck` into `sim` (built from the same case) and re-sorts; returns the stepping
// state read. Throws CaseError when the checkpoint does not fit the case's levels.
template <int D>
RunState restore_checkpoint(Simulation<D>& sim, const Checkpoint& ck);

}  // namespace vrsph
