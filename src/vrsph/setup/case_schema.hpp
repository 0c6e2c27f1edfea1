// The case-file schema: the allowed keys of every table, the lists the parser checks each table
// against (case_sections.cpp; anything else is an "unknown key" error), and the list of tables
// that ties them to their dotted paths. known_case_keys() (case_parser.hpp) walks it, and
// tests/test_case_docs.cpp checks that docs/cases.md describes every key. A new key goes into its
// table's list here; a new table needs its list and its entry in kCaseSchema.
#pragma once

#include <span>
#include <string_view>

namespace vrsph::case_detail {

using Keys = std::span<const std::string_view>;

inline constexpr std::string_view kRootKeys[] = {
    "case",       "fluid",  "eos",        "resolution", "numerics", "fluid_block",
    "wall_block", "domain", "refinement", "output",     "analysis"};
inline constexpr std::string_view kCaseKeys[] = {"name", "dimension", "end_time"};
inline constexpr std::string_view kFluidKeys[] = {"density", "kinematic_viscosity",
                                                  "surface_tension", "gravity"};
inline constexpr std::string_view kEosKeys[] = {"gamma", "max_speed", "sound_speed_factor",
                                                "sound_speed"};
inline constexpr std::string_view kResolutionKeys[] = {"dp", "h_over_dp"};
inline constexpr std::string_view kNumericsKeys[] = {"cfl",
                                                     "precision",
                                                     "viscosity",
                                                     "density_diffusion",
                                                     "shifting",
                                                     "surface_tension",
                                                     "hydrostatic_initial_density",
                                                     "local_time_stepping",
                                                     "start_damping_time",
                                                     "start_damping_tau",
                                                     "vres_conserve_momentum",
                                                     "vres_buffer_fill_min",
                                                     "vres_buffer_ramp",
                                                     "vres_surface_across_levels",
                                                     "vres_buffer_surface",
                                                     "vres_shepard_fill",
                                                     "vres_buffer_spacing",
                                                     "vres_flux_edge",
                                                     "vres_kink_radius"};
// The model tables of [numerics] (usually written as inline tables).
inline constexpr std::string_view kViscosityKeys[] = {"model", "alpha"};
inline constexpr std::string_view kDiffusionKeys[] = {"model", "delta"};
inline constexpr std::string_view kShiftingKeys[] = {"model", "coefficient", "surface_threshold"};
inline constexpr std::string_view kSurfaceTensionKeys[] = {
    "lambda_threshold", "normal_epsilon", "surface_offset",  "curvature_correction",
    "zero_net_force",   "refresh",        "refresh_interval"};
inline constexpr std::string_view kFluidBlockKeys[] = {"shape", "center", "radius",   "min",
                                                       "max",   "fill",   "velocity", "pressure"};
inline constexpr std::string_view kWallBlockKeys[] = {"shape", "min", "max", "layers", "thin"};
inline constexpr std::string_view kDomainKeys[] = {"min", "max", "max_lost_fraction"};
inline constexpr std::string_view kRefinementKeys[] = {"min", "max", "dp_ratio", "buffer_width",
                                                       "buffer_rounding"};
inline constexpr std::string_view kOutputKeys[] = {"interval",    "formats", "precision",
                                                   "compression", "line",    "probe"};
inline constexpr std::string_view kLineKeys[] = {"name", "from", "to"};
inline constexpr std::string_view kProbeKeys[] = {"name", "position"};
inline constexpr std::string_view kAnalysisKeys[] = {"laplace_pressure"};

// One table of the schema: its dotted path ("" for the top level), its allowed keys, and whether
// it is an array of tables ([[name]]: its elements are "name.0", "name.1", ...).
struct SchemaTable {
  std::string_view path;
  Keys keys;
  bool array = false;
};

inline constexpr SchemaTable kCaseSchema[] = {
    {"", kRootKeys},
    {"case", kCaseKeys},
    {"fluid", kFluidKeys},
    {"eos", kEosKeys},
    {"resolution", kResolutionKeys},
    {"numerics", kNumericsKeys},
    {"numerics.viscosity", kViscosityKeys},
    {"numerics.density_diffusion", kDiffusionKeys},
    {"numerics.shifting", kShiftingKeys},
    {"numerics.surface_tension", kSurfaceTensionKeys},
    {"fluid_block", kFluidBlockKeys, true},
    {"wall_block", kWallBlockKeys, true},
    {"domain", kDomainKeys},
    {"refinement", kRefinementKeys, true},
    {"output", kOutputKeys},
    {"output.line", kLineKeys, true},
    {"output.probe", kProbeKeys, true},
    {"analysis", kAnalysisKeys},
};

}  // namespace vrsph::case_detail
