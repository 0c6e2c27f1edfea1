// Checkpoint records and series.csv columns are read by name: the run state round-trips through
// a checkpoint file member by member (each member checked by hand, so one left out of the record
// list fails), a checkpoint of another format version is refused with a message naming the
// version, and every fixed series column shows its own row member.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "vrsph/driver/run_checkpoint.hpp"
#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/series.hpp"

namespace vrsph {
namespace {

namespace fs = std::filesystem;

fs::path temp_path(const std::string& stem) {
  return fs::temp_directory_path() /
         (stem + "_" + std::to_string(::getpid()) + "_" + std::to_string(std::random_device{}()));
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
  return out;
}

// A state with a different value in every member.
RunState distinct_state() {
  RunState s;
  s.time = 0.125;
  s.dt_next = 1.5e-5;
  s.dt_last = 2.5e-5;
  s.step = 4001;
  s.output_index = 17;
  s.levels = 3;
  s.initial_fluid = 123456;
  RunCounters& c = s.counters;
  c.particle_steps = 1001;
  c.pairs = 1002;
  c.dt_limit_counts = {1003, 1004, 1005, 1006};
  c.lost_fluid = 1007;
  c.wall_seconds = 1008.5;
  c.created = 1009;
  c.deleted = 1010;
  c.created_mass = 1011.25;
  c.deleted_mass = 1012.75;
  c.next_id = 1013;
  return s;
}

TEST(NamedRecords, RunStateRoundTripsMemberByMember) {
  Checkpoint ck;
  put_run_state(ck, distinct_state());
  const fs::path path = temp_path("vrsph_state");
  ck.save(path);
  const Checkpoint back = Checkpoint::load(path);
  fs::remove(path);
  const RunState s = get_run_state(back);
  EXPECT_EQ(s.time, 0.125);
  EXPECT_EQ(s.dt_next, 1.5e-5);
  EXPECT_EQ(s.dt_last, 2.5e-5);
  EXPECT_EQ(s.step, 4001);
  EXPECT_EQ(s.output_index, 17);
  EXPECT_EQ(s.levels, 3);
  EXPECT_EQ(s.initial_fluid, 123456u);
  const RunCounters& c = s.counters;
  EXPECT_EQ(c.particle_steps, 1001u);
  EXPECT_EQ(c.pairs, 1002u);
  EXPECT_EQ(c.dt_limit_counts, (std::array<std::uint64_t, 4>{1003, 1004, 1005, 1006}));
  EXPECT_EQ(c.lost_fluid, 1007u);
  EXPECT_EQ(c.wall_seconds, 1008.5);
  EXPECT_EQ(c.created, 1009u);
  EXPECT_EQ(c.deleted, 1010u);
  EXPECT_EQ(c.created_mass, 1011.25);
  EXPECT_EQ(c.deleted_mass, 1012.75);
  EXPECT_EQ(c.next_id, 1013u);
  // One record per value, under names that are part of the file format.
  const std::vector<std::string> names = {"counters.created",
                                          "counters.created_mass",
                                          "counters.deleted",
                                          "counters.deleted_mass",
                                          "counters.dt_limit.acoustic",
                                          "counters.dt_limit.capillary",
                                          "counters.dt_limit.force",
                                          "counters.dt_limit.viscous",
                                          "counters.lost_fluid",
                                          "counters.next_id",
                                          "counters.pairs",
                                          "counters.particle_steps",
                                          "counters.wall_seconds",
                                          "dt_last",
                                          "dt_next",
                                          "initial_fluid",
                                          "levels",
                                          "output_index",
                                          "step",
                                          "time"};
  EXPECT_EQ(back.names(), names);
}

TEST(NamedRecords, MissingRecordIsNamed) {
  const RunState s = distinct_state();
  Checkpoint partial;
  for_each_record(s, [&partial](const std::string& name, const auto& v) {
    if (name != "counters.pairs") partial.put_value(name, v);
  });
  try {
    get_run_state(partial);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'counters.pairs' is missing"), std::string::npos)
        << e.what();
  }
}

// A checkpoint of format version 1 (the layout before records were named: the counters in
// one positional array) is refused with one line naming both versions.
TEST(NamedRecords, OldFormatVersionIsRefused) {
  const fs::path path = temp_path("vrsph_old_checkpoint");
  {
    std::ofstream os(path, std::ios::binary);
    os.write("VRSPHCK\0", 8);
    const std::uint32_t version = 1;
    os.write(reinterpret_cast<const char*>(&version), sizeof(version));
    const std::string name = "counters";
    const auto len = static_cast<std::uint32_t>(name.size());
    os.write(reinterpret_cast<const char*>(&len), sizeof(len));
    os.write(name.data(), static_cast<std::streamsize>(name.size()));
    const std::uint8_t type = 3;  // u64
    os.write(reinterpret_cast<const char*>(&type), 1);
    const std::uint64_t count = 8;
    os.write(reinterpret_cast<const char*>(&count), sizeof(count));
    const std::vector<std::uint64_t> counters(8, 5);
    os.write(reinterpret_cast<const char*>(counters.data()), 8 * sizeof(std::uint64_t));
  }
  try {
    Checkpoint::load(path);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("checkpoint format version 1 is not supported"), std::string::npos) << what;
    EXPECT_NE(what.find("reads version " + std::to_string(kCheckpointVersion)), std::string::npos)
        << what;
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  fs::remove(path);
  EXPECT_GE(kCheckpointVersion, 2u);
}

// Every fixed column is named in the header and shows its own member, read back by name.
TEST(NamedRecords, SeriesColumnsShowTheirMembersByName) {
  const fs::path path = temp_path("vrsph_series");
  SeriesWriter w(path, {"extra_a", "extra_b"});
  SeriesRow row;
  row.t = 0.5;
  row.step = 12;
  row.dt = 0.25;
  row.n_fluid = 34;
  row.n_buffer = 56;
  row.mass_fluid = 7.5;
  row.kinetic_energy = 8.5;
  row.max_speed = 9.5;
  row.extra = {10.5, 11.5};
  w.append(row);
  std::istringstream text(read_text_file(path));
  fs::remove(path);
  std::string header, line;
  std::getline(text, header);
  std::getline(text, line);
  const auto names = split(header), values = split(line);
  ASSERT_EQ(names.size(), values.size());
  std::map<std::string, std::string> by_name;
  for (std::size_t k = 0; k < names.size(); ++k) by_name[names[k]] = values[k];
  EXPECT_EQ(by_name.size(), kSeriesColumns.size() + 2);
  const std::map<std::string, std::string> expected = {{"t", "0.5"},
                                                       {"step", "12"},
                                                       {"dt", "0.25"},
                                                       {"n_fluid", "34"},
                                                       {"n_buffer", "56"},
                                                       {"mass_fluid", "7.5"},
                                                       {"kinetic_energy", "8.5"},
                                                       {"max_speed", "9.5"},
                                                       {"extra_a", "10.5"},
                                                       {"extra_b", "11.5"}};
  EXPECT_EQ(by_name, expected);
  EXPECT_EQ(header,
            "t,step,dt,n_fluid,n_buffer,mass_fluid,kinetic_energy,max_speed,extra_a,extra_b");
}

}  // namespace
}  // namespace vrsph
