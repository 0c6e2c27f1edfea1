// Particle storage: one structure of arrays per resolution level, fluid, wall and buffer particles
// together with a kind per particle. Every array has one entry per particle, so index i means the
// same particle in all of them. The arrays are listed once, in ParticleSet::zip_fields; resize,
// compaction, the cell sort (CellGrid::sort), checkpoints and level merges go through that list.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "vrsph/core/vec.hpp"

namespace vrsph {

enum class Kind : std::uint8_t { fluid = 0, wall = 1, buffer = 2 };

inline std::string_view kind_name(Kind k) {
  switch (k) {
    case Kind::fluid:
      return "fluid";
    case Kind::wall:
      return "wall";
    case Kind::buffer:
      return "buffer";
  }
  return "unknown";
}

// What an array holds, which decides what happens to it when particles are reordered or saved.
enum class FieldRole : std::uint8_t {
  persistent,  // the state: checkpointed, follows its particle through sorts and compaction
  derived,     // recomputed by every force evaluation: only resized
  step_copy,   // start-of-step copy of the symplectic scheme: follows its particle (the corrector
               // reads it after the mid-step sort), not checkpointed (outputs fall between steps)
};

// True for the arrays whose values must follow their particle when the order changes.
constexpr bool carried(FieldRole r) { return r != FieldRole::derived; }

template <int D>
struct ParticleSet {
  std::vector<std::uint64_t> id;  // permanent particle id
  std::vector<Kind> kind;
  std::vector<Vec<D>> pos;  // m
  std::vector<Vec<D>> vel;  // m/s
  std::vector<double> rho;  // kg/m^3
  // Particle mass, kg. Every particle of a level usually has the same mass, rho0 dp^D: then the
  // set holds that one value (mass_each) and `mass` stays empty, which saves a double per
  // particle. A set given different masses keeps one per particle (keeps_mass). Read it through
  // mass_of(i).
  double mass_each = 0.0;
  std::vector<double> mass;
  // Last shifting displacement, m (an output field). Kept only while keeps_shift (the level
  // shifts its particles: keep_shift); otherwise empty and left out of the field list, which
  // saves D doubles per particle.
  std::vector<Vec<D>> shift;
  std::vector<Vec<D>> acc;   // dv/dt without gravity, m/s^2
  std::vector<double> drho;  // drho/dt, kg/m^3/s
  // Position at the step's start, m. The corrector does without it; only the level coupling of a
  // multi-level run reads it (a donor's state within its step, a buffer particle's face at the
  // step's start). Kept only while keeps_pos0 (keep_pos0); otherwise empty and left out of the
  // field list, which saves D doubles per particle.
  std::vector<Vec<D>> pos0;
  std::vector<Vec<D>> vel0;
  std::vector<double> rho0;
  bool keeps_shift = true;
  bool keeps_pos0 = true;
  bool keeps_mass = false;

  // The list of arrays: calls f(name, role, s.array...) with the same array of every set in
  // `sets`, array after array (mass, shift and pos0 only when every set keeps them). A new
  // per-particle array is one line here.
  template <class F, class... Sets>
  static void zip_fields(F&& f, Sets&... sets) {
    f(std::string_view("id"), FieldRole::persistent, sets.id...);
    f(std::string_view("kind"), FieldRole::persistent, sets.kind...);
    f(std::string_view("pos"), FieldRole::persistent, sets.pos...);
    f(std::string_view("vel"), FieldRole::persistent, sets.vel...);
    f(std::string_view("rho"), FieldRole::persistent, sets.rho...);
    if ((sets.keeps_mass && ...)) f(std::string_view("mass"), FieldRole::persistent, sets.mass...);
    if ((sets.keeps_shift && ...))
      f(std::string_view("shift"), FieldRole::persistent, sets.shift...);
    f(std::string_view("acc"), FieldRole::derived, sets.acc...);
    f(std::string_view("drho"), FieldRole::derived, sets.drho...);
    if ((sets.keeps_pos0 && ...)) f(std::string_view("pos0"), FieldRole::step_copy, sets.pos0...);
    f(std::string_view("vel0"), FieldRole::step_copy, sets.vel0...);
    f(std::string_view("rho0"), FieldRole::step_copy, sets.rho0...);
  }

  // Calls f(name, array, role) for every array of this set (generic lambdas: the arrays differ
  // in element type).
  template <class F>
  void for_each_field(F&& f) {
    zip_fields([&f](std::string_view name, FieldRole role, auto& v) { f(name, v, role); }, *this);
  }
  template <class F>
  void for_each_field(F&& f) const {
    zip_fields([&f](std::string_view name, FieldRole role, const auto& v) { f(name, v, role); },
               *this);
  }

  std::size_t size() const { return pos.size(); }

  double mass_of(std::size_t i) const { return keeps_mass ? mass[i] : mass_each; }
  // Every particle's mass, one value per particle (outputs and checkpoints).
  std::vector<double> masses() const {
    return keeps_mass ? mass : std::vector<double>(size(), mass_each);
  }

  // One mass per particle from now on (each set to mass_each), or one for the set: on = false
  // needs every particle's mass equal, and keeps that value.
  void keep_mass(bool on) {
    if (on == keeps_mass) return;
    if (on) {
      mass.assign(size(), mass_each);
    } else {
      if (!mass.empty()) mass_each = mass.front();
      std::vector<double>().swap(mass);
    }
    keeps_mass = on;
  }
  // Back to one mass for the set when the per-particle masses are all equal (after a load).
  void share_mass_if_uniform() {
    if (keeps_mass &&
        std::adjacent_find(mass.begin(), mass.end(), std::not_equal_to<>()) == mass.end())
      keep_mass(false);
  }

  // Keeps the shift array (sized to the particles, zero where new) or gives it back.
  void keep_shift(bool on) { keep_optional(on, keeps_shift, shift); }
  // The same for pos0.
  void keep_pos0(bool on) { keep_optional(on, keeps_pos0, pos0); }

  void resize(std::size_t n) {
    for_each_field([n](std::string_view, auto& v, FieldRole) { v.resize(n); });
  }

  void reserve(std::size_t n) {
    for_each_field([n](std::string_view, auto& v, FieldRole) { v.reserve(n); });
  }
  // Gives back the capacity beyond the size (after a cut of a larger fill): one array at a
  // time, so the copy costs one array's size more than the set.
  void shrink_to_fit() {
    for_each_field([](std::string_view, auto& v, FieldRole) { v.shrink_to_fit(); });
  }

  // One particle more (set-up: reserve first, or every array may end with twice its size).
  void push_back(std::uint64_t id_, Kind k, const Vec<D>& x, const Vec<D>& v, double rho_,
                 double m) {
    const std::size_t n = size();
    if (!keeps_mass && n == 0) mass_each = m;
    if (!keeps_mass && m != mass_each) keep_mass(true);
    resize(n + 1);
    id[n] = id_;
    kind[n] = k;
    pos[n] = x;
    vel[n] = v;
    rho[n] = rho_;
    if (keeps_mass) mass[n] = m;
  }

  // Keeps the particles with keep[i] != 0, in order (the carried arrays; derived arrays are
  // resized and hold stale values until the next pass). Returns the number removed.
  std::size_t compact(const std::vector<std::uint8_t>& keep) {
    const std::size_t n = size();
    std::size_t w = 0;
    for_each_field([&](std::string_view, auto& v, FieldRole role) {
      if (!carried(role)) return;
      w = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (keep[i]) v[w++] = v[i];
    });
    resize(w);
    return n - w;
  }

  std::size_t count(Kind k) const {
    std::size_t c = 0;
    for (Kind x : kind) c += (x == k);
    return c;
  }

 private:
  // An optional array: sized to the particles (zero where new) while on, given back when off.
  void keep_optional(bool on, bool& flag, std::vector<Vec<D>>& v) {
    flag = on;
    if (on)
      v.resize(size());
    else
      std::vector<Vec<D>>().swap(v);
  }
};

}  // namespace vrsph
