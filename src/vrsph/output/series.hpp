// series.csv: one row of global diagnostics per call (at least one per output time), columns
//   t,step,dt,n_fluid,n_buffer,mass_fluid,kinetic_energy,max_speed[,extra columns...]
// (the fixed ones listed once in kSeriesColumns, which the header, the rows and resume all use).
// Each row is appended with a single write() and fsync'ed, so a killed run leaves whole lines only;
// resume() also drops any incomplete trailing line.
#pragma once

#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vrsph/particles/particles.hpp"

namespace vrsph {

struct SeriesRow {
  double t = 0.0;  // s
  long step = 0;
  double dt = 0.0;  // s
  long n_fluid = 0;
  long n_buffer = 0;
  double mass_fluid = 0.0;      // kg, fluid particles of all levels, buffers excluded
  double kinetic_energy = 0.0;  // J, sum 0.5 m |v|^2 over fluid
  double max_speed = 0.0;       // m/s, max |v| over fluid
  std::vector<double> extra;    // one value per extra column, in the writer's order
};

// A fixed column: its name and the row member it shows (exactly one of the two is set).
struct SeriesColumn {
  std::string_view name;
  double SeriesRow::*real = nullptr;
  long SeriesRow::*count = nullptr;
};

// The fixed columns, in file order.
inline constexpr std::array kSeriesColumns = {
    SeriesColumn{"t", &SeriesRow::t, nullptr},
    SeriesColumn{"step", nullptr, &SeriesRow::step},
    SeriesColumn{"dt", &SeriesRow::dt, nullptr},
    SeriesColumn{"n_fluid", nullptr, &SeriesRow::n_fluid},
    SeriesColumn{"n_buffer", nullptr, &SeriesRow::n_buffer},
    SeriesColumn{"mass_fluid", &SeriesRow::mass_fluid, nullptr},
    SeriesColumn{"kinetic_energy", &SeriesRow::kinetic_energy, nullptr},
    SeriesColumn{"max_speed", &SeriesRow::max_speed, nullptr},
};

// The fixed columns of a row from one particle set, summed in index order (deterministic).
// For several levels, combine rows with accumulate_series_row.
template <int D>
SeriesRow compute_series_row(const ParticleSet<D>& ps, double t, long step, double dt);

// Kinetic energy of the fluid in its centre-of-mass frame: sum m |v - V|^2 / 2 over the fluid
// particles of all the sets, V = sum m v / sum m their mean velocity (J; J/m in 2D). A drop's
// oscillation and parasitic currents without its translation. Two passes in index order (V,
// then the sum), so no large translational energy is subtracted.
template <int D>
double centre_of_mass_kinetic_energy(std::span<const ParticleSet<D>* const> sets);

// Adds the counts, masses and energies of `other` into `row` and takes the larger max_speed
// (t, step, dt and extras of `row` are kept): the row of several levels.
void accumulate_series_row(SeriesRow& row, const SeriesRow& other);

class SeriesWriter {
 public:
  // Starts a new series.csv at `path` (replacing any existing one) with the header.
  explicit SeriesWriter(std::filesystem::path path, std::vector<std::string> extra_columns = {});

  // Continues an existing series after a restart from a checkpoint at `up_to_time`: keeps the
  // header and the complete rows with t <= up_to_time, dropping later and broken rows (rewritten
  // atomically). The extra columns come from the file's header; if `extra_columns` is not empty it
  // must match them (std::runtime_error otherwise). A missing file starts a new series.
  static SeriesWriter resume(const std::filesystem::path& path, double up_to_time,
                             std::vector<std::string> extra_columns = {});

  // Appends one row; row.extra must have one value per extra column (std::invalid_argument).
  void append(const SeriesRow& row);

  const std::filesystem::path& path() const { return path_; }
  const std::vector<std::string>& extra_columns() const { return extra_; }
  std::string header() const;

 private:
  struct NoInit {};
  SeriesWriter(NoInit, std::filesystem::path path, std::vector<std::string> extra_columns);

  std::filesystem::path path_;
  std::vector<std::string> extra_;
};

}  // namespace vrsph
