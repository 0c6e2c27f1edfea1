// The ParaView collection file (.pvd) listing the snapshots of a run with their times:
//   <VTKFile type="Collection" version="0.1">
//     <Collection>
//       <DataSet timestep="0" group="" part="0" file="particles_0000.vtp"/>
//       ...
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <optional>
#include <stdexcept>

#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/snapshot.hpp"
#include "vrsph/output/snapshot_detail.hpp"

namespace vrsph {
namespace {

// Value of attribute `name` inside one XML tag, unescaped; empty optional when absent.
std::optional<std::string> attribute(std::string_view tag, std::string_view name) {
  std::string key = " ";
  key.append(name).append("=\"");
  const std::size_t start = tag.find(key);
  if (start == std::string_view::npos) return std::nullopt;
  const std::size_t from = start + key.size();
  const std::size_t end = tag.find('"', from);
  if (end == std::string_view::npos) return std::nullopt;
  return xml_unescape(tag.substr(from, end - from));
}

double parse_time(const std::string& text, const std::filesystem::path& path) {
  double t = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), t);
  if (ec != std::errc() || ptr != text.data() + text.size())
    throw std::runtime_error(
        fmt::format("{}: bad timestep \"{}\" in collection", path.string(), text));
  return t;
}

}  // namespace

PvdCollection::PvdCollection(std::filesystem::path pvd_path) : path_(std::move(pvd_path)) {}

PvdCollection PvdCollection::load(const std::filesystem::path& pvd_path, double up_to_time) {
  PvdCollection pvd(pvd_path);
  if (!std::filesystem::exists(pvd_path)) return pvd;
  const std::string text = read_text_file(pvd_path);
  for (std::size_t pos = text.find("<DataSet"); pos != std::string::npos;
       pos = text.find("<DataSet", pos + 1)) {
    const std::size_t end = text.find('>', pos);
    if (end == std::string::npos) break;
    const std::string_view tag(text.data() + pos, end - pos);
    const auto time = attribute(tag, "timestep");
    const auto file = attribute(tag, "file");
    if (!time || !file)
      throw std::runtime_error(pvd_path.string() + ": DataSet without timestep or file");
    const double t = parse_time(*time, pvd_path);
    if (t <= up_to_time) pvd.add(t, *file);
  }
  return pvd;
}

void PvdCollection::add(double time, const std::string& vtp_file_name) {
  std::erase_if(entries_, [&](const Entry& e) { return e.file == vtp_file_name; });
  // Insert after every entry with time <= `time`, so equal times keep their insertion order.
  const auto at = std::upper_bound(entries_.begin(), entries_.end(), time,
                                   [](double t, const Entry& e) { return t < e.time; });
  entries_.insert(at, Entry{time, vtp_file_name});
}

void PvdCollection::write() const {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const Entry& e : entries_)
    xml += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                       xml_escape(e.file));
  xml += "  </Collection>\n</VTKFile>\n";
  write_file_atomic(path_, xml);
}

}  // namespace vrsph
