// case_to_toml(): the resolved case written back as TOML with every default filled in, in the
// layout of docs/cases.md. parse_case() of the result gives back an equal CaseSpec (numbers are
// written in their shortest exact round-trip form).
#include <fmt/format.h>

#include "vrsph/setup/case_parser.hpp"
#include "vrsph/setup/case_reader.hpp"

namespace vrsph {
namespace {

using namespace case_detail;

constexpr std::size_t kCommentColumn = 40;  // comments start here when the line is shorter

// A double as a TOML float: shortest round-trip digits, always with '.' or an exponent.
std::string num(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// First dim components as a TOML array of floats.
std::string vec(const Vec3d& v, int dim) {
  std::string out = "[";
  for (int k = 0; k < dim; ++k) out += (k ? ", " : "") + num(v[k]);
  return out + "]";
}

// Accumulates "key = value  # comment" lines.
struct Writer {
  std::string out;

  // One key/value line, with an optional comment aligned to kCommentColumn.
  void kv(std::string_view key, const std::string& value, std::string_view comment = {}) {
    std::string line = fmt::format("{} = {}", key, value);
    if (!comment.empty()) {
      line.resize(std::max(line.size() + 2, kCommentColumn), ' ');
      line += fmt::format("# {}", comment);
    }
    out += line + "\n";
  }
  // A table header ("[name]" or "[[name]]") preceded by a blank line.
  void header(std::string_view text) { out += fmt::format("\n{}\n", text); }
  void comment(std::string_view text) { out += fmt::format("# {}\n", text); }
};

// [case], [fluid], [eos], [resolution].
void write_physics(Writer& w, const CaseSpec& s) {
  const int dim = s.dimension;
  w.header("[case]");
  w.kv("name", toml_quote(s.name));
  w.kv("dimension", fmt::format("{}", dim));
  w.kv("end_time", num(s.end_time), "s");
  w.header("[fluid]");
  w.kv("density", num(s.fluid.density), "kg/m^3");
  w.kv("kinematic_viscosity", num(s.fluid.kinematic_viscosity), "m^2/s");
  w.kv("surface_tension", num(s.fluid.surface_tension), "N/m");
  w.kv("gravity", vec(s.fluid.gravity, dim), "m/s^2");
  w.header("[eos]");
  w.kv("gamma", num(s.eos.gamma));
  if (s.eos.max_speed) {
    w.kv("max_speed", num(*s.eos.max_speed), "m/s");
  } else {
    w.comment("max_speed: not set (sqrt(g H) for gravity cases)");
  }
  w.kv("sound_speed_factor", num(s.eos.sound_speed_factor), "c0 = factor * max_speed");
  if (s.eos.sound_speed) {
    w.kv("sound_speed", num(*s.eos.sound_speed), "m/s, overrides the two above");
  } else {
    w.comment("sound_speed: not set");
  }
  w.header("[resolution]");
  w.kv("dp", num(s.dp), "m, spacing of level 0");
  w.kv("h_over_dp", num(s.h_over_dp));
}

const char* toml_bool(bool b) { return b ? "true" : "false"; }

// The model tables of [numerics], as inline tables.
std::string viscosity_table(const ViscosityParams& p) {
  return fmt::format("{{ model = {}, alpha = {} }}",
                     toml_quote(enum_name(kViscosityNames, p.model)), num(p.alpha));
}

std::string density_diffusion_table(const DiffusionParams& p) {
  return fmt::format("{{ model = {}, delta = {} }}",
                     toml_quote(enum_name(kDiffusionNames, p.model)), num(p.delta));
}

std::string shifting_table(const ShiftingParams& p) {
  return fmt::format("{{ model = {}, coefficient = {}, surface_threshold = {} }}",
                     toml_quote(enum_name(kShiftingNames, p.model)), num(p.coefficient),
                     num(p.surface_threshold));
}

// The refresh keys are written only when not "every_step", so that checkpoints made before they
// existed (their physical keys lack them) still resume: a run folder's case.toml without them
// refreshed every step (app/main.cpp, load_run_case), although "capillary" is the default.
std::string surface_tension_table(const SurfaceTensionParams& p) {
  const std::string refresh =
      p.refresh == SurfaceRefresh::every_step
          ? std::string()
          : fmt::format(", refresh = {}, refresh_interval = {}",
                        toml_quote(enum_name(kRefreshNames, p.refresh)), num(p.refresh_interval));
  return fmt::format(
      "{{ lambda_threshold = {}, normal_epsilon = {}, surface_offset = {}, "
      "curvature_correction = {}, zero_net_force = {}{} }}",
      num(p.lambda_threshold), num(p.normal_epsilon), toml_bool(p.surface_offset),
      toml_bool(p.curvature_correction), toml_bool(p.zero_net_force), refresh);
}

// [numerics] with its inline model tables.
void write_numerics(Writer& w, const CaseSpec& s) {
  const NumericsSpec& n = s.numerics;
  w.header("[numerics]");
  w.kv("cfl", num(n.cfl));
  // Written only when not "double", so that checkpoints made before the key existed (their
  // physical keys lack it) still resume: a run folder's case.toml without it ran in double
  // (app/main.cpp, load_run_case), although "mixed" is the default of case files.
  if (n.precision != Precision::double_precision)
    w.kv("precision", toml_quote(enum_name(kArithmeticNames, n.precision)),
         "of the force pass: double | mixed");
  w.kv("viscosity", viscosity_table(n.viscosity), "alpha: artificial only");
  w.kv("density_diffusion", density_diffusion_table(n.density_diffusion));
  w.kv("shifting", shifting_table(n.shifting));
  w.kv("surface_tension", surface_tension_table(n.surface_tension));
  w.kv("hydrostatic_initial_density", toml_bool(n.hydrostatic_initial_density));
  if (n.local_time_stepping)  // written only when on, as precision
    w.kv("local_time_stepping", "true", "each resolution level on its own dt");
  if (n.start_damping_time > 0.0) {  // written only when on, as precision
    w.kv("start_damping_time", num(n.start_damping_time), "s: fluid velocities damped before");
    w.kv("start_damping_tau", num(n.start_damping_tau), "s: their decay time meanwhile");
  }
  w.kv("vres_conserve_momentum", toml_bool(s.vres_conserve_momentum));
  w.kv("vres_buffer_fill_min", num(s.vres_buffer_fill_min),
       "donor fill below which a buffer particle is deleted (0.5 on a free surface)");
  if (s.vres_buffer_ramp > 0.0)  // written only when on: older run folders resume without it
    w.kv("vres_buffer_ramp", num(s.vres_buffer_ramp),
         "dp over which buffer volumes ramp to 0 at the shell's outer edge");
  if (s.vres_surface_across_levels)  // written only when on, as the ramp
    w.kv("vres_surface_across_levels", "true", "surface fields over the fluid of both levels");
  if (s.vres_shepard_fill > 0.0)  // written only when on
    w.kv("vres_shepard_fill", num(s.vres_shepard_fill),
         "donor fill below which buffer values are Shepard averages");
  if (s.vres_flux_edge > 0.0)  // written only when on
    w.kv("vres_flux_edge", num(s.vres_flux_edge),
         "donor fill below which mass points pass their flux inward");
  if (s.vres_buffer_spacing > 0.0)  // written only when on
    w.kv("vres_buffer_spacing", num(s.vres_buffer_spacing),
         "dp within which buffer particles are moved apart");
  if (s.vres_buffer_surface != BufferSurface::edge)  // written only when not the default
    w.kv("vres_buffer_surface", toml_quote(enum_name(kBufferSurfaceNames, s.vres_buffer_surface)),
         "buffers' lambda and normal: own | edge | donor | donor_normals | edge_kink");
  if (s.vres_kink_radius > 0.0)  // written only when set
    w.kv("vres_kink_radius", num(s.vres_kink_radius),
         "m; edge_kink's threshold on |n_d - n_o| is dp_coarse / this");
}

// [[fluid_block]] and [[wall_block]].
void write_blocks(Writer& w, const CaseSpec& s) {
  const int dim = s.dimension;
  for (const auto& b : s.fluid_blocks) {
    w.header("[[fluid_block]]");
    w.kv("shape", toml_quote(enum_name(kBlockShapeNames, b.shape)));
    if (b.shape == BlockShape::box) {
      w.kv("min", vec(b.min, dim), "m");
      w.kv("max", vec(b.max, dim), "m");
    } else {
      w.kv("center", vec(b.center, dim), "m");
      w.kv("radius", num(b.radius), "m");
    }
    w.kv("fill", toml_quote(enum_name(kFillNames, b.fill)));
    w.kv("velocity", vec(b.velocity, dim), "m/s");
    w.kv("pressure", num(b.pressure), "Pa, initial (density from the EOS)");
  }
  for (const auto& b : s.wall_blocks) {
    w.header("[[wall_block]]");
    w.kv("shape", toml_quote(enum_name(kWallShapeNames, b.shape)));
    w.kv("min", vec(b.min, dim), "m");
    w.kv("max", vec(b.max, dim), "m");
    w.kv("layers", fmt::format("{}", b.layers));
    if (b.thin) w.kv("thin", "true", "thinner than the support, accepted");
  }
}

// [domain] and [[refinement]].
void write_domain(Writer& w, const CaseSpec& s) {
  const int dim = s.dimension;
  w.header("[domain]");
  if (s.domain_min && s.domain_max) {
    w.kv("min", vec(*s.domain_min, dim), "m");
    w.kv("max", vec(*s.domain_max, dim), "m");
  } else {
    w.comment("min, max: not set (bounding box of all particles + margin)");
  }
  w.kv("max_lost_fraction", num(s.max_lost_fraction));
  for (const auto& r : s.refinements) {
    w.header("[[refinement]]");
    w.kv("min", vec(r.min, dim), "m");
    w.kv("max", vec(r.max, dim), "m");
    w.kv("dp_ratio", fmt::format("{}", r.dp_ratio));
    w.kv("buffer_width", num(r.buffer_width), "in units of each level's h");
    // Written only when set: case files of earlier runs have no such key and mean "none".
    if (r.buffer_rounding != BufferRounding::none)
      w.kv("buffer_rounding", toml_quote(enum_name(kBufferRoundingNames, r.buffer_rounding)));
  }
}

// [output], [[output.line]], [[output.probe]] and [analysis].
void write_output(Writer& w, const CaseSpec& s) {
  w.header("[output]");
  w.kv("interval", num(s.output_interval), "s; 0 = first and last snapshot only");
  std::string formats;
  if (s.write_vtp) formats += "\"vtp\"";
  if (s.write_csv) formats += std::string(formats.empty() ? "" : ", ") + "\"csv\"";
  w.kv("formats", "[" + formats + "]");
  w.kv("precision", toml_quote(enum_name(kPrecisionNames, s.output_precision)),
       "particle fields of the snapshots; positions stay double");
  w.kv("compression", toml_quote(enum_name(kCompressionNames, s.output_compression)),
       ".vtp appended data");
  for (const auto& line : s.lines) {
    w.header("[[output.line]]");
    w.kv("name", toml_quote(line.name));
    w.kv("from", vec(line.from, s.dimension), "m");
    w.kv("to", vec(line.to, s.dimension), "m");
  }
  for (const auto& probe : s.probes) {
    w.header("[[output.probe]]");
    w.kv("name", toml_quote(probe.name));
    w.kv("position", vec(probe.position, s.dimension), "m");
  }
  w.header("[analysis]");
  if (s.laplace_pressure) {
    w.kv("laplace_pressure", num(*s.laplace_pressure), "Pa");
  } else {
    w.comment("laplace_pressure: not set");
  }
}

}  // namespace

// The resolved case as TOML; see case_parser.hpp.
std::string case_to_toml(const CaseSpec& spec) {
  Writer w;
  w.comment("vrsph case as resolved: every default filled in, --set overrides applied.");
  write_physics(w, spec);
  write_numerics(w, spec);
  write_blocks(w, spec);
  write_domain(w, spec);
  write_output(w, spec);
  return w.out;
}

}  // namespace vrsph
