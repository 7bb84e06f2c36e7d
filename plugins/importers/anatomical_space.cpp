// anatomical_space.cpp - see anatomical_space.hpp.
#include "anatomical_space.hpp"

#include "text_scan.hpp"

#include <string>
#include <vector>

namespace arbor::importers {

namespace {

// LPS axis and sign of a direction name: left = +x, posterior = +y,
// superior = +z; their opposites are negative.
bool direction_of(std::string_view word, int &axis, double &sign)
{
    struct Name {
        const char *letter;
        const char *word;
        int axis;
        double sign;
    };
    static constexpr Name kNames[] = {{"l", "left", 0, 1.0},      {"r", "right", 0, -1.0},
                                      {"p", "posterior", 1, 1.0}, {"a", "anterior", 1, -1.0},
                                      {"s", "superior", 2, 1.0},  {"i", "inferior", 2, -1.0}};
    for (const Name &n : kNames)
        if (word == n.letter || word == n.word) {
            axis = n.axis;
            sign = n.sign;
            return true;
        }
    return false;
}

} // namespace

std::optional<SpaceToLps> space_to_lps(std::string_view name)
{
    const std::string text = lower(trim(name));
    if (text == "scanner-xyz" || text == "3d-right-handed" || text == "3d-left-handed")
        return SpaceToLps{};
    std::vector<std::string> parts;
    if (text.find('-') != std::string::npos) {
        std::size_t start = 0;
        while (start <= text.size()) {
            const std::size_t dash = text.find('-', start);
            const std::size_t end = dash == std::string::npos ? text.size() : dash;
            parts.push_back(text.substr(start, end - start));
            start = end + 1;
        }
    } else if (text.size() == 3) {
        for (char c : text)
            parts.emplace_back(1, c);
    }
    if (parts.size() != 3)
        return std::nullopt;
    SpaceToLps frame;
    bool used[3] = {false, false, false};
    for (int i = 0; i < 3; ++i) {
        int axis = 0;
        double sign = 1.0;
        if (!direction_of(parts[static_cast<std::size_t>(i)], axis, sign) || used[axis])
            return std::nullopt;
        used[axis] = true;
        frame.axis[static_cast<std::size_t>(i)] = axis;
        frame.sign[static_cast<std::size_t>(i)] = sign;
    }
    return frame;
}

} // namespace arbor::importers
