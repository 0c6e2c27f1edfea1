// Everything a run writes at an output time: snapshot (vtp/csv + pvd), line profiles (particle
// strip and interpolated), a row of every probe file, a series row and the checkpoint; plus the
// final summary.json.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "vrsph/analysis/laplace.hpp"
#include "vrsph/output/probe_series.hpp"
#include "vrsph/output/series.hpp"
#include "vrsph/output/snapshot.hpp"
#include "vrsph/setup/case_spec.hpp"
#include "vrsph/sim/simulation.hpp"

namespace vrsph {

// What the extra series.csv columns read at an output time.
struct SeriesInputs {
  std::vector<SeriesRow> levels;  // the fixed columns of each level alone
  const RunCounters* counters = nullptr;
  LaplaceError laplace;         // only with a Laplace check (analysis.laplace_pressure and a line)
  LaplaceError laplace_interp;  // the same on the interpolated line
  std::vector<std::array<double, 3>> wall_forces;  // the fluid's force on each wall block (N)
  std::vector<double> mass_stored;  // kg: mass held by each level's mass points (refinement)
  double kinetic_energy_cm = 0.0;   // J: the fluid's, in its centre-of-mass frame
};

// An extra series.csv column: its name in the header and its value in a row. The list of them,
// built once from the case, gives both the header and every row.
struct SeriesExtraColumn {
  std::string name;
  std::function<double(const SeriesInputs&)> value;
};

template <int D>
class RunOutputs {
 public:
  // fresh: start new files; otherwise continue the files of a run resumed at time t.
  RunOutputs(const CaseSpec& spec, std::filesystem::path dir, bool fresh, double t);

  // Writes snapshot `index` of the current state (and the checkpoint) at the current time.
  void write(Simulation<D>& sim, int index);

  // Writes the checkpoint of the current state, `index` being the last snapshot written.
  void write_checkpoint(const Simulation<D>& sim, int index) const;

  // The summary of a finished or stopped run.
  nlohmann::json summary(const Simulation<D>& sim, bool completed, double wall_seconds, int threads,
                         const std::string& error) const;

  const std::filesystem::path& dir() const { return dir_; }

 private:
  void write_snapshot(Simulation<D>& sim, int index);
  // The files of every line; the Laplace figures of the first line into `in`.
  void write_lines(const Simulation<D>& sim, int index, SeriesInputs& in) const;
  void append_series(const Simulation<D>& sim, SeriesInputs& in);

  const CaseSpec& spec_;
  std::filesystem::path dir_;
  std::string case_text_;  // the physical keys, checkpointed to refuse a resume of another case
  PvdCollection pvd_;
  std::vector<SeriesExtraColumn> extras_;
  SeriesWriter series_;
  std::vector<ProbeWriter<D>> probes_;  // one per [[output.probe]], in case order
};

}  // namespace vrsph
