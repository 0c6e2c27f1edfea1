// The resolved case as flat dotted keys ("resolution.dp", "fluid_block.0.max",
// "numerics.viscosity.model"), the same paths --set takes, each with its value as TOML text.
// A checkpoint stores the physical ones, so that a resume with a changed case is refused naming
// the key that changed.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "vrsph/setup/case_spec.hpp"

namespace vrsph {

// Every key of case_to_toml(spec), tables and arrays of tables flattened, arrays of values kept
// whole ("[0.0, -9.81]"). A key the resolved case leaves unset (eos.sound_speed) is absent.
std::map<std::string, std::string> resolved_case_keys(const CaseSpec& spec);

// Whether a key describes the physical case: every key except case.end_time and those under
// output (what a resumed run may change).
bool is_physical_key(std::string_view key);

// The physical keys of the resolved case, as "key = value" lines in key order.
std::string physical_case_text(const CaseSpec& spec);

// Parses the text of physical_case_text back into keys and values.
std::map<std::string, std::string> parse_case_text(std::string_view text);

// The keys whose values differ between two key maps (absent on one side counts), as
// "key = VALUE_A (B: VALUE_B)" phrases joined by "; ", at most `max_keys` of them and then
// "and N more". Empty when they are equal.
std::string describe_key_changes(const std::map<std::string, std::string>& a,
                                 const std::map<std::string, std::string>& b,
                                 std::string_view b_label, std::size_t max_keys = 4);

}  // namespace vrsph
