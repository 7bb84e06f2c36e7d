// anatomical_space.hpp - named world frames ("right-anterior-superior",
// "RAS", "left-posterior-superior"...) and how their coordinates become the
// LPS coordinates of the SDK (volume.h).
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace arbor::importers {

// LPS coordinate axis[i] is sign[i] times coordinate i of the named frame.
struct SpaceToLps {
    std::array<int, 3> axis{0, 1, 2};
    std::array<double, 3> sign{1.0, 1.0, 1.0};

    std::array<double, 3> apply(const std::array<double, 3> &v) const
    {
        std::array<double, 3> out{};
        for (int i = 0; i < 3; ++i)
            out[static_cast<std::size_t>(axis[i])] = sign[i] * v[i];
        return out;
    }
};

// The frame of a three-letter code (each letter one of L/R, P/A, S/I, every
// pair once: "RAS", "LPS", "RPI"...) or of the hyphenated long form
// ("right-anterior-superior"), case-insensitive.  Frames without anatomical
// meaning ("scanner-xyz", "3D-right-handed", "3D-left-handed") are taken as
// LPS.  nullopt for anything else.
std::optional<SpaceToLps> space_to_lps(std::string_view name);

} // namespace arbor::importers
