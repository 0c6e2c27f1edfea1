// The validated description of a run: what a case file (plus --set overrides) says, with every
// default filled in. Built by parse_case() (case_parser.hpp); consumed by the solver set-up.
// Vectors are stored with 3 components; only the first `dimension` are meaningful.
// Every key with its unit, default and checks: docs/cases.md.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "vrsph/core/precision.hpp"
#include "vrsph/physics/density_diffusion.hpp"
#include "vrsph/physics/eos.hpp"
#include "vrsph/physics/shifting.hpp"
#include "vrsph/physics/surface_tension.hpp"
#include "vrsph/physics/viscosity.hpp"

namespace vrsph {

using Vec3d = std::array<double, 3>;

enum class BlockShape { circle, sphere, box };
// lattice: nodes from min (box) or a lattice centred on the centre (round shapes), every dp;
// rings: concentric rings (circles); cells: the centres of the dp cells that tile a box, so its
// faces lie dp/2 beyond the outer rows at every resolution level.
enum class FillMode { lattice, rings, rings_on_radius, cells };
// refinement.N.buffer_rounding: buffer shells exactly buffer_width x h, or that width rounded up
// to a whole number of the level's dp (as DualSPHysics lays its buffers).
enum class BufferRounding { none, whole_dp };
// numerics.vres_buffer_surface: where buffer particles take lambda and the normal from. own:
// their own level's sums (as Ricci et al. 2024 and DualSPHysics); edge: from the other level's
// fluid near the outer edge of their shell, where their own support is cut (vrsph's default);
// donor: from the other level's fluid everywhere in the shell; donor_normals: lambda as edge, the
// normal from the other level's fluid everywhere in the shell; edge_kink: as edge, and the normal
// moved to the other level's where the two meet at a kink (vres/kink_normal.hpp).
enum class BufferSurface { own, edge, donor, donor_normals, edge_kink };
enum class WallShape { tank, box };
// output.precision: how the particle fields of a snapshot are stored (positions stay double).
enum class OutputPrecision { float64, float32 };
// output.compression: the .vtp appended data as written, or zlib-compressed.
enum class OutputCompression { none, zlib };

struct FluidBlock {
  BlockShape shape = BlockShape::box;
  Vec3d center{};  // circle / sphere
  double radius = 0.0;
  Vec3d min{};  // box
  Vec3d max{};
  FillMode fill = FillMode::lattice;
  Vec3d velocity{};       // initial velocity (m/s)
  double pressure = 0.0;  // initial pressure (Pa): the density starts at the EOS value for it

  bool operator==(const FluidBlock&) const = default;
};

struct WallBlock {
  WallShape shape = WallShape::tank;
  Vec3d min{};
  Vec3d max{};
  int layers = 3;
  bool thin = false;  // accept a wall thinner than the kernel support (as DualSPHysics cases)

  bool operator==(const WallBlock&) const = default;
};

struct RefinementBox {
  Vec3d min{};
  Vec3d max{};
  int dp_ratio = 2;
  double buffer_width = 4.0;  // in units of each level's own h
  BufferRounding buffer_rounding = BufferRounding::none;

  bool operator==(const RefinementBox&) const = default;
};

struct OutputLine {
  std::string name;
  Vec3d from{};
  Vec3d to{};

  bool operator==(const OutputLine&) const = default;
};

struct OutputProbe {
  std::string name;
  Vec3d position{};  // m

  bool operator==(const OutputProbe&) const = default;
};

// [fluid]
struct FluidSpec {
  double density = 1000.0;              // rho0 (kg/m^3)
  double kinematic_viscosity = 1.0e-6;  // nu (m^2/s), used by the laminar model
  double surface_tension = 0.0;         // sigma (N/m); 0: no surface tension
  Vec3d gravity{};                      // g (m/s^2)

  bool operator==(const FluidSpec&) const = default;
};

// [numerics]: the time step, one table per model (each the model's own struct) and the start.
struct NumericsSpec {
  double cfl = 0.2;                        // CFL number of the time step (dimensionless)
  Precision precision = Precision::mixed;  // of the force pass (core/precision.hpp)
  ViscosityParams viscosity;
  DiffusionParams density_diffusion;
  ShiftingParams shifting;
  SurfaceTensionParams surface_tension;
  bool hydrostatic_initial_density = true;  // gravity cases start at rest in equilibrium
  bool local_time_stepping = false;         // variable resolution: each level on its own dt
  double start_damping_time = 0.0;          // s: fluid velocities damped while t < this (0: off)
  double start_damping_tau = 1.0e-3;        // s: their decay time meanwhile

  bool operator==(const NumericsSpec&) const = default;
};

struct CaseSpec {
  // [case]
  std::string name;
  int dimension = 2;
  double end_time = 0.0;

  FluidSpec fluid;
  EosParams eos;

  // [resolution]
  double dp = 0.0;
  double h_over_dp = 1.3;

  NumericsSpec numerics;
  // numerics.vres_*: read by the multi-level coupling (solver/simulation.cpp, vres/)
  bool vres_conserve_momentum = false;  // remove the coupling's net force and momentum jumps
  double vres_buffer_fill_min = 0.0;    // buffer particles below this donor fill are deleted
  double vres_buffer_ramp = 0.0;        // dp: buffer volumes ramp to 0 over this at the outer edge
  bool vres_surface_across_levels = false;  // surface passes over the fluid of both levels
  BufferSurface vres_buffer_surface = BufferSurface::edge;  // buffers' lambda and normal
  double vres_shepard_fill = 0.0;    // below this donor fill, buffers take Shepard averages
  double vres_flux_edge = 0.0;       // below this donor fill, mass points pass their flux inward
  double vres_kink_radius = 0.0;     // edge_kink's R_k (m), threshold dp / R_k; 0: 10 dp of level 0
  double vres_buffer_spacing = 0.0;  // buffer particles kept this many dp apart (0: off)

  // geometry
  std::vector<FluidBlock> fluid_blocks;
  std::vector<WallBlock> wall_blocks;

  // [domain] (absent: bounding box of all particles + margin)
  std::optional<Vec3d> domain_min;
  std::optional<Vec3d> domain_max;
  double max_lost_fraction = 0.01;  // run stops when more fluid than this has left the domain

  std::vector<RefinementBox> refinements;

  // [output]
  double output_interval = 0.0;  // 0: only the initial and final snapshots
  bool write_vtp = true;
  bool write_csv = true;
  OutputPrecision output_precision = OutputPrecision::float64;
  OutputCompression output_compression = OutputCompression::none;
  std::vector<OutputLine> lines;
  std::vector<OutputProbe> probes;

  // [analysis]
  std::optional<double> laplace_pressure;

  bool operator==(const CaseSpec&) const = default;
};

}  // namespace vrsph
