#include "block_statistics.hpp"
#include "cancellation.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace arbor::raycast {

void BlockStatistics::build(const VoxelGrid &g, const sdk::Task &task)
{
    bx_ = (g.nx + kBlock - 1) / kBlock;
    by_ = (g.ny + kBlock - 1) / kBlock;
    bz_ = (g.nz + kBlock - 1) / kBlock;
    const std::size_t n = static_cast<std::size_t>(bx_ * by_ * bz_);
    lo_.assign(n, INFINITY);
    hi_.assign(n, -INFINITY);
    labels_.assign(n * kMaxLabels, 0);
    label_count_.assign(n, 0);
    Cancellation cancel(task);
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, bz_ * by_), [&](const tbb::blocked_range<int64_t> &rows) {
        if (cancel.stopped())
            return;
        for (int64_t row = rows.begin(); row != rows.end(); ++row) {
            const int64_t bk = row / by_, bj = row % by_;
            for (int64_t bi = 0; bi < bx_; ++bi) {
                const std::size_t b = static_cast<std::size_t>(bi + bx_ * (bj + by_ * bk));
                float lo = INFINITY, hi = -INFINITY;
                uint32_t *mine = &labels_[b * kMaxLabels];
                uint32_t count = 0;
                const int64_t k0 = std::max<int64_t>(bk * kBlock - 1, 0), k1 = std::min((bk + 1) * kBlock, g.nz - 1);
                const int64_t j0 = std::max<int64_t>(bj * kBlock - 1, 0), j1 = std::min((bj + 1) * kBlock, g.ny - 1);
                const int64_t i0 = std::max<int64_t>(bi * kBlock - 1, 0), i1 = std::min((bi + 1) * kBlock, g.nx - 1);
                for (int64_t k = k0; k <= k1; ++k)
                    for (int64_t j = j0; j <= j1; ++j) {
                        const std::size_t start = g.index(i0, j, k);
                        for (int64_t i = i0; i <= i1; ++i) {
                            const float x = g.value[start + static_cast<std::size_t>(i - i0)];
                            lo = std::min(lo, x);
                            hi = std::max(hi, x);
                        }
                        if (g.label.empty() || count > kMaxLabels)
                            continue;
                        for (int64_t i = i0; i <= i1; ++i) {
                            const uint32_t l = g.label[start + static_cast<std::size_t>(i - i0)];
                            if (count > 0 && mine[count - 1] == l) // runs of one label are the rule
                                continue;
                            if (std::find(mine, mine + count, l) != mine + count)
                                continue;
                            if (count == kMaxLabels) {
                                count = kMaxLabels + 1;
                                break;
                            }
                            mine[count++] = l;
                        }
                    }
                if (g.label.empty())
                    mine[count++] = 0;
                else if (count <= kMaxLabels)
                    count = g.tree.close_paths(mine, count, kMaxLabels); // what mixed cells resolve to
                lo_[b] = lo;
                hi_[b] = hi;
                label_count_[b] = count;
            }
        }
    });
    task.throw_if_cancelled();
}

} // namespace arbor::raycast
