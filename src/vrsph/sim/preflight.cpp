// The set-up checks before any particle is made (preflight.hpp).
#include "vrsph/sim/preflight.hpp"

#include <fmt/format.h>

#include <cfloat>
#include <cmath>

#include "vrsph/core/to_vec.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/physics/eos.hpp"
#include "vrsph/physics/viscosity.hpp"
#include "vrsph/setup/block_extent.hpp"
#include "vrsph/setup/case_parser.hpp"
#include "vrsph/vres/levels.hpp"

namespace vrsph {
namespace {

// "<source>: <key> = <value>: <reason>", the one-line form of every case error.
[[noreturn]] void refuse(const std::string& source, const std::string& key,
                         const std::string& value, const std::string& reason) {
  throw CaseError(fmt::format("{}: {} = {}: {}", source, key, value, reason));
}

// A vector as the case gives it (all digits) or, computed (digits6), to 6 significant digits.
std::string vec_value(const Vec3d& v, int dim, bool digits6 = false) {
  std::string out = "[";
  for (int k = 0; k < dim; ++k)
    out += digits6 ? fmt::format("{}{:.6g}", k ? ", " : "", v[k])
                   : fmt::format("{}{}", k ? ", " : "", v[k]);
  return out + "]";
}

double gravity_norm(const CaseSpec& spec) {
  double g2 = 0.0;
  for (int k = 0; k < spec.dimension; ++k) g2 += spec.fluid.gravity[k] * spec.fluid.gravity[k];
  return std::sqrt(g2);
}

// The fastest fluid block (its index and speed), for the initial max_speed and its key.
std::size_t fastest_block(const CaseSpec& spec, double& vmax) {
  std::size_t best = 0;
  vmax = 0.0;
  for (std::size_t i = 0; i < spec.fluid_blocks.size(); ++i) {
    double v2 = 0.0;
    for (int k = 0; k < spec.dimension; ++k)
      v2 += spec.fluid_blocks[i].velocity[k] * spec.fluid_blocks[i].velocity[k];
    if (std::sqrt(v2) > vmax) vmax = std::sqrt(v2), best = i;
  }
  return best;
}

// The dp of every level (level 0 first) and, for levels >= 1, the [[refinement]] that makes it.
struct LevelDp {
  double dp = 0.0;
  int refinement = -1;
};

template <int D>
std::vector<LevelDp> level_dps(const CaseSpec& spec) {
  std::vector<LevelDp> out;
  for (const LevelLayout<D>& L : make_level_layout<D>(spec)) {
    LevelDp l{L.dp, -1};
    for (std::size_t i = 0; i < spec.refinements.size() && L.region.has_box; ++i) {
      if (to_vec<D>(spec.refinements[i].min) == L.region.box.lo &&
          to_vec<D>(spec.refinements[i].max) == L.region.box.hi)
        l.refinement = static_cast<int>(i);
    }
    out.push_back(l);
  }
  return out;
}

// The smallest h over the levels (the finest level's).
double finest_h(const SetupEstimate& e) {
  double h = std::numeric_limits<double>::infinity();
  for (const LevelEstimate& L : e.levels) h = std::min(h, L.h);
  return h;
}

// The first time step over the levels, as Simulation takes it (level_dt_at_start).
void first_dt(const CaseSpec& spec, double vmax, SetupEstimate& e) {
  e.dt0 = std::numeric_limits<double>::infinity();
  for (const LevelEstimate& L : e.levels) {
    const ViscosityLevel visc =
        viscosity_level(spec.numerics.viscosity, spec.fluid.kinematic_viscosity, e.c0, L.h);
    const DtInputs in{L.h,
                      spec.numerics.cfl,
                      e.c0,
                      0.0,
                      vmax,
                      0.0,
                      visc.nu,
                      spec.fluid.density,
                      spec.fluid.surface_tension};
    const DtChoice c = choose_dt(in);
    if (!(c.dt >= e.dt0)) e.dt0 = c.dt, e.limit = c.limit;  // NaN is taken (and refused)
  }
}

// The key behind the first time step's binding limit (and its value).
std::pair<std::string, std::string> dt_key(const CaseSpec& given, const SetupEstimate& e) {
  const CaseSpec& s = given;
  if (!(finest_h(e) >= DBL_MIN)) return {"resolution.dp", fmt::format("{}", s.dp)};
  if (e.limit == DtLimit::viscous)
    return {"fluid.kinematic_viscosity", fmt::format("{}", s.fluid.kinematic_viscosity)};
  if (e.limit == DtLimit::capillary)
    return {"fluid.surface_tension", fmt::format("{}", s.fluid.surface_tension)};
  if (s.eos.sound_speed) return {"eos.sound_speed", fmt::format("{}", *s.eos.sound_speed)};
  if (s.eos.max_speed) return {"eos.max_speed", fmt::format("{}", *s.eos.max_speed)};
  if (gravity_norm(s) > 0.0) return {"fluid.gravity", vec_value(s.fluid.gravity, s.dimension)};
  double v = 0.0;
  const std::size_t i = fastest_block(s, v);
  return {fmt::format("fluid_block.{}.velocity", i),
          vec_value(s.fluid_blocks[i].velocity, s.dimension)};
}

// The first step must be positive, finite and long enough to move the clock at end_time; the
// output interval longer than it.
void check_first_dt(const CaseSpec& given, const std::string& source, const SetupEstimate& e) {
  const double h = finest_h(e);
  if (!(e.dt0 > 0.0) || !std::isfinite(e.dt0) || given.end_time + e.dt0 == given.end_time) {
    const auto [key, value] = dt_key(given, e);
    refuse(source, key, value,
           fmt::format("the first time step ({} limit, h = {:.3g} m, c0 = {:.3g} m/s) is {:.3g} "
                       "s: it must be > 0, finite and large enough to advance the clock to "
                       "case.end_time = {:g} s",
                       kDtLimitNames[static_cast<std::size_t>(e.limit)], h, e.c0, e.dt0,
                       given.end_time));
  }
  if (given.output_interval > 0.0 && given.output_interval <= e.dt0) {
    refuse(source, "output.interval", fmt::format("{}", given.output_interval),
           fmt::format("at or below the first time step {:.3g} s: a snapshot would be written at "
                       "every step (give an interval above it, or 0 for the first and last "
                       "snapshots only)",
                       e.dt0));
  }
}

// Gravity and initial pressures that would wreck the first step: gravity moving the fluid by
// more than h in it (the first dt does not see gravity: the fluid starts at rest), a block's
// pressure whose density lies outside the window [0.5, 2] rho0 of the stability check (the
// pressure force then also throws the block apart within that step).
void check_first_step(const CaseSpec& spec, const std::string& source, const SetupEstimate& e) {
  const double h = finest_h(e);
  const double fall = 0.5 * gravity_norm(spec) * e.dt0 * e.dt0;
  if (fall > h) {
    refuse(source, "fluid.gravity", vec_value(spec.fluid.gravity, spec.dimension),
           fmt::format("the first step (dt = {:.3g} s at c0 = {:.4g} m/s) would move the fluid by "
                       "{:.3g} m, more than h = {:.3g} m, and out of the domain (raise "
                       "eos.sound_speed or lower the gravity)",
                       e.dt0, e.c0, fall, h));
  }
  const TaitEos eos(spec.fluid.density, spec.eos.gamma, e.c0);
  const double rho0 = spec.fluid.density;
  for (std::size_t i = 0; i < spec.fluid_blocks.size(); ++i) {
    const double p = spec.fluid_blocks[i].pressure;
    const double rho = eos.density(p);
    if (p == 0.0 || (rho >= 0.5 * rho0 && rho <= 2.0 * rho0)) continue;
    refuse(source, fmt::format("fluid_block.{}.pressure", i), fmt::format("{}", p),
           fmt::format("gives the initial density {:.4g} kg/m^3, outside [{:g}, {:g}] kg/m^3: the "
                       "run would stop at its first step (c0 = {:.4g} m/s gives B = {:.4g} Pa; "
                       "raise eos.sound_speed or lower the pressure)",
                       rho, 0.5 * rho0, 2.0 * rho0, e.c0, eos.b));
  }
}

// The block that makes the most particles at some level: what drives the count.
struct Contributor {
  double count = -1.0;
  std::size_t level = 0;
  bool wall = false;
  std::size_t block = 0;
};

// Every level filled with every block at its dp (what level_fill makes before the cut).
void count_levels(const CaseSpec& spec, const std::vector<LevelDp>& dps, SetupEstimate& e,
                  Contributor& top) {
  const int dim = spec.dimension;
  for (std::size_t k = 0; k < dps.size(); ++k) {
    LevelEstimate L{dps[k].dp, spec.h_over_dp * dps[k].dp, 0.0, 0.0};
    for (std::size_t i = 0; i < spec.fluid_blocks.size(); ++i) {
      const double n = fluid_count(spec.fluid_blocks[i], L.dp, dim);
      L.fluid += n;
      if (!(n <= top.count)) top = {n, k, false, i};
    }
    for (std::size_t i = 0; i < spec.wall_blocks.size(); ++i) {
      const double n = wall_count(spec.wall_blocks[i], L.dp, dim);
      L.wall += n;
      if (!(n <= top.count)) top = {n, k, true, i};
    }
    e.levels.push_back(L);
    e.particles += L.fluid + L.wall;
  }
  e.bytes = kBaseBytes + e.particles * bytes_per_particle(dim);
}

std::string size_text(const Vec3d& min, const Vec3d& max, int dim) {
  std::string out;
  for (int k = 0; k < dim; ++k) out += fmt::format("{}{:g}", k ? " x " : "", max[k] - min[k]);
  return out + " m";
}

// "fluid_block.0, a box of 1 x 2 m", "wall_block.0, a tank of 4 x 2.5 m with 3 layers", ...
std::string block_text(const CaseSpec& spec, const Contributor& c) {
  const int dim = spec.dimension;
  if (c.wall) {
    const WallBlock& w = spec.wall_blocks[c.block];
    return fmt::format("wall_block.{}, a {} of {}{}", c.block,
                       w.shape == WallShape::tank ? "tank" : "box", size_text(w.min, w.max, dim),
                       w.shape == WallShape::tank ? fmt::format(" with {} layers", w.layers) : "");
  }
  const FluidBlock& b = spec.fluid_blocks[c.block];
  if (b.shape == BlockShape::box)
    return fmt::format("fluid_block.{}, a box of {}", c.block, size_text(b.min, b.max, dim));
  return fmt::format("fluid_block.{}, a {} of radius {:g} m", c.block,
                     dim == 2 ? "circle" : "sphere", b.radius);
}

// The key that drives the count: a refinement's dp_ratio when a finer level makes the most,
// a tank's layers when they are far more than the support needs, else resolution.dp.
std::pair<std::string, std::string> count_key(const CaseSpec& spec, const std::vector<LevelDp>& dps,
                                              const Contributor& c) {
  const int ref = dps[c.level].refinement;
  if (c.level > 0 && ref >= 0) {
    return {fmt::format("refinement.{}.dp_ratio", ref),
            fmt::format("{}", spec.refinements[static_cast<std::size_t>(ref)].dp_ratio)};
  }
  if (c.wall) {
    const WallBlock& w = spec.wall_blocks[c.block];
    if (w.shape == WallShape::tank && w.layers > 2.0 * std::ceil(2.0 * spec.h_over_dp))
      return {fmt::format("wall_block.{}.layers", c.block), fmt::format("{}", w.layers)};
  }
  return {"resolution.dp", fmt::format("{}", spec.dp)};
}

std::string bytes_text(double b) {
  if (b < 1024.0 * 1024 * 1024) return fmt::format("{:.3g} MiB", b / (1024.0 * 1024));
  return fmt::format("{:.3g} GiB", b / (1024.0 * 1024 * 1024));
}

// The count and memory limits: 2^32 - 1 particles per level (the sort's 32-bit indices),
// --max-particles, and the memory available.
void check_counts(const CaseSpec& spec, const std::string& source, const PreflightLimits& lim,
                  const std::vector<LevelDp>& dps, const SetupEstimate& e, const Contributor& top) {
  constexpr double kIndexLimit = 4294967295.0;
  std::string why;
  for (std::size_t k = 0; k < e.levels.size() && why.empty(); ++k) {
    if (!(e.levels[k].fluid + e.levels[k].wall <= kIndexLimit))
      why = fmt::format(
          "level {} alone would hold more than the 2^32 - 1 particles a level can "
          "index",
          k);
  }
  if (why.empty() && lim.max_particles && !(e.particles <= *lim.max_particles))
    why = fmt::format("above --max-particles = {:.0f}", *lim.max_particles);
  if (why.empty() && lim.memory_bytes && !(e.bytes <= *lim.memory_bytes))
    why = fmt::format(
        "needing about {} of memory ({:.0f} bytes per particle), more than the {} "
        "available (MemAvailable in /proc/meminfo)",
        bytes_text(e.bytes), bytes_per_particle(spec.dimension), bytes_text(*lim.memory_bytes));
  if (why.empty()) return;
  const auto [key, value] = count_key(spec, dps, top);
  const double dp = dps[top.level].dp;
  refuse(
      source, key, value,
      fmt::format(
          "the set-up would make about {:.3g} particles ({:.3g} of them from {} at "
          "dp = {:g} m{}), {}",
          e.particles, top.count, block_text(spec, top), dp,
          top.level > 0 ? fmt::format(", level {}: dp / {:g}", top.level, spec.dp / dp) : "", why));
}

// The domain (given, or the default one estimated from the blocks) in cells of the finest level
// at the finest cell size (--cells-per-support 4: h / 2); the grid lays at most 2^40.
void check_domain_cells(const CaseSpec& spec, const std::string& source, const SetupEstimate& e) {
  const int dim = spec.dimension;
  Extent d = default_domain_extent(spec);
  if (spec.domain_min) d = {*spec.domain_min, *spec.domain_max};
  double cells = 1.0;
  for (int k = 0; k < dim; ++k) cells *= std::ceil((d.hi[k] - d.lo[k]) / (0.5 * finest_h(e))) + 9;
  if (cells <= static_cast<double>(kMaxDomainCells)) return;
  refuse(
      source, spec.domain_min ? "domain.max" : "resolution.dp",
      spec.domain_min ? vec_value(d.hi, dim) : fmt::format("{}", spec.dp),
      fmt::format("the domain {} .. {} spans about {:.3g} cells of h / 2 = {:.3g} m, more than "
                  "the 2^40 a cell grid can lay{}",
                  vec_value(d.lo, dim, true), vec_value(d.hi, dim, true), cells, 0.5 * finest_h(e),
                  spec.domain_min ? ""
                                  : " (it is the default domain, the particles' bounding box "
                                    "plus a margin: set a smaller one with [domain])"));
}

}  // namespace

// Bytes per particle, measured: peak resident memory of runs (/usr/bin/time -v) at two
// resolutions with surface tension, shifting and both snapshot formats on (the most a particle
// carries), the difference divided by the difference in particles. 2D: bench_dam_break_2d at
// dp = 0.005 and 0.0025 (85,415 and 329,616 particles, 95.8 and 336.2 MB): 1008 B. 3D:
// droplet_3d at dp = 2e-4 and 8e-5 (4,224 and 65,752 particles, 13.0 and 98.1 MB): 1416 B. The
// peaks hold the fill's transient copy, the sort's scratch and the snapshot writers. Taken
// about 1.5 x for headroom; kBaseBytes covers the 6-13 MB a run needs before any particle.
double bytes_per_particle(int dimension) { return dimension == 2 ? 1536.0 : 2048.0; }

SetupEstimate preflight(const CaseSpec& given, const std::string& source,
                        const PreflightLimits& limits) {
  CaseSpec spec = given;  // the speed of sound fills eos.max_speed here, not in the caller's
  double vmax = 0.0;
  fastest_block(spec, vmax);
  SetupEstimate e;
  e.c0 = resolve_sound_speed(spec, fluid_height(spec), vmax);
  const std::vector<LevelDp> dps = spec.dimension == 2 ? level_dps<2>(spec) : level_dps<3>(spec);
  Contributor top;
  count_levels(spec, dps, e, top);
  first_dt(spec, vmax, e);
  check_first_dt(given, source, e);
  check_first_step(spec, source, e);
  check_counts(spec, source, limits, dps, e, top);
  check_domain_cells(spec, source, e);
  return e;
}

double fluid_height(const CaseSpec& spec) {
  const int vert = spec.dimension - 1;
  double zmin = 1e300, zmax = -1e300;
  for (const FluidBlock& b : spec.fluid_blocks) {
    const bool box = b.shape == BlockShape::box;
    zmin = std::min(zmin, box ? b.min[vert] : b.center[vert] - b.radius);
    zmax = std::max(zmax, box ? b.max[vert] : b.center[vert] + b.radius);
  }
  return zmax > zmin ? zmax - zmin : 0.0;
}

double resolve_sound_speed(CaseSpec& spec, double height, double vmax) {
  const double g = gravity_norm(spec);
  if (!spec.eos.max_speed) {
    if (g > 0.0 && height > 0.0) {
      spec.eos.max_speed = std::sqrt(g * height);
    } else if (vmax > 0.0) {
      spec.eos.max_speed = vmax;
    }
  }
  if (!spec.eos.sound_speed && !spec.eos.max_speed) {
    throw std::invalid_argument(
        "eos.max_speed: missing: needed to set the speed of sound when there is no gravity and no "
        "initial velocity (give eos.max_speed or eos.sound_speed)");
  }
  return spec.eos.sound_speed ? *spec.eos.sound_speed
                              : spec.eos.sound_speed_factor * *spec.eos.max_speed;
}

}  // namespace vrsph
