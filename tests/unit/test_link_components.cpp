// The lower-link table of the merge-tree sweeps, against the triangulation
// itself: for every subset of a vertex's neighbours, the pieces the table
// names are the connected components of that subset under the grid's own
// edges (GridNeighbors), found here by flood fill on vertex ids.
#include "topology/grid_neighbors.hpp"
#include "topology/link_components.hpp"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace arbor::topology {
namespace {

TEST(LinkComponents, PiecesAreTheComponentsOfTheNeighbourSubsetInTheGrid)
{
    const GridNeighbors grid(5, 5, 5);
    const int64_t centre = 2 + 5 * (2 + 5 * 2);
    std::vector<int64_t> star;
    grid.for_each(centre, [&](int64_t w) { star.push_back(w); });
    ASSERT_EQ(star.size(), 14u);
    // The link: 14 vertices, 36 edges (a triangulated sphere, 24 triangles).
    int edges = 0;
    for (const int64_t a : star)
        grid.for_each(a, [&](int64_t w) { edges += std::set<int64_t>(star.begin(), star.end()).count(w) > 0; });
    EXPECT_EQ(edges / 2, 36);

    const std::vector<LinkComponents> &table = link_components_table();
    ASSERT_EQ(table.size(), 1u << 14);
    int most = 0;
    for (uint32_t mask = 0; mask < table.size(); ++mask) {
        std::set<int64_t> in;
        for (int n = 0; n < 14; ++n)
            if ((mask >> n) & 1u)
                in.insert(centre + grid.offset(n));
        // Flood fill from each representative: the fills are disjoint and
        // together cover the subset.
        std::set<int64_t> covered;
        const LinkComponents &entry = table[mask];
        for (int p = 0; p < entry.count; ++p) {
            const int64_t start = centre + grid.offset(entry.first[p]);
            ASSERT_TRUE(in.count(start)) << "mask " << mask;
            ASSERT_FALSE(covered.count(start)) << "mask " << mask << ": two representatives of one piece";
            std::vector<int64_t> stack{start};
            covered.insert(start);
            while (!stack.empty()) {
                const int64_t x = stack.back();
                stack.pop_back();
                grid.for_each(x, [&](int64_t w) {
                    if (in.count(w) && covered.insert(w).second)
                        stack.push_back(w);
                });
            }
        }
        ASSERT_EQ(covered, in) << "mask " << mask;
        most = std::max<int>(most, entry.count);
    }
    EXPECT_EQ(most, 6);
}

} // namespace
} // namespace arbor::topology
