// number_text.hpp - numbers written as text, parsed strictly: the whole text
// must be the number, and integers that do not fit in 64 bits are refused
// instead of wrapping ("99999999999999999999" is not a size).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace arbor::importers {

// Decimal integer with an optional sign; nullopt for anything else or when
// the value lies outside int64_t.
std::optional<int64_t> parse_integer(std::string_view text);

// Decimal or scientific real with an optional sign; "nan" and "inf" are
// accepted (callers decide whether they make sense).  nullopt otherwise.
std::optional<double> parse_real(std::string_view text);

// Every word of `text` as a real; nullopt when one is not a number.
std::optional<std::vector<double>> parse_reals(std::string_view text);

} // namespace arbor::importers
