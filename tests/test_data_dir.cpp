// The shipped data folder found at run time (driver/data_dir.hpp): VRSPH_DATA_DIR first, then
// ../share/vrsph beside the executable when it holds cases/, then the source tree; and a case
// path looked up there when it is not in the current folder. tests/install_test.sh runs the
// installed program itself.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "vrsph/driver/data_dir.hpp"

namespace {

namespace fs = std::filesystem;
using vrsph::data_dir_for;
using vrsph::find_case_file;

// A temporary tree PREFIX/bin, PREFIX/share/vrsph/cases/a.toml, removed at the end.
struct Prefix {
  fs::path root = fs::temp_directory_path() / ("vrsph_data_dir_" + std::to_string(::getpid()));
  Prefix() {
    fs::create_directories(root / "bin");
    fs::create_directories(root / "share/vrsph/cases");
    std::ofstream(root / "share/vrsph/cases/a.toml") << "# a case\n";
  }
  ~Prefix() { fs::remove_all(root); }
};

// Sets VRSPH_DATA_DIR for one test and restores it.
struct DataDirEnv {
  std::string saved;
  bool had = false;
  explicit DataDirEnv(const std::string& value) {
    if (const char* v = std::getenv("VRSPH_DATA_DIR")) {
      saved = v;
      had = true;
    }
    ::setenv("VRSPH_DATA_DIR", value.c_str(), 1);
  }
  ~DataDirEnv() {
    if (had)
      ::setenv("VRSPH_DATA_DIR", saved.c_str(), 1);
    else
      ::unsetenv("VRSPH_DATA_DIR");
  }
};

TEST(DataDir, EnvironmentThenBesideTheExecutableThenTheSourceTree) {
  const Prefix p;
  const fs::path exe = p.root / "bin/vrsph";
  EXPECT_EQ(data_dir_for("/some/where", exe), fs::path("/some/where"));
  EXPECT_EQ(data_dir_for(nullptr, exe), p.root / "share/vrsph");
  EXPECT_EQ(data_dir_for("", exe), p.root / "share/vrsph");  // empty: as unset
  // A binary whose ../share/vrsph has no cases/ (a build folder) uses the source tree.
  EXPECT_EQ(data_dir_for(nullptr, p.root / "share/vrsph/cases/vrsph"), fs::path(VRSPH_SOURCE_DIR));
  EXPECT_EQ(data_dir_for(nullptr, fs::path()), fs::path(VRSPH_SOURCE_DIR));
  EXPECT_TRUE(fs::exists(fs::path(VRSPH_SOURCE_DIR) / "cases/bench_dam_break_2d.toml"));
}

TEST(DataDir, ACaseNotInTheCurrentFolderIsLookedUpInTheDataFolder) {
  const Prefix p;
  const DataDirEnv env((p.root / "share/vrsph").string());
  EXPECT_EQ(find_case_file("cases/a.toml"), p.root / "share/vrsph/cases/a.toml");
  // Found nowhere, absolute, or present from here: the path as given.
  EXPECT_EQ(find_case_file("cases/missing.toml"), fs::path("cases/missing.toml"));
  EXPECT_EQ(find_case_file("/cases/a.toml"), fs::path("/cases/a.toml"));
  const fs::path here = fs::current_path();
  fs::current_path(p.root / "share/vrsph");
  EXPECT_EQ(find_case_file("cases/a.toml"), fs::path("cases/a.toml"));
  fs::current_path(here);
}

}  // namespace
