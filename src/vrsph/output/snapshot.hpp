// Particle snapshots: VTK XML PolyData (.vtp) with a ParaView time-series collection (.pvd), and
// plain CSV. Extra per-particle fields can be appended as further arrays/columns without touching
// the writers. Column and array names: docs/outputs.md ("Particle snapshots").
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vrsph/particles/particles.hpp"
#include "vrsph/physics/eos.hpp"

namespace vrsph {

// One extra per-particle field: values are particle-major, values[i * components + c].
// In the CSV a 1-component field is one column `name`; 2 or 3 components become
// `name_x,name_y[,name_z]`, more become `name_0,name_1,...`. In the .vtp it is one array
// (a 2-component field in 2D is padded with z = 0 so ParaView treats it as a vector).
struct ExtraField {
  std::string name;
  int components = 1;
  std::vector<double> values;  // size() == n * components
};

// How the particle fields of a snapshot are stored (case keys output.precision and
// output.compression, docs/outputs.md).
struct SnapshotFormat {
  // Particle fields (velocity, rho, p, mass and the extras) as float32: Float32 arrays in the
  // .vtp, and in the CSV the shortest text that reads back as the same float (about 7 digits
  // instead of up to 17). Positions, id, level and kind are written as without it.
  bool float32 = false;
  // The .vtp appended data zlib-compressed (vtk_zlib.hpp); the CSV is not affected.
  bool zlib = false;
};

// `level` gives the resolution level of each particle; empty means all level 0. The pressure is
// written as the EOS `eos` gives it from each particle's density (it is not stored).
// Both writers are atomic (temp file + rename) and throw std::runtime_error on I/O failure and
// std::invalid_argument when an extra field or `level` has the wrong size.

// VTK XML PolyData, appended binary (Float64 / UInt64 / UInt8 / Int64; the fields Float32 with
// format.float32): Points (x, y, z; z = 0 in 2D, always Float64), one vertex per particle,
// PointData id, level, kind (0 fluid, 1 wall, 2 buffer), velocity (3 components), rho, p, mass,
// then the extras.
template <int D>
void write_vtp(const std::filesystem::path& path, const ParticleSet<D>& ps, const TaitEos& eos,
               std::span<const ExtraField> extras, std::span<const std::uint8_t> level,
               SnapshotFormat format = {});

// CSV with header id,level,kind,x,y[,z],vx,vy[,vz],rho,p,mass[,extras...]; kind as a word;
// numbers in shortest round-trip form (of the float32 value for the fields with format.float32).
template <int D>
void write_particles_csv(const std::filesystem::path& path, const ParticleSet<D>& ps,
                         const TaitEos& eos, std::span<const ExtraField> extras,
                         std::span<const std::uint8_t> level, SnapshotFormat format = {});

// "particles_0007.vtp" for (7, "vtp"): the snapshot file name of output number `index`.
std::string snapshot_file_name(int index, std::string_view extension);

// Several resolution levels gathered into one set for a snapshot (all levels go into the same
// file): every array of ParticleSet's field list is copied level after level, and `level[i]` is
// the index of the level particle i came from.
template <int D>
struct MergedLevels {
  ParticleSet<D> particles;
  std::vector<std::uint8_t> level;
};
template <int D>
MergedLevels<D> merge_levels(std::span<const ParticleSet<D>* const> levels);

// The .pvd collection listing the snapshots with their times (seconds), kept in time order.
class PvdCollection {
 public:
  struct Entry {
    double time = 0.0;
    std::string file;  // relative to the .pvd's directory
  };

  explicit PvdCollection(std::filesystem::path pvd_path);

  // Reads the entries of an existing .pvd (for a resumed run), keeping those with
  // time <= up_to_time; a missing file gives an empty collection.
  static PvdCollection load(const std::filesystem::path& pvd_path,
                            double up_to_time = std::numeric_limits<double>::infinity());

  // Adds a snapshot; an entry with the same file name is replaced. Entries stay sorted by time.
  void add(double time, const std::string& vtp_file_name);
  // Rewrites the .pvd atomically.
  void write() const;

  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::filesystem::path path_;
  std::vector<Entry> entries_;
};

}  // namespace vrsph
