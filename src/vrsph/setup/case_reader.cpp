// Typed, checked reading of case-file tables and the one-line error format (case_reader.hpp).
#include "vrsph/setup/case_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace vrsph::case_detail {
namespace {

constexpr std::size_t kMaxRendered = 80;  // longer values are cut with "..."

// The node itself when it has a source line, else its first descendant that has one.
const toml::node* first_sourced(const toml::node* node) {
  if (node == nullptr) return nullptr;
  if (node->source().begin.line > 0) return node;
  if (const auto* tbl = node->as_table()) {
    for (const auto& [k, v] : *tbl) {
      if (const auto* s = first_sourced(&v)) return s;
    }
  } else if (const auto* arr = node->as_array()) {
    for (const auto& v : *arr) {
      if (const auto* s = first_sourced(&v)) return s;
    }
  }
  return nullptr;
}

// Source line of a node for ordering (nodes without one sort last).
std::uint32_t line_of(const toml::node& node) {
  const auto* s = first_sourced(&node);
  return s ? s->source().begin.line : std::numeric_limits<std::uint32_t>::max();
}

// A float as TOML text: shortest round-trip form.
std::string render_float(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{}", v);
}

}  // namespace

// Full (untruncated) compact rendering; see render_value().
std::string render_full(const toml::node& node) {
  if (const auto* s = node.as_string()) return toml_quote(s->get());
  if (const auto* i = node.as_integer()) return fmt::format("{}", i->get());
  if (const auto* f = node.as_floating_point()) return render_float(f->get());
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* arr = node.as_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < arr->size(); ++k) {
      out += (k ? ", " : "") + render_full(*arr->get(k));
    }
    return out + "]";
  }
  if (const auto* tbl = node.as_table()) {
    std::string out = "{";
    bool first = true;
    for (const auto& [k, v] : *tbl) {
      out += fmt::format("{} {} = {}", first ? "" : ",", k.str(), render_full(v));
      first = false;
    }
    return out + (first ? "}" : " }");
  }
  std::ostringstream os;  // dates and times
  node.visit([&](const auto& n) { os << n; });
  return os.str();
}

// Error prefix for a node: "--set ", "file:line: " or "file: ".
std::string location_of(const toml::node* node, const std::string& source) {
  const toml::node* sourced = first_sourced(node);
  if (sourced != nullptr) {
    const auto& src = sourced->source();
    if (src.path && *src.path == kSetSource) return std::string(kSetSource) + " ";
    return fmt::format("{}:{}: ", source, src.begin.line);
  }
  return source.empty() ? std::string() : source + ": ";
}

// Compact one-line rendering, cut to kMaxRendered characters.
std::string render_value(const toml::node& node) {
  std::string text = render_full(node);
  if (text.size() > kMaxRendered) text = text.substr(0, kMaxRendered - 3) + "...";
  return text;
}

// TOML basic string: quotes, backslash escapes, control characters as \uXXXX.
std::string toml_quote(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      out += fmt::format("\\u{:04X}", u);
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string vec_text(const Vec3d& v, int dim) {
  std::string out = "[";
  for (int k = 0; k < dim; ++k) out += fmt::format("{}{}", k ? ", " : "", v[k]);
  return out + "]";
}

TableReader::TableReader(const toml::table* tbl, std::string path, std::string source, Keys keys)
    : tbl_(tbl), path_(std::move(path)), source_(std::move(source)) {
  check_keys(keys);
}

// Rejects the first unknown key (by source line), listing the allowed ones.
void TableReader::check_keys(Keys keys) const {
  if (tbl_ == nullptr) return;
  const toml::key* worst = nullptr;
  std::uint32_t worst_line = 0;
  for (const auto& [k, v] : *tbl_) {
    if (std::find(keys.begin(), keys.end(), k.str()) != keys.end()) continue;
    const auto line = line_of(v);
    if (worst == nullptr || line < worst_line) {
      worst = &k;
      worst_line = line;
    }
  }
  if (worst == nullptr) return;
  std::string allowed;
  for (const auto k : keys) allowed += (allowed.empty() ? "" : ", ") + std::string(k);
  fail(worst->str(), fmt::format("unknown key (allowed {}: {})",
                                 path_.empty() ? "at top level" : "in " + path_, allowed));
}

// "path.key", or "key" at the root.
std::string TableReader::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

// The node of `key`, or null when absent (or when this reader covers no table).
const toml::node* TableReader::node(std::string_view key) const {
  return tbl_ == nullptr ? nullptr : tbl_->get(key);
}

// Number (TOML integer or float), finite, passing `check`.
std::optional<double> TableReader::opt_number(std::string_view key, Check check) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  double v = 0.0;
  if (const auto* i = n->as_integer()) {
    v = static_cast<double>(i->get());
  } else if (const auto* f = n->as_floating_point()) {
    v = f->get();
  } else {
    fail(key, "must be a number");
  }
  require(key, std::isfinite(v), "must be finite");
  require(key, check.ok(v), check.reason);
  return v;
}

// TOML integer that fits an int (a float such as 2.0 or 2.5 is refused).
std::optional<int> TableReader::opt_integer(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* i = n->as_integer();
  if (i == nullptr) fail(key, "must be an integer");
  const std::int64_t v = i->get();
  require(key, v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max(),
          "integer out of range");
  return static_cast<int>(v);
}

// TOML boolean.
std::optional<bool> TableReader::opt_bool(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* b = n->as_boolean();
  if (b == nullptr) fail(key, "must be true or false");
  return b->get();
}

// TOML string.
std::optional<std::string> TableReader::opt_string(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* s = n->as_string();
  if (s == nullptr) fail(key, "must be a string");
  return s->get();
}

// Array of exactly `dim` finite numbers; the components beyond dim stay 0.
std::optional<Vec3d> TableReader::opt_vector(std::string_view key, int dim) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* arr = n->as_array();
  const std::string reason =
      fmt::format("must be an array of {} numbers (dimension = {})", dim, dim);
  if (arr == nullptr || arr->size() != static_cast<std::size_t>(dim)) fail(key, reason);
  Vec3d out{};
  for (int k = 0; k < dim; ++k) {
    const toml::node& e = *arr->get(static_cast<std::size_t>(k));
    if (const auto* i = e.as_integer()) {
      out[k] = static_cast<double>(i->get());
    } else if (const auto* f = e.as_floating_point()) {
      out[k] = f->get();
    } else {
      fail(key, reason);
    }
    require(key, std::isfinite(out[k]), "components must be finite");
  }
  return out;
}

// Array of strings.
std::optional<std::vector<std::string>> TableReader::opt_string_array(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  const auto* arr = n->as_array();
  if (arr == nullptr) fail(key, "must be an array of strings");
  std::vector<std::string> out;
  for (const auto& e : *arr) {
    const auto* s = e.as_string();
    if (s == nullptr) fail(key, "must be an array of strings");
    out.push_back(s->get());
  }
  return out;
}

// Regular or inline sub-table; absent gives a reader over nothing.
TableReader TableReader::sub_table(std::string_view key, Keys keys) const {
  const toml::node* n = node(key);
  if (n != nullptr && !n->is_table()) fail(key, "must be a table");
  return TableReader(n ? n->as_table() : nullptr, key_path(key), source_, keys);
}

// Array of tables; each element is read as "key.<index>".
std::vector<TableReader> TableReader::table_array(std::string_view key, Keys keys) const {
  std::vector<TableReader> out;
  const toml::node* n = node(key);
  if (n == nullptr) return out;
  const std::string reason = fmt::format("must be an array of tables ([[{}]])", key_path(key));
  const auto* arr = n->as_array();
  if (arr == nullptr) fail(key, reason);
  for (std::size_t k = 0; k < arr->size(); ++k) {
    const auto* elem = arr->get(k)->as_table();
    if (elem == nullptr) fail(key, reason);
    out.emplace_back(elem, fmt::format("{}.{}", key_path(key), k), source_, keys);
  }
  return out;
}

void TableReader::fail(std::string_view key, std::string_view reason) const {
  const toml::node* n = node(key);
  if (n == nullptr) fail_missing_reason(key, reason);
  throw CaseError(fmt::format("{}{} = {}: {}", location_of(n, source_), key_path(key),
                              render_value(*n), reason));
}

void TableReader::fail_missing(std::string_view key) const {
  fail_missing_reason(key, "required key is missing");
}

// Error about an absent key: located at its table (file name only at the root).
void TableReader::fail_missing_reason(std::string_view key, std::string_view reason) const {
  const toml::node* where = path_.empty() ? nullptr : tbl_;
  throw CaseError(fmt::format("{}{}: {}", location_of(where, source_), key_path(key), reason));
}

}  // namespace vrsph::case_detail
