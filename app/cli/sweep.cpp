#include "sweep.hpp"

#include "usage_error.hpp"

#include <cctype>
#include <stdexcept>

namespace arbor::cli {

namespace {

std::string file_safe(const std::string &s)
{
    std::string out;
    for (const char c : s)
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-')
            out += c;
    return out;
}

struct Axis {
    const std::vector<std::string> *values;
    std::optional<std::string> SweepPoint::*member;
    const char *prefix;  // in file names ("k" for keep 16: k16)
    const char *caption; // "keep "
};

} // namespace

std::vector<SweepPoint> sweep_points(const SweepAxes &axes)
{
    const Axis order[] = {{&axes.simplifiers, &SweepPoint::simplifier, "", ""},
                          {&axes.keeps, &SweepPoint::keep, "k", "keep "},
                          {&axes.flow_rates, &SweepPoint::flow_rate, "q", "Q "},
                          {&axes.shapes, &SweepPoint::shape, "", ""},
                          {&axes.hues, &SweepPoint::hues, "", "hues "}};
    std::vector<SweepPoint> points(1);
    for (const Axis &axis : order) {
        if (axis.values->empty())
            continue;
        const bool swept = axis.values->size() > 1;
        std::vector<SweepPoint> next;
        for (const SweepPoint &p : points)
            for (const std::string &v : *axis.values) {
                SweepPoint q = p;
                q.*axis.member = v;
                if (swept) {
                    q.name += (q.name.empty() ? "" : "-") + std::string(axis.prefix) + file_safe(v);
                    q.caption += (q.caption.empty() ? "" : ", ") + std::string(axis.caption) + v;
                }
                next.push_back(std::move(q));
            }
        points = std::move(next);
    }
    return points;
}

void refuse_lists(const SweepAxes &axes, const std::string &command)
{
    const std::pair<const char *, const std::vector<std::string> *> flags[] = {
        {"--simplifier", &axes.simplifiers}, {"--keep", &axes.keeps}, {"--flow-rate", &axes.flow_rates},
        {"--shape", &axes.shapes}, {"--hues", &axes.hues}};
    for (const auto &[flag, values] : flags)
        if (values->size() > 1)
            throw UsageError(std::string(flag) + " takes one value in `arbor " + command +
                             "` (lists are sweeps of `arbor run`)");
}

} // namespace arbor::cli
