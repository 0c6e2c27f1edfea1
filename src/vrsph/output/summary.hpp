// summary.json (written at the end of a run; the caller builds the JSON, see docs/outputs.md) and
// reading a JSON file back.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

namespace vrsph {

// Writes `summary` with a 2-space indent and a final newline, atomically.
void write_summary_json(const std::filesystem::path& path, const nlohmann::json& summary);

// Reads a JSON file (e.g. a previous summary.json when resuming); throws std::runtime_error with
// the path on I/O or parse errors.
nlohmann::json read_json_file(const std::filesystem::path& path);

}  // namespace vrsph
