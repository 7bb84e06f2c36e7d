// priority_line_view.hpp - the thesis' priority-line window (Appendix A):
// one row per simplifier, the branches of the decomposition along x in the
// current simplifier's order (most important first), a vertical line per
// branch as tall as its importance in that row, the kept ones coloured; the
// threshold is a horizontal line to drag, and the cut follows live.  The
// current simplifier's row is its own importance; the rows of the other
// single-measure simplifiers (persistence, volume, hypervolume) are those
// measures relative to the root, and dragging in one of them switches to
// that simplifier.  Keep-N is the alternative: a slider below.
#pragma once

#include "pipeline/stage_results.hpp"

#include <memory>
#include <string>
#include <vector>

namespace arbor::workstation {

class Workstation;

class PriorityLineView {
public:
    void draw(Workstation &workstation);

private:
    struct Row {
        std::string simplifier; // short plugin name
        int measure = -1;       // topology::kPersistence...: that measure relative to the root; -1: the importance
        bool current = false;
        double top = 1;         // the largest value: the row's full height
    };
    double value(const Row &row, uint32_t branch) const;
    // The rows and the `count` most important branches, in order.  Nothing
    // per branch is kept but that order: a noisy scan's decomposition has
    // hundreds of thousands of branches, and arrays of them made on the UI
    // thread cost it a frame in page faults alone.
    void build_rows(Workstation &ws, const pipeline::DecompositionResult &decomposition, std::size_t count);

    // The decomposition they were made for: a new decomposition (a new tree,
    // another simplifier) makes them again, a new cut of the same one (a
    // dragged threshold) does not.
    std::shared_ptr<const pipeline::DecompositionResult> rows_of_;
    std::vector<Row> rows_;
    std::vector<uint32_t> order_; // the current simplifier's most important branches, most important first
    std::string dragging_; // the row's simplifier while its threshold is dragged
};

} // namespace arbor::workstation
