// harmonic_template.hpp - the hue templates of Cohen-Or et al. 2006, "Color
// harmonization": sets of sectors of the hue wheel (degrees, 0 = red, as in
// HSV) from which harmonious hues are drawn, optionally rotated.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace arbor::tf {

// The arc of hues within width/2 degrees of centre.
struct HueSector {
    double centre, width;
};

class HarmonicTemplate {
public:
    // "X" or "X:30" (rotated by 30 degrees), X one of i V L I T Y X N; "full"
    // is another name for N, the whole wheel.  Names are case-sensitive (i and
    // I differ).  Throws std::invalid_argument, naming the valid templates,
    // for an unknown name or a rotation that is not a finite number.
    static HarmonicTemplate parse(const std::string &spec);

    // Rotated, centres in [0, 360).
    const std::vector<HueSector> &sectors() const;
    // The template's letter ("N" for "full").
    std::string name() const;
    // In degrees, reduced to [0, 360).
    double rotation() const;

    // Whether hue lies in one of the sectors, edges included, to within
    // tolerance_degrees; hues wrap modulo 360.
    bool contains(double hue, double tolerance_degrees = 1e-9) const;

    // The hue at fraction t of the way along the sectors' arcs laid end to
    // end (in order, each from centre - width/2 to centre + width/2), in
    // [0, 360).  t wraps into [0, 1).
    double hue_at(double t) const;

    // n hues spread evenly along the arcs: hue_at((k + 0.5) / n), k = 0..n-1.
    std::vector<double> spread(std::size_t n) const;

private:
    HarmonicTemplate(std::string name, double rotation, std::vector<HueSector> sectors);

    std::string name_;
    double rotation_;
    std::vector<HueSector> sectors_;
};

} // namespace arbor::tf
