// Restart files. A checkpoint is a versioned binary file of named arrays ("records"), so later
// state (more levels, buffer zones, accumulated masses at creation points) is added as new
// records without breaking old files: a reader asks for the records it knows.
// Layout: "VRSPHCK\0", u32 version, then records: u32 name length, name, u8 type, u64 count,
// raw little-endian data. Written atomically (temp file + rename).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vrsph/particles/particles.hpp"

namespace vrsph {

class Checkpoint {
 public:
  void put(const std::string& name, std::vector<double> v);
  void put(const std::string& name, std::vector<std::int64_t> v);
  void put(const std::string& name, std::vector<std::uint64_t> v);
  void put(const std::string& name, std::vector<std::uint8_t> v);
  void put_scalar(const std::string& name, double v) { put(name, std::vector<double>{v}); }

  const std::vector<double>& f64(const std::string& name) const;
  const std::vector<std::int64_t>& i64(const std::string& name) const;
  const std::vector<std::uint64_t>& u64(const std::string& name) const;
  const std::vector<std::uint8_t>& u8(const std::string& name) const;
  double scalar(const std::string& name) const;
  bool has(const std::string& name) const;
  std::vector<std::string> names() const;  // every record, sorted

  void save(const std::filesystem::path& path) const;
  static Checkpoint load(const std::filesystem::path& path);

  // The persistent arrays of ParticleSet's field list for one level, as "levelN.<field>"
  // (vectors flattened, D values per particle).
  template <int D>
  void put_particles(int level, const ParticleSet<D>& ps);
  template <int D>
  void get_particles(int level, ParticleSet<D>& ps) const;

 private:
  template <class T>
  const std::vector<T>& get(const std::string& name) const;

  std::map<std::string, std::vector<double>> f64_;
  std::map<std::string, std::vector<std::int64_t>> i64_;
  std::map<std::string, std::vector<std::uint64_t>> u64_;
  std::map<std::string, std::vector<std::uint8_t>> u8_;
};

}  // namespace vrsph
