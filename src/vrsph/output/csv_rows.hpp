// Helpers of the time-series CSV files that a run appends to (series.csv, probe_<name>.csv): split
// a line, append a row durably, and cut a file back to the rows of a checkpoint's time on resume.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vrsph {

// The fields of a CSV line (no quoting: the run's files hold numbers and names only); an empty
// field counts, so "a,,b" gives three.
std::vector<std::string> split_fields(std::string_view line, char sep = ',');

// Appends `text` with one write() and fsyncs; throws std::runtime_error with the path and errno
// text on failure.
void append_durably(const std::filesystem::path& path, std::string_view text);

// The complete lines of `text` (a trailing partial line dropped): lines[0] the header.
std::vector<std::string> complete_lines(const std::string& text);

// True if `line` has `n_columns` fields and its field `t_column` parses as a number <= t_max.
bool row_up_to(const std::string& line, std::size_t n_columns, std::size_t t_column, double t_max);

}  // namespace vrsph
