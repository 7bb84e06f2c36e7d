// number_text.cpp - see number_text.hpp.  std::from_chars does the work: it
// reports overflow instead of saturating or wrapping, and never allocates.
#include "number_text.hpp"

#include "text_scan.hpp"

#include <charconv>
#include <system_error>

namespace arbor::importers {

std::optional<int64_t> parse_integer(std::string_view text)
{
    if (!text.empty() && text.front() == '+')
        text.remove_prefix(1);
    if (text.empty() || text.front() == '+')
        return std::nullopt;
    int64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
        return std::nullopt;
    return value;
}

std::optional<double> parse_real(std::string_view text)
{
    if (!text.empty() && text.front() == '+')
        text.remove_prefix(1);
    if (text.empty() || text.front() == '+')
        return std::nullopt;
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
        return std::nullopt;
    return value;
}

std::optional<std::vector<double>> parse_reals(std::string_view text)
{
    std::vector<double> values;
    for (std::string_view word : split_words(text)) {
        const std::optional<double> v = parse_real(word);
        if (!v)
            return std::nullopt;
        values.push_back(*v);
    }
    return values;
}

} // namespace arbor::importers
