// The checks that keep a run's folder and checkpoint sound, in-process: a checkpoint with a
// damaged byte, a cut or extra bytes is refused naming the file and the record; per-particle
// vectors beside the field list round-trip or are refused; the case check names the key that
// changed; the lock of an output folder goes to exactly one of many starts and is taken over when
// its holder died; leftovers of atomic writes are told from other files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "vrsph/driver/fnv_hash.hpp"
#include "vrsph/driver/run_checkpoint.hpp"
#include "vrsph/output/atomic_file.hpp"
#include "vrsph/output/run_lock.hpp"
#include "vrsph/setup/case_keys.hpp"

namespace vrsph {
namespace {

namespace fs = std::filesystem;

// A fresh folder under the temp dir, removed at the end.
struct ScratchDir {
  fs::path path = fs::temp_directory_path() / ("vrsph_checks_" + std::to_string(::getpid()) + "_" +
                                               std::to_string(std::random_device{}()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

// A checkpoint of three records of different types.
Checkpoint three_records() {
  Checkpoint ck;
  ck.put("alpha", std::vector<double>{1.0, 2.0, 3.0, 4.0});
  ck.put("beta", std::vector<std::int64_t>{-5, 6});
  ck.put("gamma", std::vector<std::uint8_t>{7, 8, 9});
  return ck;
}

// The message of the CheckpointError that loading `path` throws ("" when it loads).
std::string load_error(const fs::path& path) {
  try {
    Checkpoint::load(path);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

// Per-particle vectors beside the field list (the capillary refresh's held acceleration): they
// come back as written; an absent record leaves the array, an empty one empties it, and a record
// of another size is refused naming it.
TEST(CheckpointChecks, HeldVectorsComeBackOrAreRefusedNamingTheRecord) {
  Checkpoint ck;
  const std::vector<Vec<2>> a = {Vec<2>{1.0, -2.0}, Vec<2>{3.5, 0.25}};
  ck.put_vectors<2>("level0.acc_ref", a);
  ck.put_vectors<2>("level0.acc_rate", std::vector<Vec<2>>{});
  std::vector<Vec<2>> b;
  ck.get_vectors<2>("level0.acc_ref", 2, b);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[1][0], 3.5);
  EXPECT_EQ(b[0][1], -2.0);
  ck.get_vectors<2>("level0.absent", 2, b);
  EXPECT_EQ(b.size(), 2u);
  ck.get_vectors<2>("level0.acc_rate", 2, b);
  EXPECT_TRUE(b.empty());
  try {
    ck.get_vectors<2>("level0.acc_ref", 3, b);
    ADD_FAILURE() << "a record of 2 vectors read as 3";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("level0.acc_ref: 4 values for 3 particles"),
              std::string::npos)
        << e.what();
  }
}

TEST(CheckpointChecks, FnvMatchesItsPublishedValues) {
  // FNV-1a 64 test vectors (Fowler, Noll, Vo).
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);
}

TEST(CheckpointChecks, AByteFlippedInARecordNamesTheRecord) {
  ScratchDir dir;
  const fs::path path = dir.path / "checkpoint.bin";
  three_records().save(path);
  ASSERT_EQ(load_error(path), "");
  const std::string good = read_bytes(path);
  // Flip one bit in the data of each record in turn: each is named.
  for (const std::string name : {"alpha", "beta", "gamma"}) {
    const std::size_t at = good.find(name);
    ASSERT_NE(at, std::string::npos) << name;
    std::string bad = good;
    bad[at + name.size() + 1 + 8] ^= 0x10;  // the first data byte, after type and count
    write_bytes(path, bad);
    const std::string what = load_error(path);
    EXPECT_NE(what.find("record '" + name + "' fails its checksum"), std::string::npos) << what;
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  // A damaged name is shown on one line all the same.
  std::string bad_name = good;
  bad_name[good.find("beta")] = '\n';
  write_bytes(path, bad_name);
  const std::string what = load_error(path);
  EXPECT_NE(what.find("record '?eta' fails its checksum"), std::string::npos) << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  // A flipped count runs past the end of the file instead of being allocated.
  std::string bad = good;
  bad[good.find("alpha") + 5 + 1 + 7] = '\x7f';
  write_bytes(path, bad);
  EXPECT_NE(load_error(path).find("'alpha'"), std::string::npos) << load_error(path);
}

TEST(CheckpointChecks, TruncatedOrExtendedFilesAreRefused) {
  ScratchDir dir;
  const fs::path path = dir.path / "checkpoint.bin";
  three_records().save(path);
  const std::string good = read_bytes(path);
  // Cut at every length from the header on: always refused, naming the file; a cut at a record
  // boundary too (the header counts the records).
  for (std::size_t n = 0; n < good.size(); ++n) {
    write_bytes(path, good.substr(0, n));
    const std::string what = load_error(path);
    ASSERT_NE(what, "") << "cut to " << n << " of " << good.size() << " bytes";
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    if (n >= 20) {
      EXPECT_NE(what.find("truncated"), std::string::npos) << n << ": " << what;
    }
  }
  const std::size_t after_alpha = good.find("beta") - 4;  // the name length of record 2
  write_bytes(path, good.substr(0, after_alpha));
  EXPECT_NE(load_error(path).find("record 2 of 3"), std::string::npos) << load_error(path);
  write_bytes(path, good + "x");
  EXPECT_NE(load_error(path).find("1 bytes follow the last"), std::string::npos)
      << load_error(path);
}

TEST(CheckpointChecks, OtherFormatVersionsAreRefusedNamingTheVersion) {
  ScratchDir dir;
  const fs::path path = dir.path / "checkpoint.bin";
  three_records().save(path);
  std::string bytes = read_bytes(path);
  for (const std::uint32_t v : {1u, 2u, kCheckpointVersion + 1}) {
    bytes.replace(8, 4, reinterpret_cast<const char*>(&v), 4);
    write_bytes(path, bytes);
    const std::string what = load_error(path);
    EXPECT_NE(what.find("checkpoint format version " + std::to_string(v) + " is not supported"),
              std::string::npos)
        << what;
  }
  EXPECT_EQ(kCheckpointVersion, 3u);
}

TEST(CheckpointChecks, CaseCheckNamesTheChangedKeysOnly) {
  CaseSpec a;
  a.name = "c";
  a.dimension = 2;
  a.end_time = 1.0;
  a.dp = 0.01;
  a.fluid_blocks.push_back({});
  Checkpoint ck;
  put_case(ck, physical_case_text(a));
  EXPECT_NO_THROW(check_case(ck, a, "ck.bin"));
  CaseSpec later = a;  // the end time and the output keys may change
  later.end_time = 2.0;
  later.output_interval = 0.125;
  later.write_csv = !a.write_csv;
  EXPECT_NO_THROW(check_case(ck, later, "ck.bin"));
  CaseSpec other = a;
  other.dp = 0.02;
  other.fluid_blocks[0].max = {0.5, 0.25, 0.0};
  try {
    check_case(ck, other, "dir/ck.bin");
    FAIL() << "a changed dp was accepted";
  } catch (const CheckpointError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("dir/ck.bin: ", 0), 0u) << what;
    EXPECT_NE(what.find("resolution.dp = 0.02 (checkpoint: 0.01)"), std::string::npos) << what;
    EXPECT_NE(what.find("fluid_block.0.max = [0.5, 0.25] (checkpoint: [0, 0])"), std::string::npos)
        << what;
    EXPECT_EQ(what.find("end_time ="), std::string::npos) << what;
  }
}

TEST(CheckpointChecks, PhysicalKeysLeaveOutEndTimeAndOutput) {
  EXPECT_TRUE(is_physical_key("resolution.dp"));
  EXPECT_TRUE(is_physical_key("case.name"));
  EXPECT_TRUE(is_physical_key("outputs.x"));
  EXPECT_FALSE(is_physical_key("case.end_time"));
  EXPECT_FALSE(is_physical_key("output.interval"));
  EXPECT_FALSE(is_physical_key("output.line.0.from"));
  CaseSpec s;
  s.name = "k";
  s.dimension = 2;
  s.end_time = 1.0;
  s.dp = 0.01;
  const auto keys = parse_case_text(physical_case_text(s));
  EXPECT_EQ(keys.at("resolution.dp"), "0.01");
  EXPECT_EQ(keys.at("case.name"), "\"k\"");
  EXPECT_TRUE(keys.count("numerics.viscosity.model"));  // inline tables flattened
  EXPECT_FALSE(keys.count("case.end_time"));
  for (const auto& [k, v] : keys) EXPECT_FALSE(k.starts_with("output")) << k;
}

TEST(RunLockChecks, OneOfManySimultaneousStartsWins) {
  // Each start opens the lock file on its own, as separate processes do (flock is per open
  // file), all at once; exactly one gets it, the others are refused naming its pid.
  ScratchDir dir;
  constexpr int kStarts = 8;
  std::atomic<int> ready{0}, winners{0}, refused{0}, tried{0};
  std::vector<std::thread> starts;
  for (int k = 0; k < kStarts; ++k) {
    starts.emplace_back([&] {
      ++ready;
      while (ready < kStarts) std::this_thread::yield();
      try {
        RunLock lock(dir.path, "--out");
        ++winners;
        ++tried;
        while (tried < kStarts) std::this_thread::yield();  // hold it until all have tried
      } catch (const CaseError& e) {
        if (std::string(e.what()).find("pid " + std::to_string(::getpid())) != std::string::npos)
          ++refused;
        ++tried;
      }
    });
  }
  for (auto& t : starts) t.join();
  EXPECT_EQ(winners, 1);
  EXPECT_EQ(refused, kStarts - 1);
  EXPECT_FALSE(fs::exists(dir.path / RunLock::kFileName)) << "removed by its holder";
}

TEST(RunLockChecks, LockOfADeadRunIsTakenOverAndNamed) {
  ScratchDir dir;
  write_bytes(dir.path / RunLock::kFileName, "pid 123456789\nhost elsewhere\nstarted yesterday\n");
  {
    RunLock lock(dir.path, "--resume");
    EXPECT_EQ(lock.stale_holder(), "pid 123456789 on host elsewhere, started yesterday");
    const std::string mine = read_bytes(dir.path / RunLock::kFileName);
    EXPECT_EQ(mine.rfind("pid " + std::to_string(::getpid()) + "\n", 0), 0u) << mine;
    EXPECT_THROW(RunLock(dir.path, "--resume"), CaseError);
  }
  RunLock again(dir.path, "--out");  // released and removed: a plain start
  EXPECT_EQ(again.stale_holder(), "");
}

TEST(AtomicFileChecks, LeftoverTempFilesAreToldFromOtherFiles) {
  EXPECT_TRUE(is_temp_file_name(".series.csv.tmpAb12Cd"));
  EXPECT_TRUE(is_temp_file_name(".checkpoint.bin.tmp000000"));
  EXPECT_FALSE(is_temp_file_name("series.csv.tmpAb12Cd"));  // not hidden
  EXPECT_FALSE(is_temp_file_name(".series.csv.tmpAb12"));   // not mkstemp's six
  EXPECT_FALSE(is_temp_file_name(".notes.tmp"));
  EXPECT_FALSE(is_temp_file_name(".x.tmpAb-2Cd"));
  ScratchDir dir;
  write_bytes(dir.path / ".case.toml.tmpQwErTy", "half");
  write_bytes(dir.path / ".notes.tmp", "mine");
  write_bytes(dir.path / "case.toml", "whole");
  EXPECT_EQ(remove_temp_files(dir.path), 1u);
  EXPECT_FALSE(fs::exists(dir.path / ".case.toml.tmpQwErTy"));
  EXPECT_TRUE(fs::exists(dir.path / ".notes.tmp"));
  EXPECT_TRUE(fs::exists(dir.path / "case.toml"));
}

}  // namespace
}  // namespace vrsph
