// ParticleSet's field list (particles/particles.hpp): every array of the list keeps its values per
// particle through the cell sort, compaction, a checkpoint save and load, resize and the merge
// of levels. Each field is filled with values derived from the particle id and the field's place
// in the list, and checked through the same list, so an operation that forgets a field fails;
// the number of fields of each role is checked against hand-written counts, so a field dropped
// from the list fails too.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "vrsph/driver/checkpoint.hpp"
#include "vrsph/output/snapshot.hpp"
#include "vrsph/particles/cell_grid.hpp"
#include "vrsph/particles/particles.hpp"

namespace vrsph {
namespace {

// Fields of each role in ParticleSet, counted by hand: update these with the list.
constexpr int kPersistentFields = 7;  // id kind pos vel rho mass shift
constexpr int kDerivedFields = 2;     // acc drho
constexpr int kStepCopyFields = 3;    // pos0 vel0 rho0

std::uint64_t mix(std::uint64_t x) {  // splitmix64
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// In [0, 1), distinct for every (id, field, component) in practice.
double unit(std::uint64_t id, int field, int comp) {
  return static_cast<double>(mix(id * 64 + static_cast<std::uint64_t>(field * 4 + comp)) >> 11) *
         0x1p-53;
}

// The value field number `field` holds for particle `id`. The id field holds the id; positions
// (like every vector) lie in [0, 1)^D, inside the test's grid.
template <class T>
T value_of(std::uint64_t id, int field, std::string_view name) {
  if constexpr (std::is_same_v<T, std::uint64_t>) {
    return name == "id" ? id : mix(id + 1000u * static_cast<std::uint64_t>(field));
  } else if constexpr (std::is_same_v<T, Kind>) {
    return static_cast<Kind>(mix(id * 16 + static_cast<std::uint64_t>(field)) % 3);
  } else if constexpr (std::is_same_v<T, double>) {
    return field + unit(id, field, 0);
  } else {
    T v{};
    for (std::size_t k = 0; k < v.c.size(); ++k) v.c[k] = unit(id, field, static_cast<int>(k));
    return v;
  }
}

template <int D>
ParticleSet<D> filled_set(std::size_t n, std::uint64_t seed, bool keeps_shift = true,
                          bool keeps_pos0 = true) {
  std::vector<std::uint64_t> ids(n);
  for (std::size_t k = 0; k < n; ++k) ids[k] = 5000 + 13 * k;
  std::shuffle(ids.begin(), ids.end(), std::mt19937_64(seed));
  ParticleSet<D> ps;
  ps.keep_mass(true);  // masses differ: one per particle, in the list
  ps.keep_shift(keeps_shift);
  ps.keep_pos0(keeps_pos0);
  ps.resize(n);
  int field = 0;
  ps.for_each_field([&](std::string_view name, auto& v, FieldRole) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    for (std::size_t i = 0; i < n; ++i) v[i] = value_of<T>(ids[i], field, name);
    ++field;
  });
  return ps;
}

// Checks every field whose role passes `want` against the values of its particle id; the others
// must have one entry per particle. Returns the number of fields checked per role.
template <int D, class Want>
std::map<FieldRole, int> expect_fields(const ParticleSet<D>& ps, Want want, const char* what) {
  std::map<FieldRole, int> checked;
  int field = 0;
  ps.for_each_field([&](std::string_view name, const auto& v, FieldRole role) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    ASSERT_EQ(v.size(), ps.size()) << what << ": " << name;
    if (want(role)) {
      ++checked[role];
      std::size_t bad = 0;
      for (std::size_t i = 0; i < ps.size(); ++i)
        bad += !(v[i] == value_of<T>(ps.id[i], field, name));
      EXPECT_EQ(bad, 0u) << what << ": field '" << name << "' lost its values for " << bad << " of "
                         << ps.size() << " particles";
    }
    ++field;
  });
  return checked;
}

// The test grid: over [0, 1)^D, where the filled sets lie, with a margin; cells of 0.1.
template <int D>
CellGrid<D> cloud_grid() {
  Vec<D> lo, hi;
  for (int k = 0; k < D; ++k) lo[k] = -0.1, hi[k] = 1.1;
  return CellGrid<D>(lo, hi, 0.1, 2);
}

bool all_roles(FieldRole) { return true; }
bool persistent_only(FieldRole r) { return r == FieldRole::persistent; }

template <class T>
class FieldListTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(FieldListTest, Dims);

TYPED_TEST(FieldListTest, ListHasTheExpectedFields) {
  constexpr int D = TypeParam::value;
  ParticleSet<D> ps;
  ps.keep_mass(true);  // the list with every optional array
  std::map<FieldRole, int> count;
  std::set<std::string> names;
  ps.for_each_field([&](std::string_view name, auto&, FieldRole role) {
    ++count[role];
    EXPECT_TRUE(names.insert(std::string(name)).second) << "name used twice: " << name;
  });
  EXPECT_EQ(count[FieldRole::persistent], kPersistentFields);
  EXPECT_EQ(count[FieldRole::derived], kDerivedFields);
  EXPECT_EQ(count[FieldRole::step_copy], kStepCopyFields);
}

TYPED_TEST(FieldListTest, EveryCarriedFieldSurvivesTheSort) {
  constexpr int D = TypeParam::value;
  ParticleSet<D> ps = filled_set<D>(3000, 7);
  const auto ids_before = ps.id;
  CellGrid<D> grid = cloud_grid<D>();
  ASSERT_TRUE(grid.sort(ps).empty());
  ASSERT_EQ(ps.size(), ids_before.size());
  ASSERT_NE(ps.id, ids_before) << "the sort should reorder this cloud";
  const auto checked = expect_fields(ps, carried, "sort");
  EXPECT_EQ(checked.at(FieldRole::persistent), kPersistentFields);
  EXPECT_EQ(checked.at(FieldRole::step_copy), kStepCopyFields);
}

TYPED_TEST(FieldListTest, EveryCarriedFieldSurvivesCompaction) {
  constexpr int D = TypeParam::value;
  ParticleSet<D> ps = filled_set<D>(500, 8);
  std::vector<std::uint8_t> keep(ps.size());
  std::vector<std::uint64_t> kept_ids;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    keep[i] = mix(ps.id[i]) % 3 != 0;
    if (keep[i]) kept_ids.push_back(ps.id[i]);
  }
  ASSERT_GT(kept_ids.size(), 100u);
  ASSERT_LT(kept_ids.size(), ps.size());
  const std::size_t n0 = ps.size();
  EXPECT_EQ(ps.compact(keep), n0 - kept_ids.size());
  EXPECT_EQ(ps.id, kept_ids);  // in order
  const auto checked = expect_fields(ps, carried, "compact");
  EXPECT_EQ(checked.at(FieldRole::persistent), kPersistentFields);
  EXPECT_EQ(checked.at(FieldRole::step_copy), kStepCopyFields);
}

TYPED_TEST(FieldListTest, EveryPersistentFieldSurvivesACheckpoint) {
  constexpr int D = TypeParam::value;
  const ParticleSet<D> ps = filled_set<D>(400, 9);
  Checkpoint ck;
  ck.put_particles<D>(3, ps);
  const std::vector<std::string> names = {"level3.id",  "level3.kind",  "level3.mass", "level3.pos",
                                          "level3.rho", "level3.shift", "level3.vel"};
  EXPECT_EQ(ck.names(), names);  // record names are part of the file format
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("vrsph_fields_" + std::to_string(::getpid()) + ".bin");
  ck.save(path);
  const Checkpoint back = Checkpoint::load(path);
  std::filesystem::remove(path);
  ParticleSet<D> restored;
  back.get_particles<D>(3, restored);
  ASSERT_EQ(restored.id, ps.id);
  const auto checked = expect_fields(restored, persistent_only, "checkpoint");
  EXPECT_EQ(checked.at(FieldRole::persistent), kPersistentFields);
}

TYPED_TEST(FieldListTest, ResizeAndMergeCoverEveryField) {
  constexpr int D = TypeParam::value;
  const ParticleSet<D> a = filled_set<D>(60, 10), b = filled_set<D>(40, 11);
  const std::vector<const ParticleSet<D>*> sets = {&a, &b};
  const MergedLevels<D> m = merge_levels<D>(sets);
  ASSERT_EQ(m.particles.size(), 100u);
  for (std::size_t i = 0; i < 100; ++i) {
    EXPECT_EQ(m.particles.id[i], i < 60 ? a.id[i] : b.id[i - 60]);
    EXPECT_EQ(m.level[i], i < 60 ? 0 : 1);
  }
  // ids repeat between the two sets, with the same values: the check by id still holds.
  const auto checked = expect_fields(m.particles, all_roles, "merge");
  EXPECT_EQ(checked.at(FieldRole::persistent) + checked.at(FieldRole::derived) +
                checked.at(FieldRole::step_copy),
            kPersistentFields + kDerivedFields + kStepCopyFields);
  ParticleSet<D> grown = a;
  grown.resize(75);
  int sized = 0;
  grown.for_each_field([&](std::string_view name, const auto& v, FieldRole) {
    EXPECT_EQ(v.size(), 75u) << name;
    ++sized;
  });
  EXPECT_EQ(sized, kPersistentFields + kDerivedFields + kStepCopyFields);
}

}  // namespace
}  // namespace vrsph

namespace vrsph {
namespace {

// A level that does not shift keeps no shift array: the sort, compaction, a checkpoint (no
// shift record), resize and the merge leave it empty and carry every other field; keeping it
// again gives one zero displacement per particle.
TYPED_TEST(FieldListTest, WithoutShiftingTheShiftArrayStaysEmpty) {
  constexpr int D = TypeParam::value;
  ParticleSet<D> ps = filled_set<D>(800, 12, false);
  CellGrid<D> grid = cloud_grid<D>();
  ASSERT_TRUE(grid.sort(ps).empty());
  EXPECT_TRUE(ps.shift.empty());
  EXPECT_EQ(expect_fields(ps, carried, "sort").at(FieldRole::persistent), kPersistentFields - 1);
  std::vector<std::uint8_t> keep(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) keep[i] = mix(ps.id[i]) % 4 != 0;
  ps.compact(keep);
  EXPECT_TRUE(ps.shift.empty());
  expect_fields(ps, carried, "compact");
  Checkpoint ck;
  ck.put_particles<D>(0, ps);
  EXPECT_FALSE(ck.has("level0.shift"));
  ParticleSet<D> restored;
  ck.get_particles<D>(0, restored);
  EXPECT_FALSE(restored.keeps_shift);
  EXPECT_TRUE(restored.shift.empty());
  ASSERT_EQ(restored.id, ps.id);
  expect_fields(restored, persistent_only, "checkpoint");
  const ParticleSet<D> other = filled_set<D>(30, 13, false);
  const std::vector<const ParticleSet<D>*> sets = {&ps, &other};
  const MergedLevels<D> m = merge_levels<D>(sets);
  EXPECT_TRUE(m.particles.shift.empty());
  expect_fields(m.particles, carried, "merge");  // acc and drho are stale since the sort
  ps.resize(ps.size() + 5);
  EXPECT_TRUE(ps.shift.empty());
  ps.keep_shift(true);
  ASSERT_EQ(ps.shift.size(), ps.size());
  for (const Vec<D>& d : ps.shift) EXPECT_EQ(norm(d), 0.0);
}

// A level whose particles share one mass keeps it once (mass_each, no array): push_back of the
// same mass, the sort, compaction and resize leave the array empty; a checkpoint stores one
// mass per particle (the file format) and the load shares it again; the merge of two levels
// gives each particle its level's mass; a different mass makes the set keep one per particle.
TYPED_TEST(FieldListTest, AUniformMassIsKeptOnce) {
  constexpr int D = TypeParam::value;
  ParticleSet<D> ps;
  const double m = 0.0125;
  for (std::uint64_t k = 0; k < 600; ++k)
    ps.push_back(k, Kind::fluid, value_of<Vec<D>>(k, 3, "pos"), Vec<D>{}, 1000.0, m);
  EXPECT_FALSE(ps.keeps_mass);
  EXPECT_TRUE(ps.mass.empty());
  CellGrid<D> grid = cloud_grid<D>();
  ASSERT_TRUE(grid.sort(ps).empty());
  std::vector<std::uint8_t> keep(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) keep[i] = mix(ps.id[i]) % 4 != 0;
  ps.compact(keep);
  ps.resize(ps.size() + 3);
  EXPECT_TRUE(ps.mass.empty());
  EXPECT_EQ(ps.mass_of(ps.size() - 1), m);
  Checkpoint ck;
  ck.put_particles<D>(0, ps);
  ASSERT_TRUE(ck.has("level0.mass"));
  EXPECT_EQ(ck.f64("level0.mass"), std::vector<double>(ps.size(), m));
  ParticleSet<D> restored;
  ck.get_particles<D>(0, restored);
  EXPECT_FALSE(restored.keeps_mass);
  EXPECT_EQ(restored.mass_each, m);
  ParticleSet<D> coarse;
  coarse.push_back(1, Kind::fluid, Vec<D>{}, Vec<D>{}, 1000.0, 4.0 * m);
  const std::vector<const ParticleSet<D>*> sets = {&ps, &coarse};
  const MergedLevels<D> merged = merge_levels<D>(sets);
  ASSERT_TRUE(merged.particles.keeps_mass);
  EXPECT_EQ(merged.particles.mass.front(), m);
  EXPECT_EQ(merged.particles.mass.back(), 4.0 * m);
  const std::size_t n = ps.size();
  ps.push_back(9999, Kind::fluid, Vec<D>{}, Vec<D>{}, 1000.0, 2.0 * m);
  ASSERT_TRUE(ps.keeps_mass);
  ASSERT_EQ(ps.mass.size(), n + 1);
  EXPECT_EQ(ps.mass_of(n - 1), m);
  EXPECT_EQ(ps.mass_of(n), 2.0 * m);
}

// A single-level run keeps no pos0 (the corrector does without it): the sort and the merge carry
// every other field and leave it empty; the step copies are then vel0 and rho0 only.
TYPED_TEST(FieldListTest, WithoutPos0TheStepCopiesAreTheRest) {
  constexpr int D = TypeParam::value;
  ParticleSet<D> ps = filled_set<D>(500, 14, true, false);
  CellGrid<D> grid = cloud_grid<D>();
  ASSERT_TRUE(grid.sort(ps).empty());
  EXPECT_TRUE(ps.pos0.empty());
  EXPECT_EQ(expect_fields(ps, carried, "sort").at(FieldRole::step_copy), kStepCopyFields - 1);
  const ParticleSet<D> other = filled_set<D>(30, 15, true, false);
  const std::vector<const ParticleSet<D>*> sets = {&ps, &other};
  EXPECT_TRUE(merge_levels<D>(sets).particles.pos0.empty());
  ps.keep_pos0(true);
  ASSERT_EQ(ps.pos0.size(), ps.size());
}

// The sort at the end of a single-level step leaves the step copies ungathered (the next
// predictor rewrites them): every persistent field keeps its values, the copies keep their size.
TYPED_TEST(FieldListTest, SortWithDeadStepCopiesCarriesTheState) {
  constexpr int D = TypeParam::value;
  ParticleSet<D> ps = filled_set<D>(900, 16);
  CellGrid<D> grid = cloud_grid<D>();
  ASSERT_TRUE(grid.sort(ps, false).empty());
  EXPECT_EQ(expect_fields(ps, persistent_only, "sort").at(FieldRole::persistent),
            kPersistentFields);
  EXPECT_EQ(ps.vel0.size(), ps.size());
  EXPECT_EQ(ps.rho0.size(), ps.size());
  EXPECT_EQ(ps.pos0.size(), ps.size());
}

}  // namespace
}  // namespace vrsph
