// Restart files. A checkpoint is a versioned binary file of named arrays ("records"); every value
// is read back by its name, never by its place in a file or in an array. A reader asks for the
// records it knows, and a change of what a record means bumps kCheckpointVersion.
// Layout (little-endian): "VRSPHCK\0", u32 version, u64 record count, then each record: u32 name
// length, name, u8 type, u64 count, raw data, u64 FNV-1a checksum of the record's bytes from its
// name length to its data. Written atomically (temp file + rename); the reader refuses a file
// that is truncated, has a record failing its checksum, or has bytes after its last record.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vrsph/particles/particles.hpp"
#include "vrsph/setup/case_parser.hpp"

namespace vrsph {

// Version 3: a record count in the header and a checksum per record.
// Version 2: each counter its own named record, particle arrays named after the field list.
// Older versions are refused with a message naming the version.
inline constexpr std::uint32_t kCheckpointVersion = 3;

// A checkpoint that cannot be used: damaged, truncated, of another format version, or of another
// case. Bad input (exit status 1); what() names the file and the reason on one line.
struct CheckpointError : CaseError {
  using CaseError::CaseError;
};

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

  // One-value records of type double, std::int64_t or std::uint64_t.
  template <class T>
  void put_value(const std::string& name, T v) {
    put(name, std::vector<T>{v});
  }
  template <class T>
  T value(const std::string& name) const;

  void save(const std::filesystem::path& path) const;
  // Throws CheckpointError for a file that is not a whole, undamaged checkpoint of this version,
  // std::runtime_error when it cannot be opened.
  static Checkpoint load(const std::filesystem::path& path);

  // The persistent arrays of ParticleSet's field list for one level, as "levelN.<field>"
  // (vectors flattened, D values per particle; the mass one per particle even where the set
  // keeps one for all, which the load shares again).
  template <int D>
  void put_particles(int level, const ParticleSet<D>& ps);
  template <int D>
  void get_particles(int level, ParticleSet<D>& ps) const;

  // One vector per particle as a flattened record (D values each), beside the field list's.
  // get_vectors: an absent record leaves v as it is, an empty one empties it; any other size
  // than n D values is a CheckpointError.
  template <int D>
  void put_vectors(const std::string& name, const std::vector<Vec<D>>& v);
  template <int D>
  void get_vectors(const std::string& name, std::size_t n, std::vector<Vec<D>>& v) const;
  // The same for one value per particle (written with put).
  void get_values(const std::string& name, std::size_t n, std::vector<double>& v) const;

 private:
  template <class T>
  const std::vector<T>& get(const std::string& name) const;

  std::map<std::string, std::vector<double>> f64_;
  std::map<std::string, std::vector<std::int64_t>> i64_;
  std::map<std::string, std::vector<std::uint64_t>> u64_;
  std::map<std::string, std::vector<std::uint8_t>> u8_;
};

}  // namespace vrsph
