// series.csv writer and the per-step global diagnostics (see series.hpp).
#include "vrsph/output/series.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/csv_rows.hpp"

namespace vrsph {

template <int D>
SeriesRow compute_series_row(const ParticleSet<D>& ps, double t, long step, double dt) {
  SeriesRow row;
  row.t = t;
  row.step = step;
  row.dt = dt;
  double max_v2 = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kind[i] == Kind::buffer) ++row.n_buffer;
    if (ps.kind[i] != Kind::fluid) continue;
    const double v2 = norm2(ps.vel[i]);
    ++row.n_fluid;
    row.mass_fluid += ps.mass_of(i);
    row.kinetic_energy += 0.5 * ps.mass_of(i) * v2;
    max_v2 = std::max(max_v2, v2);
  }
  row.max_speed = std::sqrt(max_v2);
  return row;
}

template <int D>
double centre_of_mass_kinetic_energy(std::span<const ParticleSet<D>* const> sets) {
  double mass = 0.0;
  Vec<D> momentum{};
  for (const ParticleSet<D>* ps : sets) {
    for (std::size_t i = 0; i < ps->size(); ++i) {
      if (ps->kind[i] != Kind::fluid) continue;
      mass += ps->mass_of(i);
      momentum += ps->mass_of(i) * ps->vel[i];
    }
  }
  if (mass <= 0.0) return 0.0;
  const Vec<D> mean_v = momentum * (1.0 / mass);
  double energy = 0.0;
  for (const ParticleSet<D>* ps : sets) {
    for (std::size_t i = 0; i < ps->size(); ++i)
      if (ps->kind[i] == Kind::fluid) energy += 0.5 * ps->mass_of(i) * norm2(ps->vel[i] - mean_v);
  }
  return energy;
}

template double centre_of_mass_kinetic_energy<2>(std::span<const ParticleSet<2>* const>);
template double centre_of_mass_kinetic_energy<3>(std::span<const ParticleSet<3>* const>);

template SeriesRow compute_series_row<2>(const ParticleSet<2>&, double, long, double);
template SeriesRow compute_series_row<3>(const ParticleSet<3>&, double, long, double);

void accumulate_series_row(SeriesRow& row, const SeriesRow& other) {
  row.n_fluid += other.n_fluid;
  row.n_buffer += other.n_buffer;
  row.mass_fluid += other.mass_fluid;
  row.kinetic_energy += other.kinetic_energy;
  row.max_speed = std::max(row.max_speed, other.max_speed);
}

namespace {

// Extra column names from a header line; throws unless it starts with the fixed columns.
std::vector<std::string> extras_from_header(const std::string& header,
                                            const std::filesystem::path& path) {
  const std::vector<std::string> names = split_fields(header);
  bool fixed = names.size() >= kSeriesColumns.size();
  for (std::size_t k = 0; fixed && k < kSeriesColumns.size(); ++k)
    fixed = names[k] == kSeriesColumns[k].name;
  if (!fixed) throw std::runtime_error(path.string() + ": not a series.csv header: " + header);
  return {names.begin() + static_cast<std::ptrdiff_t>(kSeriesColumns.size()), names.end()};
}

// Index of the fixed column `name`.
constexpr std::size_t column_index(std::string_view name) {
  for (std::size_t k = 0; k < kSeriesColumns.size(); ++k)
    if (kSeriesColumns[k].name == name) return k;
  return kSeriesColumns.size();
}

}  // namespace

SeriesWriter::SeriesWriter(NoInit, std::filesystem::path path,
                           std::vector<std::string> extra_columns)
    : path_(std::move(path)), extra_(std::move(extra_columns)) {}

SeriesWriter::SeriesWriter(std::filesystem::path path, std::vector<std::string> extra_columns)
    : SeriesWriter(NoInit{}, std::move(path), std::move(extra_columns)) {
  write_file_atomic(path_, header() + "\n");
}

std::string SeriesWriter::header() const {
  std::string h;
  for (const SeriesColumn& c : kSeriesColumns) {
    if (!h.empty()) h += ',';
    h += c.name;
  }
  for (const std::string& c : extra_) h += "," + c;
  return h;
}

SeriesWriter SeriesWriter::resume(const std::filesystem::path& path, double up_to_time,
                                  std::vector<std::string> extra_columns) {
  if (!std::filesystem::exists(path)) return SeriesWriter(path, std::move(extra_columns));
  const std::string text = read_text_file(path);
  // Only newline-terminated lines count: a trailing partial line is dropped.
  const std::vector<std::string> lines = complete_lines(text);
  if (lines.empty()) return SeriesWriter(path, std::move(extra_columns));
  std::vector<std::string> extras = extras_from_header(lines[0], path);
  if (!extra_columns.empty() && extra_columns != extras)
    throw std::runtime_error(path.string() + ": extra columns differ from the resumed run's");
  SeriesWriter w(NoInit{}, path, std::move(extras));
  std::string kept = lines[0] + "\n";
  const std::size_t n_columns = kSeriesColumns.size() + w.extra_.size();
  constexpr std::size_t kt = column_index("t");
  static_assert(kt < kSeriesColumns.size());
  for (std::size_t k = 1; k < lines.size(); ++k)
    if (row_up_to(lines[k], n_columns, kt, up_to_time)) kept += lines[k] + "\n";
  write_file_atomic(path, kept);
  return w;
}

void SeriesWriter::append(const SeriesRow& row) {
  if (row.extra.size() != extra_.size())
    throw std::invalid_argument(fmt::format("series row has {} extra values for {} columns",
                                            row.extra.size(), extra_.size()));
  fmt::memory_buffer buf;
  const char* sep = "";
  for (const SeriesColumn& c : kSeriesColumns) {
    if (c.real)
      fmt::format_to(fmt::appender(buf), "{}{}", sep, row.*c.real);
    else
      fmt::format_to(fmt::appender(buf), "{}{}", sep, row.*c.count);
    sep = ",";
  }
  for (double v : row.extra) fmt::format_to(fmt::appender(buf), ",{}", v);
  buf.push_back('\n');
  append_durably(path_, std::string_view(buf.data(), buf.size()));
}

}  // namespace vrsph
