// Loading a case file and applying --set overrides (case_parser.hpp). Validation is in
// case_sections.cpp, writing back in case_writer.cpp.
#include "vrsph/setup/case_parser.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

#include "vrsph/setup/case_reader.hpp"

namespace vrsph {
namespace {

using case_detail::kSetSource;

// Parses TOML text; nullopt on a syntax error (error text in *error when given).
std::optional<toml::table> try_parse(std::string_view doc, std::string_view source,
                                     std::string* error) {
#if TOML_EXCEPTIONS
  try {
    return toml::parse(doc, source);
  } catch (const toml::parse_error& e) {
    if (error != nullptr) {
      *error = fmt::format("{}:{}:{}: TOML syntax error: {}", source, e.source().begin.line,
                           e.source().begin.column, e.description());
    }
    return std::nullopt;
  }
#else
  toml::parse_result res = toml::parse(doc, source);
  if (!res) {
    if (error != nullptr) {
      const auto& e = res.error();
      *error = fmt::format("{}:{}:{}: TOML syntax error: {}", source, e.source().begin.line,
                           e.source().begin.column, e.description());
    }
    return std::nullopt;
  }
  return std::move(res).table();
#endif
}

// Whitespace trimmed from both ends.
std::string trim(std::string_view s) {
  const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return std::string(s);
}

// True for a non-empty run of decimal digits (an array index in a --set path).
bool is_index(std::string_view s) {
  if (s.empty() || s.size() > 9) return false;
  for (const char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  return true;
}

// One --set KEY=VALUE being applied, for its error messages.
struct Override {
  std::string key;
  std::string text;
  std::vector<std::string> segments;

  [[noreturn]] void fail(std::string_view reason) const {
    throw CaseError(fmt::format("{} {} = {}: {}", kSetSource, key, text, reason));
  }
};

// Splits "KEY=VALUE" and the dotted key; CaseError when malformed.
Override split_override(const std::string& key_eq_value) {
  const auto eq = key_eq_value.find('=');
  if (eq == std::string::npos) {
    throw CaseError(fmt::format("{} {}: expected KEY=VALUE", kSetSource, key_eq_value));
  }
  Override ov{trim(std::string_view(key_eq_value).substr(0, eq)),
              trim(std::string_view(key_eq_value).substr(eq + 1)),
              {}};
  std::string_view rest = ov.key;
  while (true) {
    const auto dot = rest.find('.');
    ov.segments.push_back(trim(rest.substr(0, dot)));
    if (ov.segments.back().empty()) ov.fail("empty key segment (expected a.b.c=VALUE)");
    if (dot == std::string_view::npos) break;
    rest.remove_prefix(dot + 1);
  }
  return ov;
}

// "v = <text>" as TOML when <text> is one valid TOML value, else "v = <text as a string>".
// Nodes carry the source name "--set".
toml::table parse_override_value(const std::string& text) {
  auto parsed = try_parse("v = " + text, kSetSource, nullptr);
  if (parsed && parsed->size() == 1 && parsed->contains("v")) return std::move(*parsed);
  std::string error;
  parsed = try_parse("v = " + case_detail::toml_quote(text), kSetSource, &error);
  if (!parsed) throw CaseError(error);  // cannot happen: a quoted string is valid TOML
  return std::move(*parsed);
}

// Index `seg` into arr (named `where` in errors); CaseError unless an index in range.
std::size_t array_index(const toml::array& arr, const std::string& seg, const std::string& where,
                        const Override& ov) {
  if (!is_index(seg)) ov.fail(fmt::format("{} is an array: expected an index, got {}", where, seg));
  const auto index = static_cast<std::size_t>(std::stoul(seg));
  if (index >= arr.size()) {
    ov.fail(fmt::format("index {} out of range ({} has {} element{})", index, where, arr.size(),
                        arr.size() == 1 ? "" : "s"));
  }
  return index;
}

// Walks to the table or array that holds the last segment, creating missing tables.
toml::node* walk_to_parent(toml::table& root, const Override& ov) {
  toml::node* cur = &root;
  std::string where;
  for (std::size_t k = 0; k + 1 < ov.segments.size(); ++k) {
    const std::string& seg = ov.segments[k];
    const std::string parent = where;
    where += (where.empty() ? "" : ".") + seg;
    toml::node* next = nullptr;
    if (auto* arr = cur->as_array()) {
      next = arr->get(array_index(*arr, seg, parent, ov));
    } else {
      auto* tbl = cur->as_table();
      next = tbl->get(seg);
      if (next == nullptr) {
        if (is_index(ov.segments[k + 1])) ov.fail(fmt::format("{} does not exist", where));
        next = &tbl->insert(seg, toml::table{}).first->second;
      }
    }
    if (!next->is_table() && !next->is_array()) {
      ov.fail(fmt::format("{} is a value, not a table or array", where));
    }
    cur = next;
  }
  return cur;
}

}  // namespace

// Reads the whole file and parses it as TOML.
toml::table load_case_table(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw CaseError(fmt::format("{}: cannot open case file: no such file", path));
  }
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw CaseError(fmt::format("{}: cannot open case file: not a regular file", path));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw CaseError(fmt::format("{}: cannot open case file: {}", path, std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  std::string error;
  auto tbl = try_parse(text.str(), path, &error);
  if (!tbl) throw CaseError(error);
  return std::move(*tbl);
}

// --set KEY=VALUE: see case_parser.hpp.
void apply_override(toml::table& tbl, const std::string& key_eq_value) {
  const Override ov = split_override(key_eq_value);
  toml::table holder = parse_override_value(ov.text);
  toml::node& value = *holder.get("v");
  toml::node* parent = walk_to_parent(tbl, ov);
  const std::string& last = ov.segments.back();
  if (auto* arr = parent->as_array()) {
    const std::string where =
        ov.key.substr(0, ov.key.size() - std::min(ov.key.size(), last.size() + 1));
    const auto index = array_index(*arr, last, where, ov);
    arr->replace(arr->cbegin() + static_cast<std::ptrdiff_t>(index), std::move(value));
  } else {
    parent->as_table()->insert_or_assign(last, std::move(value));
  }
}

}  // namespace vrsph
