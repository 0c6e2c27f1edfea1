// Buffer-particle interpolation of variable resolution (vres/interpolation.hpp, docs/physics.md
// section 5): first-order corrected SPH (Liu & Liu 2006) from a donor level's fluid particles.
//  - linear rho and velocity are reproduced to round-off on a jittered lattice (up to 0.25 dp),
//    in the bulk and within h of the cloud's edge, where Shepard alone is visibly wrong;
//  - constants are exact in every branch (corrected, Shepard fallback);
//  - no support far outside the cloud (also inside the grid domain, beyond its cell table);
//    the Shepard fallback just beyond a face or a corner (3D: an edge), with values bounded
//    by the donors';
//  - buffer and wall particles of the donor set are ignored;
//  - the Shepard sums in lanes (interpolate_values, shepard_field from columns) agree with the
//    sums donor by donor to round-off, fluid, buffer and wall donors alike, also at a fraction of
//    the donors' step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "vrsph/vres/interpolation.hpp"

namespace vrsph {
namespace {

constexpr double kDp = 0.01, kHdp = 1.3, kRho0 = 1000.0;

// Linear fields over the block [0, n dp]^D.
template <int D>
double rho_lin(const Vec<D>& x) {
  double r = kRho0;
  for (int k = 0; k < D; ++k) r += (2000.0 - 1300.0 * k) * x[k];
  return r;
}
template <int D>
Vec<D> vel_lin(const Vec<D>& x) {
  Vec<D> v;
  for (int k = 0; k < D; ++k) {
    v[k] = 0.3 - 0.2 * k;
    for (int l = 0; l < D; ++l) v[k] += (k == l ? 4.0 : -1.5 + l) * x[l];
  }
  return v;
}

// n^D lattice nodes (a + 1/2) dp, each coordinate moved by up to `jitter` dp (seeded).
template <int D>
std::vector<Vec<D>> lattice(int n, double jitter, unsigned seed = 7) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  std::vector<Vec<D>> pos;
  const int total = D == 2 ? n * n : n * n * n;
  for (int i = 0; i < total; ++i) {
    Vec<D> x;
    for (int k = 0, m = i; k < D; ++k, m /= n) x[k] = (m % n + 0.5 + u(gen)) * kDp;
    pos.push_back(x);
  }
  return pos;
}

template <int D>
struct Donors {
  ParticleSet<D> ps;
  CellGrid<D> grid;
  WendlandC2<D> kernel{kHdp * kDp};
  InterpolatedState<D> at(const Vec<D>& x, double cond_limit = kVresCondLimit) const {
    return interpolate_from_level(x, ps, grid, kernel, cond_limit);
  }
};

// Fluid donors carrying the linear fields (or constants), in a grid domain 10 dp wider than the
// block on every side, so that points beyond the cloud are inside the domain.
template <int D>
Donors<D> make_donors(const std::vector<Vec<D>>& pos, int n, bool constant = false,
                      const std::vector<Kind>& kinds = {}) {
  Donors<D> d;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const Kind kind = i < kinds.size() ? kinds[i] : Kind::fluid;
    const bool crazy = kind != Kind::fluid;
    const double rho = crazy ? 1e9 : constant ? 1234.5 : rho_lin(pos[i]);
    Vec<D> v = constant ? Vec<D>{} : vel_lin(pos[i]);
    if (constant) v[0] = -0.7;
    if (crazy) v[0] = 1e6;
    d.ps.push_back(i, kind, pos[i], v, rho, crazy ? 1e3 : rho * std::pow(kDp, D));  // V = dp^D
  }
  Vec<D> lo, hi;
  for (int k = 0; k < D; ++k) lo[k] = -10.0 * kDp, hi[k] = (n + 10.0) * kDp;
  d.grid = CellGrid<D>(lo, hi, d.kernel.support(), 2);
  EXPECT_TRUE(d.grid.sort(d.ps).empty());
  return d;
}

template <int D>
Vec<D> point(double a, double b, double c = 0.0) {  // coordinates in dp
  Vec<D> x;
  x[0] = a * kDp, x[1] = b * kDp;
  if constexpr (D == 3) x[2] = c * kDp;
  return x;
}

template <int D>
double rel_error(const InterpolatedState<D>& s, const Vec<D>& x) {
  double e = std::fabs(s.rho - rho_lin(x)) / kRho0;
  for (int k = 0; k < D; ++k) e = std::max(e, std::fabs(s.vel[k] - vel_lin(x)[k]));  // |v| ~ 1 m/s
  return e;
}

template <int D>
void check_linear(int n) {
  const Donors<D> d = make_donors<D>(lattice<D>(n, 0.25), n);
  const double c = 0.5 * n;  // centre, in dp
  struct Case {
    Vec<D> x;
    const char* where;
  };
  const Case cases[] = {{point<D>(c + 0.3, c - 0.2, c + 0.1), "bulk"},
                        {point<D>(c - 0.17, c + 0.41, c - 0.33), "bulk"},
                        {point<D>(0.6, c, c), "0.6 dp inside a face"},
                        {point<D>(0.0, c + 0.2, c), "on a face"},
                        {point<D>(c, n - 0.3, c), "0.3 dp inside a face"},
                        {point<D>(0.8, 0.7, 0.9), "near a corner"}};
  for (const auto& cs : cases) {
    const auto s = d.at(cs.x);
    const auto shep = d.at(cs.x, 0.0);  // cond_limit 0: always the Shepard fallback
    std::printf(
        "[ vres %dD %-22s] shepard %.3f  cond %7.2f  corrected error %.1e  "
        "Shepard error %.1e\n",
        D, cs.where, s.shepard, s.cond, rel_error(s, cs.x), rel_error(shep, cs.x));
    EXPECT_TRUE(s.corrected) << cs.where;
    EXPECT_LT(rel_error(s, cs.x), 1e-10) << cs.where;
    EXPECT_FALSE(shep.corrected);
    if (cs.x[0] < 1.0 * kDp || cs.x[1] > (n - 1.0) * kDp) {  // edge: Shepard is first-order wrong
      EXPECT_GT(rel_error(shep, cs.x), 5e-3) << cs.where;
    }
  }
}

TEST(VresInterp, LinearFieldsOnJitteredLattice2D) { check_linear<2>(14); }
TEST(VresInterp, LinearFieldsOnJitteredLattice3D) { check_linear<3>(9); }

template <int D>
void check_constant_and_outside(int n) {
  const Donors<D> d = make_donors<D>(lattice<D>(n, 0.25), n, true);
  const double c = 0.5 * n;
  const Vec<D> pts[] = {point<D>(c, c, c), point<D>(0.2, c, c), point<D>(0.3, 0.4, 0.3),
                        point<D>(-0.4, -0.4, c), point<D>(-0.8, c, c)};  // last two: fallback
  for (const auto& x : pts) {
    for (double limit : {kVresCondLimit, 0.0}) {
      const auto s = d.at(x, limit);
      if (s.shepard < kVresShepardMin) continue;
      EXPECT_NEAR(s.rho, 1234.5, 1e-12 * 1234.5);
      EXPECT_NEAR(s.vel[0], -0.7, 1e-13);
      for (int k = 1; k < D; ++k) EXPECT_NEAR(s.vel[k], 0.0, 1e-13);
    }
  }
  // The clipped cell stencil finds every donor: Shepard sums against brute force on a line that
  // crosses the cloud, its cell table and its ghost cells.
  for (double t = -4.0; t <= n + 4.0; t += 0.25) {
    const Vec<D> x = point<D>(t, 0.7 * t + 0.1, c - 0.3);
    double shep = 0.0;
    for (std::size_t j = 0; j < d.ps.size(); ++j) {
      const double r2 = norm2(x - d.ps.pos[j]);
      if (r2 < d.kernel.support2) shep += d.ps.mass_of(j) / d.ps.rho[j] * d.kernel.w(std::sqrt(r2));
    }
    EXPECT_NEAR(d.at(x).shepard, shep, 1e-12) << "t = " << t;
  }
  // No support: beyond the cloud but inside the grid's domain (past its cell table), and
  // outside the domain.
  for (const auto& x : {point<D>(-3.0, c, c), point<D>(n + 9.5, n + 9.5, n + 9.5),
                        point<D>(c, -40.0, c), point<D>(1e9, c, c)}) {
    const auto s = d.at(x);
    EXPECT_LT(s.shepard, kVresShepardMin);
    EXPECT_FALSE(s.corrected);
    EXPECT_EQ(s.rho, 0.0);
  }
}

TEST(VresInterp, ConstantsExactAndNoSupportOutside2D) { check_constant_and_outside<2>(12); }
TEST(VresInterp, ConstantsExactAndNoSupportOutside3D) { check_constant_and_outside<3>(8); }

// Just beyond a face or a corner (an edge in 3D) only a few donors reach the point: A is ill
// conditioned and Shepard takes over. Its value is an average of donors within 2h, so it stays
// within |grad f| 2h of the linear field there.
template <int D>
void check_fallback(int n, double face_t, double corner_t) {
  const Donors<D> d = make_donors<D>(lattice<D>(n, 0.25), n);
  const double c = 0.5 * n, two_h = 2.0 * kHdp * kDp;
  for (const auto& x : {point<D>(face_t, c, c), point<D>(corner_t, corner_t, c)}) {
    const auto s = d.at(x);
    std::printf("[ vres %dD fallback at (%.2f, %.2f) dp ] shepard %.3f  cond %.3g\n", D, x[0] / kDp,
                x[1] / kDp, s.shepard, s.cond);
    EXPECT_GE(s.shepard, kVresShepardMin);
    EXPECT_GT(s.cond, kVresCondLimit);
    EXPECT_FALSE(s.corrected);
    EXPECT_LT(std::fabs(s.rho - rho_lin(x)), 2300.0 * two_h);
    for (int k = 0; k < D; ++k) EXPECT_LT(std::fabs(s.vel[k] - vel_lin(x)[k]), 8.0 * two_h);
  }
}

TEST(VresInterp, ShepardFallbackJustBeyondTheEdge2D) { check_fallback<2>(12, -0.8, -0.4); }
TEST(VresInterp, ShepardFallbackJustBeyondTheEdge3D) { check_fallback<3>(8, -0.8, -0.4); }

TEST(VresInterp, BufferAndWallDonorsIgnored) {
  const int n = 12;
  auto pos = lattice<2>(n, 0.25);
  const Donors<2> plain = make_donors<2>(pos, n);
  std::vector<Kind> kinds(pos.size(), Kind::fluid);
  for (const auto& x : lattice<2>(n, 0.3, 99)) {  // a second cloud, crazy values
    pos.push_back(x);
    kinds.push_back(pos.size() % 2 ? Kind::buffer : Kind::wall);
  }
  const Donors<2> mixed = make_donors<2>(pos, n, false, kinds);
  std::vector<Vec<2>> pts = {point<2>(6.2, 5.9), point<2>(0.1, 3.0), point<2>(-1.0, -1.1)};
  std::vector<InterpolatedState<2>> batch;
  interpolate_from_level(pts, mixed.ps, mixed.grid, mixed.kernel, batch);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto a = plain.at(pts[i]), b = mixed.at(pts[i]);
    EXPECT_DOUBLE_EQ(a.rho, b.rho);
    EXPECT_DOUBLE_EQ(a.vel[0], b.vel[0]);
    EXPECT_DOUBLE_EQ(a.vel[1], b.vel[1]);
    EXPECT_DOUBLE_EQ(a.shepard, b.shepard);
    EXPECT_EQ(a.corrected, b.corrected);
    EXPECT_EQ(batch[i].rho, b.rho);  // the batch helper gives the same as one call
    EXPECT_EQ(batch[i].vel[1], b.vel[1]);
  }
}

// numerics.vres_shepard_fill: below that donor fill the value is the Shepard average (not first
// order, so a linear field is no longer exact), above it the first-order value is kept. In the
// bulk the fill is about 1; 0.3 dp inside a face it is about 0.6.
TEST(VresInterp, ShepardBelowAGivenFill) {
  const int n = 12;
  const Donors<2> d = make_donors<2>(lattice<2>(n, 0.25), n);
  const Vec<2> bulk = point<2>(6.3, 5.8), face = point<2>(0.3, 6.1);
  auto with = [&](const Vec<2>& x, double fill) {
    return interpolate_from_level(x, d.ps, d.grid, d.kernel, kVresCondLimit, 1.0, fill);
  };
  const auto face_fo = with(face, 0.0), face_sh = with(face, 0.9), face_all = with(face, 2.0);
  const auto bulk_fo = with(bulk, 0.0), bulk_sh = with(bulk, 0.9), bulk_all = with(bulk, 2.0);
  std::printf(
      "[ vres shepard_fill ] fill bulk %.3f face %.3f; error at the face: first order "
      "%.2e, Shepard %.2e\n",
      donor_fill(bulk_fo), donor_fill(face_fo), rel_error(face_fo, face), rel_error(face_sh, face));
  ASSERT_GT(donor_fill(bulk_fo), 0.9);
  ASSERT_LT(donor_fill(face_fo), 0.9);
  EXPECT_TRUE(face_fo.corrected);
  EXPECT_LT(rel_error(face_fo, face), 1e-9);
  EXPECT_FALSE(face_sh.corrected);  // Shepard: sum V f W / sum V W, visibly off a linear field
  EXPECT_GT(rel_error(face_sh, face), 1e-3);
  EXPECT_NEAR(face_sh.rho, face_all.rho, 1e-12 * face_sh.rho);  // 2.0: the sums in lanes
  EXPECT_TRUE(bulk_sh.corrected);                               // above the fill: unchanged
  EXPECT_EQ(bulk_sh.rho, bulk_fo.rho);
  EXPECT_EQ(bulk_sh.vel[1], bulk_fo.vel[1]);
  EXPECT_FALSE(bulk_all.corrected);
}

// The Shepard sums in lanes (interpolate_values with a donor state holding columns, shepard_fill
// above 1) against the same sums donor by donor (interpolate_from_donor): equal to round-off, with
// fluid, buffer and wall donors, at the step's end and halfway through it, in the bulk, at a face,
// just beyond it and where no fluid is in reach.
template <int D>
void check_lanes(int n) {
  const auto pos = lattice<D>(n, 0.25);
  std::vector<Kind> kinds(pos.size(), Kind::fluid);
  for (std::size_t i = 0; i < pos.size(); i += 7) kinds[i] = i % 2 ? Kind::buffer : Kind::wall;
  Donors<D> d = make_donors<D>(pos, n, false, kinds);
  ASSERT_EQ(d.ps.pos0.size(), d.ps.size());
  for (std::size_t j = 0; j < d.ps.size(); ++j) {  // the state at the step's start
    for (int k = 0; k < D; ++k) d.ps.pos0[j][k] = d.ps.pos[j][k] - 0.01 * kDp * (k + 1);
    d.ps.vel0[j] = d.ps.vel[j] * 0.9;
    d.ps.rho0[j] = d.ps.rho[j] - 1.0;
  }
  const double c = 0.5 * n;
  const Vec<D> pts[] = {point<D>(c + 0.3, c - 0.2, c + 0.1), point<D>(0.3, c, c),
                        point<D>(-0.8, c + 0.1, c), point<D>(0.2, 0.3, 0.1), point<D>(-3.0, c, c)};
  auto near = [](double a, double b, double scale) { EXPECT_NEAR(a, b, 1e-13 * scale); };
  for (const double a : {1.0, 0.5}) {
    DonorStorage<D> s1, s2;
    const DonorState<D> plain(d.ps, d.grid, d.kernel, a, s1),
        lanes(d.ps, d.grid, d.kernel, a, s2, true);
    ASSERT_NE(lanes.columns, nullptr);
    for (const Vec<D>& x : pts) {
      const auto p = interpolate_from_donor(x, plain, kVresCondLimit, 2.0);
      const auto q = interpolate_values(x, lanes, kVresCondLimit, 2.0);
      near(q.shepard, p.shepard, 1.0);
      near(q.shepard_buffer, p.shepard_buffer, 1.0);
      near(q.shepard_walls, p.shepard_walls, 1.0);
      near(q.rho, p.rho, kRho0);
      for (int k = 0; k < D; ++k) near(q.vel[k], p.vel[k], 1.0);
      EXPECT_EQ(q.corrected, p.corrected);
    }
    if (a == 1.0) {  // a field of the donors' fluid (shepard_field), in lanes and donor by donor
      std::vector<double> f(d.ps.size());
      for (std::size_t j = 0; j < f.size(); ++j) f[j] = d.ps.rho[j] / kRho0;
      LaneColumns<D> fc, vc;
      fill_field_columns(d.ps, f, fc);
      fill_field_columns(d.ps, d.ps.vel, vc);
      for (const Vec<D>& x : pts) {
        near(shepard_field(x, d.grid, d.kernel, fc, -1.0),
             shepard_field(x, d.ps, d.grid, d.kernel, f, -1.0), 1.0);
        const Vec<D> v = shepard_field(x, d.grid, d.kernel, vc, Vec<D>{});
        const Vec<D> w = shepard_field(x, d.ps, d.grid, d.kernel, d.ps.vel, Vec<D>{});
        for (int k = 0; k < D; ++k) near(v[k], w[k], 1.0);
      }
    }
    // The point beyond the face has fluid in reach, the last one none.
    EXPECT_GT(interpolate_values(pts[2], lanes, kVresCondLimit, 2.0).shepard, kVresShepardMin);
    EXPECT_EQ(interpolate_values(pts[4], lanes, kVresCondLimit, 2.0).shepard, 0.0);
  }
}

TEST(VresInterp, ShepardInLanesAgreesWithDonorByDonor2D) { check_lanes<2>(12); }
TEST(VresInterp, ShepardInLanesAgreesWithDonorByDonor3D) { check_lanes<3>(8); }

}  // namespace
}  // namespace vrsph
