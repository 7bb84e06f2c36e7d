#include "body_region.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace arbor {

namespace {

constexpr double kCell = 2.0;    // mm, the coarse grid's cells (or the scan's spacing where coarser)
constexpr double kErosion = 4.0; // mm each way

using Mask = std::vector<uint8_t>;

struct Grid {
    std::array<int64_t, 3> n;
    std::size_t at(int64_t i, int64_t j, int64_t k) const { return static_cast<std::size_t>(i + n[0] * (j + n[1] * k)); }
    std::size_t size() const { return static_cast<std::size_t>(n[0] * n[1] * n[2]); }
};

// Along `axis`, every cell within `w` cells of a cell whose value is not
// `keep` takes that value: erosion of the 1s (keep 1) or dilation (keep 0).
void box_pass(Mask &m, const Grid &g, int axis, int64_t w, uint8_t keep)
{
    if (w <= 0)
        return;
    const int64_t len = g.n[static_cast<std::size_t>(axis)];
    const int64_t a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2; // the other two axes
    std::vector<int64_t> last(static_cast<std::size_t>(len));
    std::vector<uint8_t> line(static_cast<std::size_t>(len));
    for (int64_t v = 0; v < g.n[static_cast<std::size_t>(b)]; ++v)
        for (int64_t u = 0; u < g.n[static_cast<std::size_t>(a)]; ++u) {
            const auto cell = [&](int64_t t) {
                int64_t c[3];
                c[axis] = t, c[a] = u, c[b] = v;
                return g.at(c[0], c[1], c[2]);
            };
            for (int64_t t = 0; t < len; ++t)
                line[static_cast<std::size_t>(t)] = m[cell(t)];
            // Distance to the nearest other value, forwards and back.
            int64_t since = w + 1;
            for (int64_t t = 0; t < len; ++t) {
                since = line[static_cast<std::size_t>(t)] == keep ? since + 1 : 0;
                last[static_cast<std::size_t>(t)] = since;
            }
            since = w + 1;
            for (int64_t t = len; t-- > 0;) {
                since = line[static_cast<std::size_t>(t)] == keep ? since + 1 : 0;
                if (std::min(since, last[static_cast<std::size_t>(t)]) <= w)
                    m[cell(t)] = static_cast<uint8_t>(1 - keep);
            }
        }
}

// The largest 6-connected component of the 1s, the rest 0.
void keep_largest(Mask &m, const Grid &g)
{
    std::vector<int32_t> component(m.size(), -1);
    std::vector<std::size_t> sizes;
    std::deque<std::size_t> queue;
    const int64_t step[3] = {1, g.n[0], g.n[0] * g.n[1]};
    for (std::size_t s = 0; s < m.size(); ++s) {
        if (!m[s] || component[s] >= 0)
            continue;
        const int32_t id = static_cast<int32_t>(sizes.size());
        sizes.push_back(0);
        component[s] = id;
        queue.push_back(s);
        while (!queue.empty()) {
            const std::size_t c = queue.front();
            queue.pop_front();
            ++sizes.back();
            const int64_t at[3] = {static_cast<int64_t>(c) % g.n[0], static_cast<int64_t>(c) / g.n[0] % g.n[1],
                                   static_cast<int64_t>(c) / (g.n[0] * g.n[1])};
            for (int axis = 0; axis < 3; ++axis)
                for (const int64_t d : {-1, 1}) {
                    const int64_t t = at[axis] + d;
                    if (t < 0 || t >= g.n[static_cast<std::size_t>(axis)])
                        continue;
                    const std::size_t e = static_cast<std::size_t>(static_cast<int64_t>(c) + d * step[axis]);
                    if (m[e] && component[e] < 0) {
                        component[e] = id;
                        queue.push_back(e);
                    }
                }
        }
    }
    const int32_t largest =
        sizes.empty() ? -1 : static_cast<int32_t>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
    for (std::size_t s = 0; s < m.size(); ++s)
        m[s] = component[s] == largest && largest >= 0;
}

// Per slice (third axis), what the slice's border cannot reach through 0s
// becomes 1.
void fill_slices(Mask &m, const Grid &g)
{
    std::vector<uint8_t> outside;
    std::vector<std::pair<int64_t, int64_t>> stack;
    for (int64_t k = 0; k < g.n[2]; ++k) {
        outside.assign(static_cast<std::size_t>(g.n[0] * g.n[1]), 0);
        const auto push = [&](int64_t i, int64_t j) {
            const std::size_t p = static_cast<std::size_t>(i + g.n[0] * j);
            if (!outside[p] && !m[g.at(i, j, k)]) {
                outside[p] = 1;
                stack.emplace_back(i, j);
            }
        };
        for (int64_t i = 0; i < g.n[0]; ++i)
            push(i, 0), push(i, g.n[1] - 1);
        for (int64_t j = 0; j < g.n[1]; ++j)
            push(0, j), push(g.n[0] - 1, j);
        while (!stack.empty()) {
            const auto [i, j] = stack.back();
            stack.pop_back();
            if (i > 0)
                push(i - 1, j);
            if (i + 1 < g.n[0])
                push(i + 1, j);
            if (j > 0)
                push(i, j - 1);
            if (j + 1 < g.n[1])
                push(i, j + 1);
        }
        for (int64_t j = 0; j < g.n[1]; ++j)
            for (int64_t i = 0; i < g.n[0]; ++i)
                if (!outside[static_cast<std::size_t>(i + g.n[0] * j)])
                    m[g.at(i, j, k)] = 1;
    }
}

} // namespace

BodyRegion::BodyRegion(const Volume &volume, double background_level)
{
    const Geometry &geometry = volume.geometry();
    dims_ = geometry.dims;
    std::array<int64_t, 3> w{};
    for (std::size_t a = 0; a < 3; ++a) {
        factor_[a] = std::max<int64_t>(1, std::llround(kCell / geometry.spacing[a]));
        cells_[a] = (dims_[a] + factor_[a] - 1) / factor_[a];
        w[a] = std::llround(kErosion / (geometry.spacing[a] * static_cast<double>(factor_[a])));
    }
    const Grid g{cells_};
    inside_.assign(g.size(), 1);
    if (std::isnan(background_level))
        return;
    // 1. The coarse cells' means above the background level.
    std::vector<double> sum(g.size(), 0.0);
    std::vector<uint32_t> count(g.size(), 0);
    for (int64_t k = 0; k < dims_[2]; ++k)
        for (int64_t j = 0; j < dims_[1]; ++j)
            for (int64_t i = 0; i < dims_[0]; ++i) {
                const std::size_t c = g.at(i / factor_[0], j / factor_[1], k / factor_[2]);
                sum[c] += volume.value(i + dims_[0] * (j + dims_[1] * k));
                ++count[c];
            }
    // The body's threshold: halfway from the background level to the median
    // of what lies above it, so that what only just rises out of the
    // background (a CT's pillow, foam at -800 HU) is not taken for the body.
    std::vector<double> mean(g.size(), 0.0), tissue;
    for (std::size_t c = 0; c < g.size(); ++c) {
        mean[c] = count[c] > 0 ? sum[c] / count[c] : background_level;
        if (mean[c] > background_level)
            tissue.push_back(mean[c]);
    }
    double threshold = background_level;
    if (!tissue.empty()) {
        const auto middle = tissue.begin() + static_cast<std::ptrdiff_t>(tissue.size() / 2);
        std::nth_element(tissue.begin(), middle, tissue.end());
        threshold = background_level + 0.5 * (*middle - background_level);
    }
    Mask above(g.size());
    for (std::size_t c = 0; c < g.size(); ++c)
        above[c] = mean[c] > threshold;
    // 2. Its holes, slice by slice.
    fill_slices(above, g);
    // 3.-5. Eroded, its largest component, dilated back within the mask.
    Mask body = above;
    for (int a = 0; a < 3; ++a)
        box_pass(body, g, a, w[static_cast<std::size_t>(a)], 1);
    keep_largest(body, g);
    for (int a = 0; a < 3; ++a)
        box_pass(body, g, a, w[static_cast<std::size_t>(a)], 0);
    std::size_t material = 0, kept = 0;
    for (std::size_t c = 0; c < g.size(); ++c) {
        body[c] = body[c] && above[c];
        material += above[c];
        kept += body[c];
    }
    // A body holds most of what is there; where the largest piece does not
    // (a segmented vessel tree, a skull-stripped brain's parts), there is no
    // body to speak of and nothing is outside it.
    if (2 * kept >= material)
        inside_ = std::move(body);
}

std::vector<double> BodyRegion::outside_shares(std::span<const uint32_t> labels, uint32_t label_count) const
{
    std::vector<double> outside(label_count, 0.0), all(label_count, 0.0);
    std::size_t v = 0;
    for (int64_t k = 0; k < dims_[2]; ++k)
        for (int64_t j = 0; j < dims_[1]; ++j)
            for (int64_t i = 0; i < dims_[0]; ++i, ++v) {
                const uint32_t l = labels[v];
                all[l] += 1;
                outside[l] += !inside(i, j, k);
            }
    for (uint32_t l = 0; l < label_count; ++l)
        outside[l] = all[l] > 0 ? outside[l] / all[l] : 0.0;
    return outside;
}

} // namespace arbor
