// A temporary directory, text helpers and small particle sets shared by the output-layer tests
// (test_output*.cpp).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "vrsph/output/atomic_file.hpp"
#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/eos.hpp"

namespace vrsph::output_fixtures {

namespace fs = std::filesystem;

// A fresh directory under the system temp dir, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() /
           ("vrsph_output_test_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
};

inline std::string read_all(const fs::path& p) { return read_text_file(p); }

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

inline std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
  return out;
}

// The EOS the snapshot tests write pressures with (B = 14,285.7 Pa): p = 0 at 1000 kg/m^3.
inline const TaitEos kEos(1000.0, 7.0, 10.0);

// The pressure column a snapshot written with kEos holds.
template <int D>
std::vector<double> pressures(const ParticleSet<D>& ps) {
  std::vector<double> p;
  for (double rho : ps.rho) p.push_back(kEos.pressure(rho));
  return p;
}

// Four 2D particles of every kind with awkward (non-short) numbers.
inline ParticleSet<2> small_set_2d() {
  ParticleSet<2> ps;
  ps.push_back(7, Kind::fluid, {{0.1, 1.0 / 3.0}}, {{-2.5e-3, 1e-17}}, 1000.0000001, 2.5e-6);
  ps.push_back(3, Kind::wall, {{-4e-3, 0.0}}, {{0.0, 0.0}}, 999.5, 2.5e-6);
  ps.push_back(11, Kind::buffer, {{1e-300, -7.25}}, {{0.3, 0.4}}, 1001.0, 6.25e-7);
  ps.push_back(12, Kind::fluid, {{2.0, 3.0}}, {{3.0, 4.0}}, 1000.0, 1.0);
  return ps;
}

inline ParticleSet<3> small_set_3d() {
  ParticleSet<3> ps;
  ps.push_back(1, Kind::fluid, {{0.1, 0.2, 0.3}}, {{1.0, 2.0, 2.0}}, 1000.0, 1e-9);
  ps.push_back(2, Kind::wall, {{-0.1, 0.2, -0.3}}, {{0.0, 0.0, 0.0}}, 1000.0, 1e-9);
  return ps;
}

}  // namespace vrsph::output_fixtures
