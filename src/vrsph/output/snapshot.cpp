// Particle CSV writer, snapshot names, level merging and the shared input checks
// (the .vtp writer is in snapshot_vtp.cpp, the .pvd collection in pvd.cpp).
#include "vrsph/output/snapshot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>

#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/snapshot_detail.hpp"

namespace vrsph {

std::string xml_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string xml_unescape(std::string_view s) {
  static constexpr std::pair<std::string_view, char> entities[] = {
      {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    bool matched = false;
    for (const auto& [text, c] : entities) {
      if (s.substr(i, text.size()) == text) {
        out += c;
        i += text.size();
        matched = true;
        break;
      }
    }
    if (!matched) out += s[i++];
  }
  return out;
}

void check_snapshot_inputs(std::size_t n, std::span<const ExtraField> extras,
                           std::span<const std::uint8_t> level) {
  if (!level.empty() && level.size() != n)
    throw std::invalid_argument(
        fmt::format("snapshot: level has {} entries for {} particles", level.size(), n));
  for (const ExtraField& f : extras) {
    if (f.name.empty() || f.components < 1)
      throw std::invalid_argument("snapshot: extra field needs a name and components >= 1");
    if (f.values.size() != n * static_cast<std::size_t>(f.components))
      throw std::invalid_argument(fmt::format(
          "snapshot: extra field '{}' has {} values, expected {} particles x {} components", f.name,
          f.values.size(), n, f.components));
  }
}

std::string snapshot_file_name(int index, std::string_view extension) {
  return fmt::format("particles_{:04d}.{}", index, extension);
}

namespace {

// Column names of one extra field (see ExtraField).
void append_extra_header(std::string& header, const ExtraField& f) {
  static constexpr const char* axes[] = {"x", "y", "z"};
  if (f.components == 1) {
    header += "," + f.name;
    return;
  }
  for (int c = 0; c < f.components; ++c)
    header += "," + f.name + "_" + (f.components <= 3 ? axes[c] : std::to_string(c));
}

template <int D>
std::string csv_header(std::span<const ExtraField> extras) {
  std::string h =
      D == 2 ? "id,level,kind,x,y,vx,vy,rho,p,mass" : "id,level,kind,x,y,z,vx,vy,vz,rho,p,mass";
  for (const ExtraField& f : extras) append_extra_header(h, f);
  return h + "\n";
}

// One CSV row for particle i, appended to `buf`; the fields after the position as Real.
template <class Real, int D>
void csv_row(fmt::memory_buffer& buf, const ParticleSet<D>& ps, const TaitEos& eos, std::size_t i,
             int level, std::span<const ExtraField> extras) {
  auto out = fmt::appender(buf);
  auto field = [&out](double v) { fmt::format_to(out, ",{}", static_cast<Real>(v)); };
  fmt::format_to(out, "{},{},{}", ps.id[i], level, kind_name(ps.kind[i]));
  for (int k = 0; k < D; ++k) fmt::format_to(out, ",{}", ps.pos[i][k]);
  for (int k = 0; k < D; ++k) field(ps.vel[i][k]);
  field(ps.rho[i]);
  field(eos.pressure(ps.rho[i]));
  field(ps.mass_of(i));
  for (const ExtraField& f : extras)
    for (int c = 0; c < f.components; ++c) field(f.values[i * f.components + c]);
  buf.push_back('\n');
}

}  // namespace

template <int D>
void write_particles_csv(const std::filesystem::path& path, const ParticleSet<D>& ps,
                         const TaitEos& eos, std::span<const ExtraField> extras,
                         std::span<const std::uint8_t> level, SnapshotFormat format) {
  check_snapshot_inputs(ps.size(), extras, level);
  fmt::memory_buffer buf;
  const std::string header = csv_header<D>(extras);
  buf.append(header.data(), header.data() + header.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const int l = level.empty() ? 0 : level[i];
    if (format.float32)
      csv_row<float>(buf, ps, eos, i, l, extras);
    else
      csv_row<double>(buf, ps, eos, i, l, extras);
  }
  write_file_atomic(path, std::string_view(buf.data(), buf.size()));
}

template <int D>
MergedLevels<D> merge_levels(std::span<const ParticleSet<D>* const> levels) {
  MergedLevels<D> m;
  std::size_t n = 0;
  for (const ParticleSet<D>* ps : levels) n += ps->size();
  m.particles.keeps_shift = std::all_of(levels.begin(), levels.end(),
                                        [](const ParticleSet<D>* ps) { return ps->keeps_shift; });
  m.particles.keeps_pos0 = std::all_of(levels.begin(), levels.end(),
                                       [](const ParticleSet<D>* ps) { return ps->keeps_pos0; });
  m.particles.keeps_mass = true;  // levels differ in mass: one per particle
  m.particles.resize(n);
  m.level.resize(n);
  std::size_t j = 0;
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const ParticleSet<D>& ps = *levels[l];
    const std::size_t np = ps.size();
    // Every array of the field list; one a level has not filled yet stays zero.
    ParticleSet<D>::zip_fields(
        [&](std::string_view, FieldRole, auto& out, const auto& in) {
          std::copy_n(in.begin(), std::min(np, in.size()),
                      out.begin() + static_cast<std::ptrdiff_t>(j));
        },
        m.particles, ps);
    if (!ps.keeps_mass)  // the zip above copied the masses of a level that keeps one each
      std::fill_n(m.particles.mass.begin() + static_cast<std::ptrdiff_t>(j), np, ps.mass_each);
    std::fill_n(m.level.begin() + static_cast<std::ptrdiff_t>(j), np, static_cast<std::uint8_t>(l));
    j += np;
  }
  return m;
}

template void write_particles_csv<2>(const std::filesystem::path&, const ParticleSet<2>&,
                                     const TaitEos&, std::span<const ExtraField>,
                                     std::span<const std::uint8_t>, SnapshotFormat);
template void write_particles_csv<3>(const std::filesystem::path&, const ParticleSet<3>&,
                                     const TaitEos&, std::span<const ExtraField>,
                                     std::span<const std::uint8_t>, SnapshotFormat);
template MergedLevels<2> merge_levels<2>(std::span<const ParticleSet<2>* const>);
template MergedLevels<3> merge_levels<3>(std::span<const ParticleSet<3>* const>);

}  // namespace vrsph
