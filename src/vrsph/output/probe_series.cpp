#include "vrsph/output/probe_series.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/csv_rows.hpp"

namespace vrsph {

template <int D>
ProbeWriter<D>::ProbeWriter(std::filesystem::path path) : path_(std::move(path)) {
  write_file_atomic(path_, header() + "\n");
}

template <int D>
std::string ProbeWriter<D>::header() {
  return D == 2 ? "t,p,rho,vx,vy" : "t,p,rho,vx,vy,vz";
}

template <int D>
ProbeWriter<D> ProbeWriter<D>::resume(const std::filesystem::path& path, double up_to_time) {
  if (!std::filesystem::exists(path)) return ProbeWriter(path);
  const std::vector<std::string> lines = complete_lines(read_text_file(path));
  if (lines.empty()) return ProbeWriter(path);
  if (lines[0] != header())
    throw std::runtime_error(
        fmt::format("{}: not a {}D probe header: {}", path.string(), D, lines[0]));
  const std::size_t n_columns = static_cast<std::size_t>(D) + 3;
  std::string kept = lines[0] + "\n";
  for (std::size_t k = 1; k < lines.size(); ++k)
    if (row_up_to(lines[k], n_columns, 0, up_to_time)) kept += lines[k] + "\n";
  write_file_atomic(path, kept);
  return ProbeWriter(NoInit{}, path);
}

template <int D>
void ProbeWriter<D>::append(double t, const FluidPoint<D>& f) {
  fmt::memory_buffer buf;
  fmt::format_to(fmt::appender(buf), "{}", t);
  append_fluid_values<D>(buf, f);
  buf.push_back('\n');
  append_durably(path_, std::string_view(buf.data(), buf.size()));
}

std::string probe_file_name(std::string_view name) { return fmt::format("probe_{}.csv", name); }

template class ProbeWriter<2>;
template class ProbeWriter<3>;

}  // namespace vrsph
