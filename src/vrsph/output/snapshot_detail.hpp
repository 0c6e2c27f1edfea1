// Internal helpers shared by the snapshot writers (not part of the output API).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "vrsph/output/snapshot.hpp"

namespace vrsph {

// Escapes & < > " ' for use in XML attribute values, and the reverse.
std::string xml_escape(std::string_view s);
std::string xml_unescape(std::string_view s);

// Throws std::invalid_argument unless every extra has a name, components >= 1 and
// n * components values and `level` is empty or has n entries.
void check_snapshot_inputs(std::size_t n, std::span<const ExtraField> extras,
                           std::span<const std::uint8_t> level);

}  // namespace vrsph
