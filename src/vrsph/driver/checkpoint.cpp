#include "vrsph/driver/checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <type_traits>

namespace vrsph {
namespace {

template <class T>
const std::vector<T>& find(const std::map<std::string, std::vector<T>>& m,
                           const std::string& name) {
  auto it = m.find(name);
  if (it == m.end()) throw std::runtime_error("checkpoint: record '" + name + "' is missing");
  return it->second;
}

}  // namespace

void Checkpoint::put(const std::string& n, std::vector<double> v) { f64_[n] = std::move(v); }
void Checkpoint::put(const std::string& n, std::vector<std::int64_t> v) { i64_[n] = std::move(v); }
void Checkpoint::put(const std::string& n, std::vector<std::uint64_t> v) { u64_[n] = std::move(v); }
void Checkpoint::put(const std::string& n, std::vector<std::uint8_t> v) { u8_[n] = std::move(v); }

const std::vector<double>& Checkpoint::f64(const std::string& n) const { return find(f64_, n); }
const std::vector<std::int64_t>& Checkpoint::i64(const std::string& n) const {
  return find(i64_, n);
}
const std::vector<std::uint64_t>& Checkpoint::u64(const std::string& n) const {
  return find(u64_, n);
}
const std::vector<std::uint8_t>& Checkpoint::u8(const std::string& n) const { return find(u8_, n); }

double Checkpoint::scalar(const std::string& n) const {
  const auto& v = f64(n);
  if (v.size() != 1) throw std::runtime_error("checkpoint: record '" + n + "' is not a scalar");
  return v[0];
}

bool Checkpoint::has(const std::string& n) const {
  return f64_.count(n) || i64_.count(n) || u64_.count(n) || u8_.count(n);
}

std::vector<std::string> Checkpoint::names() const {
  std::vector<std::string> out;
  auto add = [&out](const auto& m) {
    for (const auto& kv : m) out.push_back(kv.first);
  };
  add(f64_), add(i64_), add(u64_), add(u8_);
  std::sort(out.begin(), out.end());
  return out;
}

template <class T>
const std::vector<T>& Checkpoint::get(const std::string& n) const {
  if constexpr (std::is_same_v<T, double>)
    return f64(n);
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return i64(n);
  else if constexpr (std::is_same_v<T, std::uint64_t>)
    return u64(n);
  else
    return u8(n);
}

template <class T>
T Checkpoint::value(const std::string& n) const {
  const auto& v = get<T>(n);
  if (v.size() != 1)
    throw std::runtime_error("checkpoint: record '" + n + "' is not a single value");
  return v[0];
}

template double Checkpoint::value<double>(const std::string&) const;
template std::int64_t Checkpoint::value<std::int64_t>(const std::string&) const;
template std::uint64_t Checkpoint::value<std::uint64_t>(const std::string&) const;

namespace {

// How one particle array is stored: its record element type and values per particle. Kinds are
// stored as u8, vectors flattened.
template <class T>
struct RecordOf {
  using type = T;
  static constexpr std::size_t width = 1;
};
template <>
struct RecordOf<Kind> {
  using type = std::uint8_t;
  static constexpr std::size_t width = 1;
};
template <int D>
struct RecordOf<Vec<D>> {
  using type = double;
  static constexpr std::size_t width = D;
};

template <class T>
std::vector<typename RecordOf<T>::type> to_record(const std::vector<T>& v) {
  if constexpr (std::is_same_v<T, Kind>) {
    std::vector<std::uint8_t> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = static_cast<std::uint8_t>(v[i]);
    return out;
  } else if constexpr (RecordOf<T>::width > 1) {
    constexpr std::size_t w = RecordOf<T>::width;
    std::vector<double> out(v.size() * w);
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t k = 0; k < w; ++k) out[i * w + k] = v[i][static_cast<int>(k)];
    return out;
  } else {
    return v;
  }
}

template <class T>
void from_record(const std::vector<typename RecordOf<T>::type>& r, std::vector<T>& v) {
  constexpr std::size_t w = RecordOf<T>::width;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if constexpr (std::is_same_v<T, Kind>)
      v[i] = static_cast<Kind>(r[i]);
    else if constexpr (w > 1)
      for (std::size_t k = 0; k < w; ++k) v[i][static_cast<int>(k)] = r[i * w + k];
    else
      v[i] = r[i];
  }
}

std::string level_prefix(int level) { return "level" + std::to_string(level) + "."; }

}  // namespace

template <int D>
void Checkpoint::put_particles(int level, const ParticleSet<D>& ps) {
  const std::string pre = level_prefix(level);
  ps.for_each_field([&](std::string_view name, const auto& v, FieldRole role) {
    if (role == FieldRole::persistent) put(pre + std::string(name), to_record(v));
  });
  if (!ps.keeps_mass) put(pre + "mass", ps.masses());  // the file holds one per particle
}

template <int D>
void Checkpoint::get_particles(int level, ParticleSet<D>& ps) const {
  const std::string pre = level_prefix(level);
  const std::size_t n = u64(pre + "id").size();
  ps = ParticleSet<D>{};
  ps.keeps_shift = has(pre + "shift");
  ps.keeps_mass = true;  // read per particle, then shared if uniform
  ps.resize(n);
  ps.for_each_field([&](std::string_view name, auto& v, FieldRole role) {
    if (role != FieldRole::persistent) return;
    using T = typename std::decay_t<decltype(v)>::value_type;
    const std::string record = pre + std::string(name);
    const auto& r = get<typename RecordOf<T>::type>(record);
    if (r.size() != n * RecordOf<T>::width) {
      throw std::runtime_error(
          fmt::format("checkpoint: {} has {} values for {} particles", record, r.size(), n));
    }
    from_record(r, v);
  });
  ps.share_mass_if_uniform();
}

template <int D>
void Checkpoint::put_vectors(const std::string& name, const std::vector<Vec<D>>& v) {
  put(name, to_record(v));
}

template <int D>
void Checkpoint::get_vectors(const std::string& name, std::size_t n, std::vector<Vec<D>>& v) const {
  if (!has(name)) return;
  const auto& r = f64(name);
  if (r.empty()) {
    v.clear();
    return;
  }
  if (r.size() != n * D)
    throw CheckpointError(fmt::format("{}: {} values for {} particles", name, r.size(), n));
  v.assign(n, Vec<D>{});
  from_record(r, v);
}

void Checkpoint::get_values(const std::string& name, std::size_t n, std::vector<double>& v) const {
  if (!has(name)) return;
  const auto& r = f64(name);
  if (!r.empty() && r.size() != n)
    throw CheckpointError(fmt::format("{}: {} values for {} particles", name, r.size(), n));
  v = r;
}

template void Checkpoint::put_vectors<2>(const std::string&, const std::vector<Vec<2>>&);
template void Checkpoint::put_vectors<3>(const std::string&, const std::vector<Vec<3>>&);
template void Checkpoint::get_vectors<2>(const std::string&, std::size_t,
                                         std::vector<Vec<2>>&) const;
template void Checkpoint::get_vectors<3>(const std::string&, std::size_t,
                                         std::vector<Vec<3>>&) const;
template void Checkpoint::put_particles<2>(int, const ParticleSet<2>&);
template void Checkpoint::put_particles<3>(int, const ParticleSet<3>&);
template void Checkpoint::get_particles<2>(int, ParticleSet<2>&) const;
template void Checkpoint::get_particles<3>(int, ParticleSet<3>&) const;

}  // namespace vrsph
