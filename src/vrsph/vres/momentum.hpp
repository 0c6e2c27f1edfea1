// Net forces and momentum of the fluid over all levels, and the two optional corrections that
// remove spurious net forces (not part of Cen et al. 2024 nor of Ricci et al. 2024; both off by
// default):
//
// - Coupling (numerics.vres_conserve_momentum). Inside one level every pair term is antisymmetric,
//   so the level's fluid-fluid pairs exchange momentum exactly. Across levels the coupling is
//   one-sided: level A's fluid feels A's buffer particles, which stand in for B's fluid, and
//   B's fluid feels B's buffer, standing in for A's; nothing makes the two forces opposite. Their
//   sum F_c = F_A<-bufA + F_B<-bufB is momentum created by the coupling. Since the fluid-fluid
//   pairs of a level cancel in the sum over its fluid, the force its buffer exerts on its fluid
//   is the fluid's whole pair force from its fluid and buffer neighbours,
//   F_<-buf = sum_fluid omega_i m_i a_pair,i (Level::pair_acc, walls and surface tension left
//   out; omega_i the volume weight of LevelColumns::weight, 1 without numerics.vres_buffer_ramp).
//   Removing it leaves the fluid's momentum changed by walls, gravity and surface tension alone,
//   to the round-off of this double sum (the reaction summed over the buffer particles, -sum_buffer
//   omega_j m_j a_j, is the same force up to the float round-off of each pair, and cost the VR drop
//   a neighbour sweep of every buffer particle: 5% of its wall time, docs/validation.md).
//   The same holds for the kind changes after a step: fluid that enters a buffer leaves the
//   fluid set with its momentum, and buffer particles that become fluid bring an interpolated
//   velocity, so the fluid momentum jumps by dP_c. The correction removes F_c as a uniform
//   acceleration -F_c / M of all fluid particles, and dP_c as a uniform velocity -dP_c / M. A
//   uniform acceleration or velocity leaves relative motion (shape, pressure) unchanged.
//
// - Surface tension (numerics.surface_tension.zero_net_force). On a closed free surface the
//   continuum capillary force integrates to zero (the surface integral of kappa n over a closed
//   surface vanishes). The discrete CSF force does not: each level measures the curvature with
//   its own truncation error, and the difference moves the drop. The correction removes the
//   net F_st = sum_fluid m_i a_st,i as a uniform acceleration -F_st / M. Valid only for fluid whose
//   free surface is closed (droplets): with walls the net capillary force is real (the parser
//   refuses the combination).
//
// docs/validation.md ("Figures formerly in code comments") records what the corrections do on
// the VR droplet.
#pragma once

#include <vector>

#include "vrsph/core/vec.hpp"
#include "vrsph/exec/parallel.hpp"
#include "vrsph/solver/level.hpp"

namespace vrsph {

// Sums over the fluid particles of all levels run in kLanes interleaved lanes (particle i into
// lane i % kLanes), added in order at the end: a fixed order, independent of the threads. One
// running sum was a chain of dependent additions that took as long as a neighbour pass's share of
// a small drop's step.
inline constexpr int kLanes = 4;

// sum_i term_i over the fluid particles i of all levels L in the lanes above, with term_i =
// level_term(L)(i) (level_term forms what its level's terms share, once): one pass on one thread,
// the lanes side by side (independent chains of additions), then added in lane order. A few
// microseconds for a drop of 5,000 particles: the same lanes summed in parallel (a lane per task)
// cost three times the samples on one thread (370 against 124 for the net capillary force,
// docs/validation.md) and kept the second thread waiting on two.
template <class T, int D, class LevelTerm>
T fluid_lane_sum(const std::vector<Level<D>>& levels, LevelTerm&& level_term) {
  T lane[kLanes] = {};
  for (const Level<D>& L : levels) {
    const auto term = level_term(L);
    const Kind* kind = L.ps.kind.data();
    for (std::size_t i = 0; i < L.ps.size(); ++i)
      if (kind[i] == Kind::fluid) lane[i % kLanes] += term(i);
  }
  T total{};
  for (const T& sum : lane) total += sum;
  return total;
}

// A vector sum of the fluid and the fluid mass, summed together (one pass for both).
template <int D>
struct MassAnd {
  Vec<D> v{};
  double m = 0.0;
  void operator+=(const MassAnd& o) { v += o.v, m += o.m; }
};

// Fluid momentum sum_i m_i v_i over all levels (buffer and wall particles excluded); mass gets
// sum_i m_i, the same bits as fluid_mass.
template <int D>
Vec<D> fluid_momentum(const std::vector<Level<D>>& levels, double& mass) {
  const MassAnd<D> s = fluid_lane_sum<MassAnd<D>>(levels, [](const Level<D>& L) {
    return [&ps = L.ps](std::size_t i) {
      return MassAnd<D>{ps.mass_of(i) * ps.vel[i], ps.mass_of(i)};
    };
  });
  mass = s.m;
  return s.v;
}

// Fluid mass sum_i m_i over all levels (fluid_momentum's mass without its momentum).
template <int D>
double fluid_mass(const std::vector<Level<D>>& levels) {
  return fluid_lane_sum<double>(levels, [](const Level<D>& L) {
    return [&ps = L.ps](std::size_t i) { return ps.mass_of(i); };
  });
}

// The mass of particle i as its level's sums see it: m_i omega_i (LevelColumns::weight,
// numerics.vres_buffer_ramp), so that the pair forces it exerts and receives balance.
template <int D>
double weighted_mass(const Level<D>& L, std::size_t i) {
  return L.cols.weight.empty() ? L.ps.mass_of(i) : L.cols.weight[i] * L.ps.mass_of(i);
}

// Adds fluid particle i's share of F_c, omega_i m_i a_pair,i, to f (one expression, so the
// compiler fuses the product into the sum as it always did: the same bits as before).
template <int D>
void add_coupling_force(const Level<D>& L, std::size_t i, Vec<D>& f) {
  f += weighted_mass(L, i) * L.pair_acc[i];
}

// F_c of level L: the net pair force of its fluid and buffer neighbours on its fluid, that is
// the force of its buffer, sum_fluid omega_i m_i a_pair,i (in index order).
template <int D>
Vec<D> level_coupling_force(const Level<D>& L) {
  Vec<D> f{};
  for (std::size_t i = 0; i < L.ps.size(); ++i)
    if (L.ps.kind[i] == Kind::fluid) add_coupling_force(L, i, f);
  return f;
}

// F_c of all levels.
template <int D>
Vec<D> coupling_net_force(const std::vector<Level<D>>& levels) {
  Vec<D> f{};
  for (const Level<D>& L : levels) f += level_coupling_force(L);
  return f;
}

// F_st: sum over fluid particles of m_i a_st,i (levels without surface tension give zero), in
// lanes; mass gets sum_i m_i, the same bits as fluid_mass.
template <int D>
Vec<D> surface_net_force(const std::vector<Level<D>>& levels, double& mass) {
  const MassAnd<D> s = fluid_lane_sum<MassAnd<D>>(levels, [](const Level<D>& L) {
    const Vec<D>* a_st = L.sf.acc_st.size() == L.ps.size() ? L.sf.acc_st.data() : nullptr;
    return [&ps = L.ps, a_st](std::size_t i) {
      const double m = ps.mass_of(i);
      return MassAnd<D>{a_st != nullptr ? m * a_st[i] : Vec<D>{}, m};
    };
  });
  mass = s.m;
  return s.v;
}

// Adds dv to the velocity of every fluid particle of every level.
template <int D>
void add_to_fluid_velocity(std::vector<Level<D>>& levels, const Vec<D>& dv) {
  for (Level<D>& L : levels) {
    Vec<D>* vel = L.ps.vel.data();
    const Kind* kind = L.ps.kind.data();
    exec::for_each(static_cast<std::int64_t>(L.ps.size()), [=](std::int64_t i) {
      if (kind[i] == Kind::fluid) vel[i] += dv;
    });
  }
}

// Gives every fluid particle of every level the uniform acceleration a on top of what the last
// force pass gave it (Level::fluid_acc_uniform, which the integrator adds).
template <int D>
void set_uniform_fluid_acceleration(std::vector<Level<D>>& levels, const Vec<D>& a) {
  for (Level<D>& L : levels) L.fluid_acc_uniform = a;
}

}  // namespace vrsph
