// Internal to the case-file layer (case_parser.hpp): reading one TOML table of a case with
// typed look-ups, range checks and one-line CaseErrors that name where (file:line or --set), the
// dotted key, the value and the reason. Each table is read against its list of allowed keys, so
// unknown keys are reported before anything else in that table.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vrsph/setup/case_parser.hpp"
#include "vrsph/setup/case_schema.hpp"

namespace vrsph::case_detail {

// Source name given to nodes created by apply_override().
inline constexpr std::string_view kSetSource = "--set";

// Error prefix for a node: "file:line: ", "--set " or "file: " (nodes without a source line).
std::string location_of(const toml::node* node, const std::string& source);

// Compact one-line TOML rendering of a node, for error messages.
std::string render_value(const toml::node& node);
// The same rendering uncut (render_value cuts long values).
std::string render_full(const toml::node& node);

// A TOML basic string literal with quotes and escapes.
std::string toml_quote(std::string_view text);

// "[a, b]" or "[a, b, c]": the first dim components, for messages.
std::string vec_text(const Vec3d& v, int dim);

// A value check for numbers: predicate plus the reason shown when it fails.
struct Check {
  bool (*ok)(double);
  const char* reason;
};
inline constexpr Check kAny{[](double) { return true; }, ""};
inline constexpr Check kPositive{[](double v) { return v > 0.0; }, "must be > 0"};
inline constexpr Check kNonNegative{[](double v) { return v >= 0.0; }, "must be >= 0"};
inline constexpr Check kUnitClosed{[](double v) { return v >= 0.0 && v <= 1.0; },
                                   "must be in [0, 1]"};
inline constexpr Check kBelowHalf{[](double v) { return v >= 0.0 && v < 0.5; },
                                  "must be in [0, 0.5) (0.5 is the fill on a free surface)"};
inline constexpr Check kBufferRamp{[](double v) { return v >= 0.0 && v <= 4.0; },
                                   "must be in [0, 4] (dp of each level; 0: off)"};
inline constexpr Check kShepardFill{[](double v) { return v >= 0.0 && v <= 2.0; },
                                    "must be in [0, 2] (0: off; 2: Shepard everywhere)"};
inline constexpr Check kBufferSpacing{[](double v) { return v >= 0.0 && v < 1.0; },
                                      "must be in [0, 1) (dp of each level; 0: off)"};
inline constexpr Check kFluxEdge{[](double v) { return v >= 0.0 && v < 1.0; },
                                 "must be in [0, 1) (a donor fill; 0: off)"};
inline constexpr Check kKinkRadius{[](double v) { return v >= 0.0; },
                                   "must be at least 0 (m; 0: 10 dp of level 0)"};
inline constexpr Check kRefreshInterval{[](double v) { return v > 0.0 && v <= 8.0; },
                                        "must be in (0, 8] (capillary time-step limits)"};
inline constexpr Check kUnitHalfOpen{[](double v) { return v > 0.0 && v <= 1.0; },
                                     "must be in (0, 1]"};

// Name of one value of an enum key.
template <class E>
struct EnumName {
  std::string_view name;
  E value;
};

// The name of an enum value (for writing the case back out).
template <class E, std::size_t N>
std::string_view enum_name(const EnumName<E> (&names)[N], E value) {
  for (const auto& n : names) {
    if (n.value == value) return n.name;
  }
  return "?";
}

// The names of every enum key, shared by the parser and the writer.
inline constexpr EnumName<ViscosityModel> kViscosityNames[] = {
    {"laminar", ViscosityModel::laminar}, {"artificial", ViscosityModel::artificial}};
inline constexpr EnumName<DiffusionModel> kDiffusionNames[] = {
    {"molteni", DiffusionModel::molteni},
    {"fourtakas", DiffusionModel::fourtakas},
    {"none", DiffusionModel::none}};
inline constexpr EnumName<ShiftingModel> kShiftingNames[] = {{"none", ShiftingModel::none},
                                                             {"lind", ShiftingModel::lind},
                                                             {"skillen", ShiftingModel::skillen}};
inline constexpr EnumName<BlockShape> kBlockShapeNames[] = {
    {"circle", BlockShape::circle}, {"sphere", BlockShape::sphere}, {"box", BlockShape::box}};
inline constexpr EnumName<FillMode> kFillNames[] = {{"lattice", FillMode::lattice},
                                                    {"rings", FillMode::rings},
                                                    {"rings_on_radius", FillMode::rings_on_radius},
                                                    {"cells", FillMode::cells}};
inline constexpr EnumName<WallShape> kWallShapeNames[] = {{"tank", WallShape::tank},
                                                          {"box", WallShape::box}};
inline constexpr EnumName<OutputPrecision> kPrecisionNames[] = {
    {"double", OutputPrecision::float64}, {"float32", OutputPrecision::float32}};
inline constexpr EnumName<Precision> kArithmeticNames[] = {{"double", Precision::double_precision},
                                                           {"mixed", Precision::mixed}};
inline constexpr EnumName<SurfaceRefresh> kRefreshNames[] = {
    {"every_step", SurfaceRefresh::every_step}, {"capillary", SurfaceRefresh::capillary}};
inline constexpr EnumName<BufferRounding> kBufferRoundingNames[] = {
    {"none", BufferRounding::none}, {"whole_dp", BufferRounding::whole_dp}};
inline constexpr EnumName<BufferSurface> kBufferSurfaceNames[] = {
    {"own", BufferSurface::own},
    {"edge", BufferSurface::edge},
    {"donor", BufferSurface::donor},
    {"donor_normals", BufferSurface::donor_normals},
    {"edge_kink", BufferSurface::edge_kink}};
inline constexpr EnumName<OutputCompression> kCompressionNames[] = {
    {"none", OutputCompression::none}, {"zlib", OutputCompression::zlib}};

// Typed reader over one table (or over nothing: an absent optional section).
class TableReader {
 public:
  // Checks that every key of tbl is in `keys` (CaseError otherwise); tbl may be null.
  TableReader(const toml::table* tbl, std::string path, std::string source, Keys keys);

  bool has(std::string_view key) const { return node(key) != nullptr; }
  // "section.key" (or "key" at the root).
  std::string key_path(std::string_view key) const;

  // Typed getters: nullopt when the key is absent, CaseError on a wrong type or failed check.
  std::optional<double> opt_number(std::string_view key, Check check = kAny) const;
  std::optional<int> opt_integer(std::string_view key) const;
  std::optional<bool> opt_bool(std::string_view key) const;
  std::optional<std::string> opt_string(std::string_view key) const;
  std::optional<Vec3d> opt_vector(std::string_view key, int dim) const;
  std::optional<std::vector<std::string>> opt_string_array(std::string_view key) const;
  template <class E, std::size_t N>
  std::optional<E> opt_enum(std::string_view key, const EnumName<E> (&names)[N]) const;

  // Sub-table (regular or inline); an absent one gives a reader over nothing.
  TableReader sub_table(std::string_view key, Keys keys) const;
  // Array of tables ([[key]]); absent gives an empty vector. Elements are "key.0", "key.1", ...
  std::vector<TableReader> table_array(std::string_view key, Keys keys) const;

  // The value of a required key, or CaseError "... required key is missing".
  template <class T>
  T req(std::string_view key, std::optional<T> value) const {
    if (!value) fail_missing(key);
    return *value;
  }
  // CaseError for `key` unless ok.
  void require(std::string_view key, bool ok, std::string_view reason) const {
    if (!ok) fail(key, reason);
  }
  // CaseError when `key` is present: it has no meaning in this context.
  void forbid(std::string_view key, std::string_view reason) const {
    if (has(key)) fail(key, reason);
  }
  // CaseError "<where><path.key> = <value>: <reason>" (value omitted when the key is absent).
  [[noreturn]] void fail(std::string_view key, std::string_view reason) const;
  [[noreturn]] void fail_missing(std::string_view key) const;

 private:
  const toml::node* node(std::string_view key) const;
  void check_keys(Keys keys) const;
  [[noreturn]] void fail_missing_reason(std::string_view key, std::string_view reason) const;

  const toml::table* tbl_;
  std::string path_;
  std::string source_;
};

template <class E, std::size_t N>
std::optional<E> TableReader::opt_enum(std::string_view key, const EnumName<E> (&names)[N]) const {
  const auto text = opt_string(key);
  if (!text) return std::nullopt;
  std::string options;
  for (const auto& n : names) {
    if (n.name == *text) return n.value;
    options += (options.empty() ? "" : ", ") + toml_quote(n.name);
  }
  fail(key, "must be one of " + options);
}

}  // namespace vrsph::case_detail
