// harmonic_template.cpp - the hue templates of Cohen-Or et al. 2006 (their
// sector widths, as fractions of the wheel, are 5%, 26% and 22% of 360 and
// a half wheel), parsing "name[:rotation]" and walking the sectors' arcs.
#include "harmonic_template.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace arbor::tf {

namespace {

struct TemplateShape {
    const char *name;
    std::vector<HueSector> sectors; // unrotated
};

const std::vector<TemplateShape> &shapes()
{
    static const std::vector<TemplateShape> kShapes = {
        {"i", {{0.0, 18.0}}},
        {"V", {{0.0, 93.6}}},
        {"L", {{0.0, 18.0}, {90.0, 79.2}}},
        {"I", {{0.0, 18.0}, {180.0, 18.0}}},
        {"T", {{0.0, 180.0}}},
        {"Y", {{0.0, 93.6}, {180.0, 18.0}}},
        {"X", {{0.0, 93.6}, {180.0, 93.6}}},
        {"N", {{0.0, 360.0}}},
    };
    return kShapes;
}

constexpr const char *kValidSpecs =
    "valid templates: i, V, L, I, T, Y, X, N (or \"full\"), optionally followed by a rotation "
    "in degrees, e.g. \"X:30\"";

double wrap_degrees(double hue)
{
    double h = std::fmod(hue, 360.0);
    if (h < 0.0)
        h += 360.0;
    // fmod of a tiny negative number plus 360 rounds to 360 itself.
    return h >= 360.0 ? 0.0 : h;
}

std::string trimmed(const std::string &text)
{
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos)
        return {};
    const auto last = text.find_last_not_of(" \t");
    return text.substr(first, last - first + 1);
}

double parse_rotation(const std::string &spec, const std::string &text)
{
    const char *begin = text.data();
    const char *end = text.data() + text.size();
    // from_chars takes no leading '+', which a user writing "X:+30" means.
    if (end - begin >= 2 && begin[0] == '+' && begin[1] != '-')
        ++begin;
    double value = 0.0;
    const auto [stop, error] = std::from_chars(begin, end, value);
    if (text.empty() || error != std::errc() || stop != end || !std::isfinite(value))
        throw std::invalid_argument("hue template \"" + spec + "\": rotation \"" + text +
                                    "\" is not a finite number of degrees; " + kValidSpecs);
    return value;
}

} // namespace

HarmonicTemplate::HarmonicTemplate(std::string name, double rotation, std::vector<HueSector> sectors)
    : name_(std::move(name)), rotation_(rotation), sectors_(std::move(sectors))
{
}

HarmonicTemplate HarmonicTemplate::parse(const std::string &spec)
{
    const auto colon = spec.find(':');
    std::string name = trimmed(spec.substr(0, colon));
    const double rotation =
        colon == std::string::npos ? 0.0 : wrap_degrees(parse_rotation(spec, trimmed(spec.substr(colon + 1))));
    if (name == "full")
        name = "N";
    for (const TemplateShape &shape : shapes()) {
        if (name != shape.name)
            continue;
        std::vector<HueSector> sectors = shape.sectors;
        for (HueSector &sector : sectors)
            sector.centre = wrap_degrees(sector.centre + rotation);
        return HarmonicTemplate(name, rotation, std::move(sectors));
    }
    throw std::invalid_argument("unknown hue template \"" + spec + "\"; " + kValidSpecs);
}

const std::vector<HueSector> &HarmonicTemplate::sectors() const
{
    return sectors_;
}

std::string HarmonicTemplate::name() const
{
    return name_;
}

double HarmonicTemplate::rotation() const
{
    return rotation_;
}

bool HarmonicTemplate::contains(double hue, double tolerance_degrees) const
{
    for (const HueSector &sector : sectors_) {
        if (sector.width >= 360.0)
            return true;
        const double apart = wrap_degrees(hue - sector.centre);
        const double distance = std::min(apart, 360.0 - apart);
        if (distance <= 0.5 * sector.width + tolerance_degrees)
            return true;
    }
    return false;
}

double HarmonicTemplate::hue_at(double t) const
{
    double total = 0.0;
    for (const HueSector &sector : sectors_)
        total += sector.width;
    double along = (t - std::floor(t)) * total;
    for (std::size_t i = 0; i < sectors_.size(); ++i) {
        const HueSector &sector = sectors_[i];
        // Rounding can leave `along` a hair past the last arc's end.
        if (along < sector.width || i + 1 == sectors_.size())
            return wrap_degrees(sector.centre - 0.5 * sector.width + std::min(along, sector.width));
        along -= sector.width;
    }
    return 0.0; // no sectors: unreachable, every template has one
}

std::vector<double> HarmonicTemplate::spread(std::size_t n) const
{
    std::vector<double> hues;
    hues.reserve(n);
    for (std::size_t k = 0; k < n; ++k)
        hues.push_back(hue_at((static_cast<double>(k) + 0.5) / static_cast<double>(n)));
    return hues;
}

} // namespace arbor::tf
