#include "visibility_balance.hpp"

#include "core/cancelled.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace arbor::pipeline {

namespace {

constexpr uint32_t kPreview = 64;
constexpr int kIterations = 8;
constexpr double kStepLimit = 6.0;   // a multiplier changes at most by this factor per iteration
constexpr double kScaleLimit = 200.0; // nor beyond this, either way, in all
constexpr double kSeen = 0.02;        // a pixel's opacity above which something is seen there
constexpr double kGrowth = 3.0;       // a free structure's share grows at most by this factor to fill the picture
constexpr double kContext = 0.5;      // a selection thins its context to no less than this part of its optical depth

struct Measure {
    std::vector<double> visibility; // summed over the views
    double mean_alpha = 0.0;        // over the pixels where something is seen
};

Measure measure(const TransferFunctions &tf, const std::vector<arbor_camera> &views, const PreviewFn &preview)
{
    Measure m;
    m.visibility.assign(tf.branch_count(), 0.0);
    double seen = 0, alpha = 0;
    for (const arbor_camera &c : views) {
        const RenderedImage im = preview(tf, c, kPreview);
        if (im.label_visibility.size() != tf.branch_count())
            throw std::invalid_argument("the renderer does not measure visibility, so there is none to balance");
        for (uint32_t b = 0; b < tf.branch_count(); ++b)
            m.visibility[b] += im.label_visibility[b];
        for (std::size_t p = 3; p < im.rgba.size(); p += 4)
            if (im.rgba[p] > kSeen) {
                seen += 1;
                alpha += im.rgba[p];
            }
    }
    m.mean_alpha = seen > 0 ? alpha / seen : 0.0;
    return m;
}

std::vector<double> shares_of(const std::vector<double> &v)
{
    const double total = std::accumulate(v.begin(), v.end(), 0.0);
    std::vector<double> s(v.size(), 0.0);
    if (total > 0)
        for (std::size_t b = 0; b < v.size(); ++b)
            s[b] = v[b] / total;
    return s;
}

// The shares closest to `s` within the bounds: the root and thin sheets
// capped, every other branch floored, the rest scaled to keep their ratios
// and the sum 1.
std::vector<double> targets_for(const std::vector<double> &s, const std::vector<double> &start,
                                const BranchLayout &layout, const BalanceTargets &t)
{
    const std::vector<bool> &sheet = layout.sheet, &context = layout.context;
    const std::size_t n = s.size();
    std::vector<double> out(s);
    if (n == 1)
        return out;
    const double floor = std::min(t.floor, 0.9 / static_cast<double>(n - 1));
    std::vector<bool> fixed(n, false), capped(n, false);
    for (int round = 0; round < 8; ++round) {
        bool changed = false;
        if (!fixed[0] && (out[0] > t.root_cap || out[0] < t.root_floor)) {
            out[0] = std::clamp(out[0], t.root_floor, t.root_cap);
            fixed[0] = changed = true;
        }
        for (std::size_t b = 1; b < n; ++b) {
            if (b < context.size() && context[b] && static_cast<int32_t>(b) != t.focus) {
                if (!fixed[b] && out[b] > t.context_cap) {
                    out[b] = t.context_cap;
                    fixed[b] = changed = true;
                }
                continue;
            }
            const double least = static_cast<int32_t>(b) == t.focus ? std::max(floor, t.focus_floor) : floor;
            if (!fixed[b] && out[b] < least) {
                out[b] = least;
                fixed[b] = changed = true;
            } else if (!fixed[b] && b < sheet.size() && sheet[b] && out[b] > t.sheet_cap) {
                out[b] = t.sheet_cap;
                fixed[b] = capped[b] = changed = true;
            }
        }
        double fixed_sum = 0, free_sum = 0;
        for (std::size_t b = 0; b < n; ++b)
            (fixed[b] ? fixed_sum : free_sum) += out[b];
        if (free_sum > 0)
            for (std::size_t b = 0; b < n; ++b)
                if (!fixed[b])
                    out[b] *= (1.0 - fixed_sum) / free_sum;
        // What the caps give up is not all forced onto the few structures
        // left free: none grows past kGrowth times its share before the
        // balance (or the floor).  With the root, the sheets and the context
        // at their caps, the one left on the CT head (its nasal cavity) took
        // a third of the picture.
        for (std::size_t b = 1; b < n; ++b)
            if (!fixed[b] && static_cast<int32_t>(b) != t.focus && b < start.size() &&
                out[b] > kGrowth * std::max(start[b], floor)) {
                out[b] = kGrowth * std::max(start[b], floor);
                fixed[b] = changed = true;
            }
        if (!changed)
            break;
    }
    // What is still left over goes back to the sheets held at their cap (the
    // CT head's skull), in proportion: the layers one sees through are the
    // anatomy, where a structure grown many times over is not.
    double sum = 0, sheets = 0;
    for (std::size_t b = 0; b < n; ++b) {
        sum += out[b];
        sheets += capped[b] ? out[b] : 0.0;
    }
    if (sum < 1.0 && sheets > 0)
        for (std::size_t b = 0; b < n; ++b)
            if (capped[b])
                out[b] *= 1.0 + (1.0 - sum) / sheets;
    return out;
}

// Iterates from the multipliers `start`, none of which goes below its
// `least`.
BalanceResult iterate(const TransferFunctions &tf, const BranchLayout &layout, const std::vector<arbor_camera> &views,
                      const PreviewFn &preview, const BalanceTargets &targets, std::vector<double> start,
                      const std::vector<double> &least, std::stop_token stop)
{
    const std::vector<int32_t> &parent = layout.parent;
    const std::vector<double> &voxels = layout.voxels;
    const std::size_t n = tf.branch_count();
    BalanceResult r;
    r.scale = std::move(start);
    std::unique_ptr<TransferFunctions> current = tf.with_optical_depth(r.scale);
    Measure m = measure(*current, views, preview);
    r.shares_before = shares_of(m.visibility);
    std::vector<double> shares = r.shares_before;
    std::vector<bool> peeled(n, false); // once peeled, never made denser for the picture's sake
    for (int it = 0; it < kIterations; ++it) {
        throw_if_stopped(stop);
        const std::vector<double> want = targets_for(shares, r.shares_before, layout, targets);
        const auto context = [&](std::size_t b) {
            return b < layout.context.size() && layout.context[b] && static_cast<int32_t>(b) != targets.focus;
        };
        // Opacity for the picture as a whole: denser everywhere when the
        // content is too faint to read as surfaces (never thinner).
        const double global =
            m.mean_alpha > 0 && m.mean_alpha < targets.coverage
                ? std::clamp(std::log(1 - targets.coverage) / std::log(1 - m.mean_alpha), 1.0, kStepLimit)
                : 1.0;
        bool done = global < 1.05;
        std::vector<double> step(n, 1.0);
        for (std::size_t b = 0; b < n; ++b) {
            if (shares[b] > 0)
                step[b] = std::pow(want[b] / shares[b], 0.9);
            else if (b != 0 && !context(b))
                step[b] = kStepLimit; // unseen: denser until it shows
            done = done && std::fabs(step[b] - 1.0) < 0.1;
        }
        // Hidden inside others: peel the ancestors of a structure that is
        // still short of its floor though already many times denser.
        std::vector<double> peel(n, 1.0);
        const double structures = std::accumulate(voxels.begin() + 1, voxels.end(), 0.0);
        // The selected structure's ancestors are peeled as soon as it is
        // short of its floor: it is what the person wants to see.
        for (std::size_t b = 1; b < n; ++b)
            if (!context(b) &&
                (static_cast<int32_t>(b) == targets.focus
                     ? shares[b] < 0.9 * want[b]
                     : shares[b] < 0.5 * want[b] && r.scale[b] * step[b] > 8.0 * r.scale[0]) &&
                voxels[b] >= 1e-4 * structures)
                for (int32_t a = parent[b]; a > 0; a = parent[static_cast<std::size_t>(a)]) { // the root keeps its floor
                    peel[static_cast<std::size_t>(a)] = std::min(peel[static_cast<std::size_t>(a)], 0.6);
                    peeled[static_cast<std::size_t>(a)] = true;
                }
        // The root follows its share alone: made denser with the rest it
        // would take the picture back.
        // A peeled branch is not made denser with the rest, which would undo
        // it, nor is context, which is to stay faint.
        for (std::size_t b = 0; b < n; ++b) {
            r.scale[b] = std::clamp(
                r.scale[b] *
                    std::clamp(step[b] * peel[b] * (b == 0 || peeled[b] || context(b) || shares[b] > want[b] ? 1.0 : global),
                               1 / kStepLimit, kStepLimit),
                1 / kScaleLimit, kScaleLimit);
            r.scale[b] = std::max(r.scale[b], least[b]);
        }
        if (done)
            break;
        current = tf.with_optical_depth(r.scale);
        m = measure(*current, views, preview);
        shares = shares_of(m.visibility);
        r.iterations = it + 1;
    }
    r.shares_after = shares;
    return r;
}

} // namespace

BalanceResult balance_visibility(const TransferFunctions &tf, const BranchLayout &layout, const Geometry &geometry,
                                 const PreviewFn &preview, const BalanceTargets &targets, std::stop_token stop)
{
    std::vector<arbor_camera> views;
    for (const auto &[azimuth, elevation] : {std::pair{0.0, 0.0}, {90.0, 0.0}, {0.0, 80.0}}) {
        Orbit o;
        o.azimuth = azimuth;
        o.elevation = elevation;
        views.push_back(orbit_camera(geometry, o));
    }
    const std::size_t n = tf.branch_count();
    const std::vector<double> ones(n, 1.0), none(n, 0.0);
    if (targets.focus <= 0 || static_cast<std::size_t>(targets.focus) >= n)
        return iterate(tf, layout, views, preview, targets, ones, none, stop);
    // A selected structure: first the picture without it, then the
    // selection from there.  The others but its ancestors (the root, the
    // body, among them) are its context: thinned to make room, but to no
    // less than half their optical depth in that picture, so that it does
    // not go dark around the selection (a jaw in front of a face gains
    // nothing from a fainter face, however small its share).
    BalanceTargets plain = targets;
    plain.focus = -1;
    const BalanceResult unselected = iterate(tf, layout, views, preview, plain, ones, none, stop);
    std::vector<double> least(n, 0.0);
    for (std::size_t b = 0; b < n; ++b)
        least[b] = kContext * unselected.scale[b];
    for (int32_t a = targets.focus; a >= 0; a = layout.parent[static_cast<std::size_t>(a)])
        least[static_cast<std::size_t>(a)] = 0.0;
    BalanceResult r = iterate(tf, layout, views, preview, targets, unselected.scale, least, stop);
    r.shares_before = unselected.shares_before;
    r.iterations += unselected.iterations;
    return r;
}

} // namespace arbor::pipeline
