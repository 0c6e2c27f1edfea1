// The resolved case as flat dotted keys (see case_keys.hpp).
#include "vrsph/setup/case_keys.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include "vrsph/setup/case_parser.hpp"
#include "vrsph/setup/case_reader.hpp"

namespace vrsph {
namespace {

bool is_array_of_tables(const toml::node& node) {
  const auto* arr = node.as_array();
  return arr != nullptr && !arr->empty() && arr->is_array_of_tables();
}

// Adds the leaves under `node` at dotted path `path`.
void flatten(const toml::node& node, const std::string& path,
             std::map<std::string, std::string>& out) {
  if (const auto* tbl = node.as_table()) {
    for (const auto& [k, v] : *tbl) {
      flatten(v, path.empty() ? std::string(k.str()) : path + "." + std::string(k.str()), out);
    }
  } else if (is_array_of_tables(node)) {
    const auto& arr = *node.as_array();
    for (std::size_t k = 0; k < arr.size(); ++k)
      flatten(arr[k], fmt::format("{}.{}", path, k), out);
  } else {
    out[path] = case_detail::render_full(node);
  }
}

}  // namespace

std::map<std::string, std::string> resolved_case_keys(const CaseSpec& spec) {
  const toml::table tbl = toml::parse(case_to_toml(spec));
  std::map<std::string, std::string> out;
  flatten(tbl, "", out);
  return out;
}

bool is_physical_key(std::string_view key) {
  return key != "case.end_time" && key != "output" && !key.starts_with("output.");
}

std::string physical_case_text(const CaseSpec& spec) {
  std::string text;
  for (const auto& [key, value] : resolved_case_keys(spec)) {
    if (is_physical_key(key)) text += fmt::format("{} = {}\n", key, value);
  }
  return text;
}

std::map<std::string, std::string> parse_case_text(std::string_view text) {
  std::map<std::string, std::string> out;
  while (!text.empty()) {
    const std::size_t end = std::min(text.find('\n'), text.size());
    const std::string_view line = text.substr(0, end);
    const std::size_t eq = line.find(" = ");
    if (eq != std::string_view::npos)
      out[std::string(line.substr(0, eq))] = std::string(line.substr(eq + 3));
    text.remove_prefix(std::min(end + 1, text.size()));
  }
  return out;
}

std::string describe_key_changes(const std::map<std::string, std::string>& a,
                                 const std::map<std::string, std::string>& b,
                                 std::string_view b_label, std::size_t max_keys) {
  std::map<std::string, std::pair<std::string, std::string>> changed;
  for (const auto& [k, v] : a) {
    auto it = b.find(k);
    if (it == b.end() || it->second != v) changed[k] = {v, it == b.end() ? "not set" : it->second};
  }
  for (const auto& [k, v] : b) {
    if (!a.count(k)) changed[k] = {"not set", v};
  }
  std::string text;
  std::size_t n = 0;
  for (const auto& [k, values] : changed) {
    if (n++ == max_keys) {
      text += fmt::format("; and {} more", changed.size() - max_keys);
      break;
    }
    text += fmt::format("{}{} = {} ({}: {})", text.empty() ? "" : "; ", k, values.first, b_label,
                        values.second);
  }
  return text;
}

}  // namespace vrsph
