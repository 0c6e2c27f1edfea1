// parse_case(): reads the case file one function per table, against the key lists of
// case_schema.hpp, with the defaults and checks that docs/cases.md describes; and
// known_case_keys(). Reading and error formatting are in case_reader.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "vrsph/setup/case_checks.hpp"
#include "vrsph/setup/case_parser.hpp"
#include "vrsph/setup/case_reader.hpp"
#include "vrsph/setup/case_schema.hpp"

namespace vrsph {
namespace {

using namespace case_detail;

// "[a, b]" or "[a, b, c]": the first dim components, for messages.
std::string vec_text(const Vec3d& v, int dim) {
  std::string out = "[";
  for (int k = 0; k < dim; ++k) out += fmt::format("{}{}", k ? ", " : "", v[k]);
  return out + "]";
}

// True when a[k] < b[k] for every k < dim.
bool all_less(const Vec3d& a, const Vec3d& b, int dim) {
  for (int k = 0; k < dim; ++k) {
    if (!(a[k] < b[k])) return false;
  }
  return true;
}

// The longest file or folder name most file systems take (ext4, XFS, APFS, NTFS: 255 bytes).
constexpr std::size_t kMaxFileName = 255;
// Integer keys beyond these make no sense and would only overflow counts further on.
constexpr int kMaxLayers = 1000;   // a wall needs 2h / dp = 2 h_over_dp layers
constexpr int kMaxDpRatio = 1000;  // dp_ratio 2 (3, 4) is the usual refinement

bool portable_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

// A case name usable as a folder name on any system: the POSIX portable file-name characters
// [A-Za-z0-9._-], not starting with '.' (hidden, '.', '..') or '-' (read as an option).
bool valid_case_name(const std::string& name) {
  if (name.empty() || name.front() == '.' || name.front() == '-') return false;
  return std::all_of(name.begin(), name.end(), [](char c) { return portable_char(c) || c == '.'; });
}

// A safe file-name fragment: [A-Za-z0-9_-]+.
bool valid_file_fragment(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), portable_char);
}

// The longest line name whose files fit kMaxFileName: the atomic writer's temporary
// ".line_<name>_<index>.csv.tmpXXXXXX" (output/atomic_file.cpp), with the index of the last
// snapshot (4 digits, more when the case writes more snapshots).
std::size_t max_line_name(const CaseSpec& spec) {
  const double snapshots = spec.output_interval > 0.0 ? spec.end_time / spec.output_interval : 1.0;
  const std::size_t digits =
      std::max<std::size_t>(4, fmt::format("{:.0f}", std::ceil(snapshots) + 1.0).size());
  const std::size_t fixed = std::string_view(".line_").size() + 1 + digits +
                            std::string_view(".csv").size() + std::string_view(".tmpXXXXXX").size();
  return kMaxFileName - fixed;
}

// Required min and max vectors with min < max in every component.
void read_box(const TableReader& r, int dim, Vec3d& min, Vec3d& max) {
  min = r.req("min", r.opt_vector("min", dim));
  max = r.req("max", r.opt_vector("max", dim));
  r.require("max", all_less(min, max, dim),
            fmt::format("must be > min = {} in every component", vec_text(min, dim)));
}

// [case]: name, dimension, end_time (all required).
void parse_case_table(const TableReader& r, CaseSpec& spec) {
  spec.name = r.req("name", r.opt_string("name"));
  r.require("name", valid_case_name(spec.name),
            "must be a folder name of the characters A-Z a-z 0-9 . _ - (not starting with '.' or "
            "'-'): it names the output folder");
  r.require("name", spec.name.size() <= kMaxFileName,
            fmt::format("is {} bytes long: the output folder's name can have at most {}",
                        spec.name.size(), kMaxFileName));
  spec.dimension = r.req("dimension", r.opt_integer("dimension"));
  r.require("dimension", spec.dimension == 2 || spec.dimension == 3, "must be 2 or 3");
  spec.end_time = r.req("end_time", r.opt_number("end_time", kPositive));
}

// [resolution] and [fluid].
void parse_resolution_and_fluid(const TableReader& res, const TableReader& fl, CaseSpec& spec) {
  spec.dp = res.req("dp", res.opt_number("dp", kPositive));
  spec.h_over_dp = res.opt_number("h_over_dp", kPositive).value_or(spec.h_over_dp);
  FluidSpec& f = spec.fluid;
  f.density = fl.opt_number("density", kPositive).value_or(f.density);
  f.kinematic_viscosity =
      fl.opt_number("kinematic_viscosity", kNonNegative).value_or(f.kinematic_viscosity);
  f.surface_tension = fl.opt_number("surface_tension", kNonNegative).value_or(f.surface_tension);
  f.gravity = fl.opt_vector("gravity", spec.dimension).value_or(Vec3d{});
}

// [eos]: gamma, max_speed (optional), sound_speed_factor, sound_speed (optional).
void parse_eos(const TableReader& r, EosParams& p) {
  p.gamma = r.opt_number("gamma", kPositive).value_or(p.gamma);
  p.max_speed = r.opt_number("max_speed", kPositive);
  p.sound_speed_factor =
      r.opt_number("sound_speed_factor", kPositive).value_or(p.sound_speed_factor);
  p.sound_speed = r.opt_number("sound_speed", kPositive);
}

// The model tables of [numerics] (inline tables), each read into its physics/ struct. `n` is
// the [numerics] reader.

// numerics.viscosity: model (default laminar), alpha.
void read_viscosity(const TableReader& n, ViscosityParams& p) {
  const auto r = n.sub_table("viscosity", kViscosityKeys);
  p.model = r.opt_enum("model", kViscosityNames).value_or(p.model);
  p.alpha = r.opt_number("alpha", kNonNegative).value_or(p.alpha);
}

// numerics.density_diffusion: model (default molteni), delta.
void read_density_diffusion(const TableReader& n, DiffusionParams& p) {
  const auto r = n.sub_table("density_diffusion", kDiffusionKeys);
  p.model = r.opt_enum("model", kDiffusionNames).value_or(p.model);
  p.delta = r.opt_number("delta", kNonNegative).value_or(p.delta);
}

// numerics.shifting: model (default none), coefficient (0.05 lind / 2 skillen),
// surface_threshold (1.5 in 2D, 2.75 in 3D; must lie in [0, dimension)).
void read_shifting(const TableReader& n, int dim, ShiftingParams& p) {
  const auto r = n.sub_table("shifting", kShiftingKeys);
  p.model = r.opt_enum("model", kShiftingNames).value_or(p.model);
  const double coefficient = p.model == ShiftingModel::skillen ? 2.0 : 0.05;
  p.coefficient = r.opt_number("coefficient", kNonNegative).value_or(coefficient);
  const double threshold = dim == 2 ? 1.5 : 2.75;
  p.surface_threshold = r.opt_number("surface_threshold", kNonNegative).value_or(threshold);
  r.require("surface_threshold", p.surface_threshold < dim,
            fmt::format("must be < dimension ({})", dim));
}

// numerics.surface_tension: the normal's thresholds and the options beyond Cen et al.
void read_surface_tension(const TableReader& n, SurfaceTensionParams& p) {
  const auto r = n.sub_table("surface_tension", kSurfaceTensionKeys);
  p.lambda_threshold = r.opt_number("lambda_threshold", kUnitClosed).value_or(p.lambda_threshold);
  p.normal_epsilon = r.opt_number("normal_epsilon", kNonNegative).value_or(p.normal_epsilon);
  p.surface_offset = r.opt_bool("surface_offset").value_or(p.surface_offset);
  p.curvature_correction = r.opt_bool("curvature_correction").value_or(p.curvature_correction);
  p.zero_net_force = r.opt_bool("zero_net_force").value_or(p.zero_net_force);
  p.refresh = r.opt_enum("refresh", kRefreshNames).value_or(p.refresh);
  p.refresh_interval =
      r.opt_number("refresh_interval", kRefreshInterval).value_or(p.refresh_interval);
}

// [numerics]: cfl, precision, the model tables, the coupling's keys and the start.
void parse_numerics(const TableReader& r, CaseSpec& spec) {
  NumericsSpec& n = spec.numerics;
  n.cfl = r.opt_number("cfl", kUnitHalfOpen).value_or(n.cfl);
  n.precision = r.opt_enum("precision", kArithmeticNames).value_or(n.precision);
  read_viscosity(r, n.viscosity);
  read_density_diffusion(r, n.density_diffusion);
  read_shifting(r, spec.dimension, n.shifting);
  read_surface_tension(r, n.surface_tension);
  auto flag = [&r](const char* key, bool& v) { v = r.opt_bool(key).value_or(v); };
  auto number = [&r](const char* key, const Check& c, double& v) {
    v = r.opt_number(key, c).value_or(v);
  };
  flag("vres_conserve_momentum", spec.vres_conserve_momentum);
  number("vres_buffer_fill_min", kBelowHalf, spec.vres_buffer_fill_min);
  number("vres_buffer_ramp", kBufferRamp, spec.vres_buffer_ramp);
  flag("vres_surface_across_levels", spec.vres_surface_across_levels);
  number("vres_shepard_fill", kShepardFill, spec.vres_shepard_fill);
  number("vres_buffer_spacing", kBufferSpacing, spec.vres_buffer_spacing);
  number("vres_flux_edge", kFluxEdge, spec.vres_flux_edge);
  number("vres_kink_radius", kKinkRadius, spec.vres_kink_radius);
  spec.vres_buffer_surface =
      r.opt_enum("vres_buffer_surface", kBufferSurfaceNames).value_or(spec.vres_buffer_surface);
  flag("hydrostatic_initial_density", n.hydrostatic_initial_density);
  flag("local_time_stepping", n.local_time_stepping);
  n.start_damping_time =
      r.opt_number("start_damping_time", kNonNegative).value_or(n.start_damping_time);
  n.start_damping_tau = r.opt_number("start_damping_tau", kPositive).value_or(n.start_damping_tau);
}

// One [[fluid_block]]: circle/sphere (center, radius >= dp) or box (min, max).
FluidBlock parse_fluid_block(const TableReader& r, const CaseSpec& spec) {
  const int dim = spec.dimension;
  FluidBlock b;
  b.shape = r.req("shape", r.opt_enum("shape", kBlockShapeNames));
  if (b.shape == BlockShape::box) {
    r.forbid("center", "not used with shape = \"box\" (give min and max)");
    r.forbid("radius", "not used with shape = \"box\" (give min and max)");
    read_box(r, dim, b.min, b.max);
  } else {
    r.require("shape", (b.shape == BlockShape::circle) == (dim == 2),
              dim == 2 ? "a 2D case uses \"circle\" (or \"box\")"
                       : "a 3D case uses \"sphere\" (or \"box\")");
    r.forbid("min", "not used with a round shape (give center and radius)");
    r.forbid("max", "not used with a round shape (give center and radius)");
    b.center = r.req("center", r.opt_vector("center", dim));
    b.radius = r.req("radius", r.opt_number("radius", kPositive));
    r.require("radius", b.radius >= spec.dp, fmt::format("must be >= resolution.dp ({})", spec.dp));
  }
  b.fill = r.opt_enum("fill", kFillNames).value_or(b.fill);
  r.require("fill",
            (b.fill != FillMode::rings && b.fill != FillMode::rings_on_radius) ||
                b.shape == BlockShape::circle,
            "\"rings\" and \"rings_on_radius\" need shape = \"circle\" (2D only)");
  r.require("fill", b.fill != FillMode::cells || b.shape == BlockShape::box,
            "\"cells\" needs shape = \"box\"");
  b.velocity = r.opt_vector("velocity", dim).value_or(Vec3d{});
  b.pressure = r.opt_number("pressure").value_or(0.0);
  return b;
}

// One [[wall_block]]: shape (tank | box), min, max, layers >= 1, thin.
WallBlock parse_wall_block(const TableReader& r, const CaseSpec& spec) {
  WallBlock w;
  w.shape = r.req("shape", r.opt_enum("shape", kWallShapeNames));
  read_box(r, spec.dimension, w.min, w.max);
  w.layers = r.opt_integer("layers").value_or(w.layers);
  r.require(
      "layers", w.layers >= 1 && w.layers <= kMaxLayers,
      fmt::format("must be in [1, {}] (a wall needs 2h / dp = 2 x h_over_dp layers)", kMaxLayers));
  w.thin = r.opt_bool("thin").value_or(false);
  return w;
}

// [domain]: min and max together (or neither), max_lost_fraction in [0, 1].
void parse_domain(const TableReader& r, CaseSpec& spec) {
  if (r.has("min") || r.has("max")) {
    Vec3d min{}, max{};
    if (!r.has("max")) r.fail("max", "required when domain.min is given");
    if (!r.has("min")) r.fail("min", "required when domain.max is given");
    read_box(r, spec.dimension, min, max);
    spec.domain_min = min;
    spec.domain_max = max;
  }
  spec.max_lost_fraction =
      r.opt_number("max_lost_fraction", kUnitClosed).value_or(spec.max_lost_fraction);
}

// One [[refinement]]: box inside the domain (when given), dp_ratio >= 2, buffer_width > 0.
RefinementBox parse_refinement(const TableReader& r, const CaseSpec& spec) {
  const int dim = spec.dimension;
  RefinementBox b;
  read_box(r, dim, b.min, b.max);
  if (spec.domain_min && spec.domain_max) {
    const std::string reason =
        fmt::format("refinement box must lie inside the domain (domain.min = {}, domain.max = {})",
                    vec_text(*spec.domain_min, dim), vec_text(*spec.domain_max, dim));
    for (int k = 0; k < dim; ++k) {
      r.require("min", b.min[k] >= (*spec.domain_min)[k], reason);
      r.require("max", b.max[k] <= (*spec.domain_max)[k], reason);
    }
  }
  b.dp_ratio = r.opt_integer("dp_ratio").value_or(b.dp_ratio);
  r.require("dp_ratio", b.dp_ratio >= 2 && b.dp_ratio <= kMaxDpRatio,
            fmt::format("must be in [2, {}]", kMaxDpRatio));
  b.buffer_width = r.opt_number("buffer_width", kPositive).value_or(b.buffer_width);
  b.buffer_rounding =
      r.opt_enum("buffer_rounding", kBufferRoundingNames).value_or(b.buffer_rounding);
  return b;
}

// [[output.line]] segments: names unique, fit for a file name and not ending in "_interp" (the
// interpolated line of "a" is line_a_interp_NNNN.csv, which a line "a_interp" would overwrite).
void parse_lines(const TableReader& r, CaseSpec& spec) {
  std::set<std::string> names;
  for (const auto& lr : r.table_array("line", kLineKeys)) {
    OutputLine line;
    line.name = lr.req("name", lr.opt_string("name"));
    lr.require("name", valid_file_fragment(line.name), "must match [A-Za-z0-9_-]+");
    lr.require("name", !line.name.ends_with("_interp"),
               "must not end in \"_interp\" (reserved for the interpolated line files)");
    const std::size_t longest = max_line_name(spec) - std::string_view("_interp").size();
    lr.require("name", line.name.size() <= longest,
               fmt::format("is {} bytes long: at most {} fit the {}-byte file names "
                           "line_<name>_interp_NNNN.csv (and their temporary names)",
                           line.name.size(), longest, kMaxFileName));
    lr.require("name", names.insert(line.name).second, "duplicate line name");
    line.from = lr.req("from", lr.opt_vector("from", spec.dimension));
    line.to = lr.req("to", lr.opt_vector("to", spec.dimension));
    lr.require("to", line.to != line.from, "must differ from `from` (zero-length line)");
    spec.lines.push_back(line);
  }
}

// [[output.probe]] points: names unique and fit for a file name.
void parse_probes(const TableReader& r, CaseSpec& spec) {
  std::set<std::string> names;
  for (const auto& pr : r.table_array("probe", kProbeKeys)) {
    OutputProbe probe;
    probe.name = pr.req("name", pr.opt_string("name"));
    pr.require("name", valid_file_fragment(probe.name), "must match [A-Za-z0-9_-]+");
    pr.require("name", names.insert(probe.name).second, "duplicate probe name");
    probe.position = pr.req("position", pr.opt_vector("position", spec.dimension));
    spec.probes.push_back(probe);
  }
}

// [output]: interval >= 0, formats from {"vtp", "csv"}, precision and compression of the
// snapshots, [[output.line]] segments, [[output.probe]] points.
void parse_output(const TableReader& r, CaseSpec& spec) {
  spec.output_interval = r.opt_number("interval", kNonNegative).value_or(spec.output_interval);
  if (const auto formats = r.opt_string_array("formats")) {
    spec.write_vtp = spec.write_csv = false;
    for (const auto& f : *formats) {
      r.require("formats", f == "vtp" || f == "csv", "formats must be \"vtp\" or \"csv\"");
      (f == "vtp" ? spec.write_vtp : spec.write_csv) = true;
    }
  }
  spec.output_precision = r.opt_enum("precision", kPrecisionNames).value_or(spec.output_precision);
  spec.output_compression =
      r.opt_enum("compression", kCompressionNames).value_or(spec.output_compression);
  parse_lines(r, spec);
  parse_probes(r, spec);
}

}  // namespace

// Validates the whole case table; see case_parser.hpp.
CaseSpec parse_case(const toml::table& tbl, const std::string& source_name) {
  const TableReader root(&tbl, "", source_name, kRootKeys);
  CaseSpec spec;
  parse_case_table(root.sub_table("case", kCaseKeys), spec);
  parse_resolution_and_fluid(root.sub_table("resolution", kResolutionKeys),
                             root.sub_table("fluid", kFluidKeys), spec);
  parse_eos(root.sub_table("eos", kEosKeys), spec.eos);
  parse_numerics(root.sub_table("numerics", kNumericsKeys), spec);
  const auto fluid_readers = root.table_array("fluid_block", kFluidBlockKeys);
  for (const auto& r : fluid_readers) spec.fluid_blocks.push_back(parse_fluid_block(r, spec));
  root.require("fluid_block", !spec.fluid_blocks.empty(),
               "at least one [[fluid_block]] is required");
  const auto wall_readers = root.table_array("wall_block", kWallBlockKeys);
  for (const auto& r : wall_readers) spec.wall_blocks.push_back(parse_wall_block(r, spec));
  root.sub_table("numerics", kNumericsKeys)
      .sub_table("surface_tension", kSurfaceTensionKeys)
      .require("zero_net_force",
               !(spec.numerics.surface_tension.zero_net_force && !spec.wall_blocks.empty()),
               "true with walls: the net capillary force is zero only on a closed free surface "
               "(drops); with walls it is real");
  parse_domain(root.sub_table("domain", kDomainKeys), spec);
  const auto refinement_readers = root.table_array("refinement", kRefinementKeys);
  for (const auto& r : refinement_readers) spec.refinements.push_back(parse_refinement(r, spec));
  parse_output(root.sub_table("output", kOutputKeys), spec);
  spec.laplace_pressure =
      root.sub_table("analysis", kAnalysisKeys).opt_number("laplace_pressure", kPositive);
  check_geometry({fluid_readers, wall_readers, refinement_readers}, spec);
  return spec;
}

namespace {

// The schema table at `path`, or null.
const SchemaTable* schema_table(std::string_view path) {
  for (const SchemaTable& t : kCaseSchema) {
    if (t.path == path) return &t;
  }
  return nullptr;
}

// "a.b" (or "b" when a is empty).
std::string join_key(std::string_view a, std::string_view b) {
  return a.empty() ? std::string(b) : fmt::format("{}.{}", a, b);
}

// The --set form of a table's path: ".N" after every array of tables on the way
// ("output.line" -> "output.line.N").
std::string set_path(std::string_view path) {
  std::string out, prefix;
  while (!path.empty()) {
    const std::size_t dot = path.find('.');
    const std::string_view seg = path.substr(0, dot);
    prefix = join_key(prefix, seg);
    out = join_key(out, seg);
    const SchemaTable* t = schema_table(prefix);
    if (t != nullptr && t->array) out += ".N";
    path = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
  }
  return out;
}

}  // namespace

// The leaves of kCaseSchema; see case_parser.hpp.
std::vector<std::string> known_case_keys() {
  std::vector<std::string> out;
  for (const SchemaTable& t : kCaseSchema) {
    for (const std::string_view k : t.keys) {
      if (schema_table(join_key(t.path, k)) != nullptr) continue;  // a table: its keys follow
      out.push_back(join_key(set_path(t.path), k));
    }
  }
  return out;
}

}  // namespace vrsph
