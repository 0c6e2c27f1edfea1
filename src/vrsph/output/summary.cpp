// summary.json writer and JSON reader (see summary.hpp).
#include "vrsph/output/summary.hpp"

#include <stdexcept>

#include "vrsph/output/atomic_file.hpp"

namespace vrsph {

void write_summary_json(const std::filesystem::path& path, const nlohmann::json& summary) {
  write_file_atomic(path, summary.dump(2) + "\n");
}

nlohmann::json read_json_file(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

}  // namespace vrsph
