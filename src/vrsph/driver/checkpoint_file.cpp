// The checkpoint file format (see checkpoint.hpp): header, then records, each closed by the
// FNV-1a 64 checksum of its bytes. The reader knows the file size, so a length or count that runs
// past the end is reported as such instead of being allocated, and a file cut at a record
// boundary is told apart from a whole one by the record count of the header.
#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <type_traits>

#include "vrsph/driver/checkpoint.hpp"
#include "vrsph/driver/fnv_hash.hpp"
#include "vrsph/output/atomic_file.hpp"

namespace vrsph {
namespace {

constexpr char kMagic[8] = {'V', 'R', 'S', 'P', 'H', 'C', 'K', '\0'};
constexpr std::uint32_t kMaxNameLength = 4096;
enum class RecordType : std::uint8_t { f64 = 1, i64 = 2, u64 = 3, u8 = 4 };

template <class T>
void write_pod(std::ostream& os, const T& v) {
  os.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

// Writes the records of one type, each followed by the checksum of its bytes.
template <class T>
void write_records(std::ostream& os, const std::map<std::string, std::vector<T>>& m,
                   RecordType type) {
  for (const auto& [name, v] : m) {
    const auto len = static_cast<std::uint32_t>(name.size());
    const auto count = static_cast<std::uint64_t>(v.size());
    const std::size_t bytes = v.size() * sizeof(T);
    Fnv1a64 h;
    h.add(&len, sizeof(len)).add(name).add(&type, sizeof(type)).add(&count, sizeof(count));
    h.add(v.data(), bytes);
    write_pod(os, len);
    os.write(name.data(), static_cast<std::streamsize>(name.size()));
    write_pod(os, type);
    write_pod(os, count);
    os.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(bytes));
    write_pod(os, h.value());
  }
}

// Reads a checkpoint file front to back, knowing how many bytes are left; every failure is a
// CheckpointError naming the file.
class FileReader {
 public:
  FileReader(std::istream& is, std::uint64_t size, const std::filesystem::path& path)
      : is_(is), left_(size), path_(path) {}

  // Reads n bytes; `what` names the part for the message when the file ends first.
  void read(void* dst, std::size_t n, const std::string& what) {
    if (n > left_) fail(fmt::format("the checkpoint is truncated ({} is cut short)", what));
    is_.read(static_cast<char*>(dst), static_cast<std::streamsize>(n));
    if (!is_) fail(fmt::format("cannot read {} of the checkpoint", what));
    left_ -= n;
  }
  template <class T>
  T pod(const std::string& what) {
    T v{};
    read(&v, sizeof(T), what);
    return v;
  }
  std::uint64_t left() const { return left_; }

  [[noreturn]] void fail(const std::string& reason) const {
    throw CheckpointError(fmt::format("{}: {}", path_.string(), reason));
  }

 private:
  std::istream& is_;
  std::uint64_t left_;
  const std::filesystem::path& path_;
};

// The values of one record; `h` has the record's header bytes and takes its data.
template <class T>
std::vector<T> read_values(FileReader& in, std::uint64_t count, const std::string& name,
                           Fnv1a64& h) {
  if (count > in.left() / sizeof(T)) {
    in.fail(
        fmt::format("checkpoint record '{}' ({} values) runs past the end of the file: the "
                    "checkpoint is truncated or damaged",
                    name, count));
  }
  std::vector<T> v(count);
  in.read(v.data(), count * sizeof(T), fmt::format("record '{}'", name));
  h.add(v.data(), count * sizeof(T));
  return v;
}

// A record name as read, fit for a one-line message (a damaged name may hold any byte).
std::string printable(std::string name) {
  for (char& ch : name) {
    if (static_cast<unsigned char>(ch) < 32 || static_cast<unsigned char>(ch) > 126) ch = '?';
  }
  return name;
}

// Reads record r (0-based) of n into c; throws on a short, impossible or damaged record.
void read_record(FileReader& in, std::uint64_t r, std::uint64_t n, Checkpoint& c) {
  const std::string where = fmt::format("record {} of {}", r + 1, n);
  const auto len = in.pod<std::uint32_t>(where);
  if (len > kMaxNameLength) {
    in.fail(fmt::format("checkpoint {} has an impossible name length {}: the file is damaged",
                        where, len));
  }
  std::string raw(len, '\0');
  in.read(raw.data(), len, where);
  Fnv1a64 h;
  h.add(&len, sizeof(len)).add(raw);
  const std::string name = printable(std::move(raw));
  const auto type = in.pod<RecordType>(fmt::format("record '{}'", name));
  const auto count = in.pod<std::uint64_t>(fmt::format("record '{}'", name));
  h.add(&type, sizeof(type)).add(&count, sizeof(count));
  switch (type) {
    case RecordType::f64:
      c.put(name, read_values<double>(in, count, name, h));
      break;
    case RecordType::i64:
      c.put(name, read_values<std::int64_t>(in, count, name, h));
      break;
    case RecordType::u64:
      c.put(name, read_values<std::uint64_t>(in, count, name, h));
      break;
    case RecordType::u8:
      c.put(name, read_values<std::uint8_t>(in, count, name, h));
      break;
    default:
      in.fail(fmt::format("checkpoint record '{}' has an unknown type {}: the file is damaged",
                          name, static_cast<int>(type)));
  }
  if (in.pod<std::uint64_t>(fmt::format("the checksum of record '{}'", name)) != h.value())
    in.fail(fmt::format("checkpoint record '{}' fails its checksum: the file is damaged", name));
}

}  // namespace

void Checkpoint::save(const std::filesystem::path& path) const {
  AtomicWriter w(path);
  std::ostream& os = w.stream();
  os.write(kMagic, sizeof(kMagic));
  write_pod(os, kCheckpointVersion);
  write_pod(os, static_cast<std::uint64_t>(f64_.size() + i64_.size() + u64_.size() + u8_.size()));
  write_records(os, f64_, RecordType::f64);
  write_records(os, i64_, RecordType::i64);
  write_records(os, u64_, RecordType::u64);
  write_records(os, u8_, RecordType::u8);
  w.commit();
}

Checkpoint Checkpoint::load(const std::filesystem::path& path) {
  std::ifstream is(path, std::ios::binary);
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (!is || ec) throw std::runtime_error(path.string() + ": cannot open checkpoint");
  FileReader in(is, size, path);
  char magic[8];
  if (size < sizeof(magic)) in.fail("not a vrsph checkpoint (too short)");
  in.read(magic, sizeof(magic), "the header");
  if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) in.fail("not a vrsph checkpoint");
  const auto version = in.pod<std::uint32_t>("the header");
  if (version != kCheckpointVersion) {
    in.fail(fmt::format(
        "checkpoint format version {} is not supported (this build reads version {}): rerun the "
        "case from the start",
        version, kCheckpointVersion));
  }
  const auto n = in.pod<std::uint64_t>("the header");
  Checkpoint c;
  for (std::uint64_t r = 0; r < n; ++r) read_record(in, r, n, c);
  if (in.left() != 0) {
    in.fail(
        fmt::format("{} bytes follow the last of the checkpoint's {} records: the file is damaged",
                    in.left(), n));
  }
  return c;
}

}  // namespace vrsph
