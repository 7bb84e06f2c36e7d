// priority_line_view.hpp - the thesis' priority-line window (Appendix A):
// one row per simplifier, the branches of the decomposition along x in the
// current simplifier's order (most important first), a vertical line per
// branch as tall as its importance in that row, the kept ones coloured; the
// threshold is a horizontal line to drag, and the cut follows live.  The
// current simplifier's row is its own importance; the rows of the other
// single-measure simplifiers (persistence, volume, hypervolume) are those
// measures relative to the root, and dragging in one of them switches to
// that simplifier.  A row whose values span more than two decades is drawn
// on a log scale (the study's figures use one too), else a dominant branch
// leaves the others a flat line the threshold cannot be placed on.  Keep-N
// is the alternative: a slider below.
#pragma once

#include "pipeline/stage_results.hpp"
#include "topology/branch_decomposition.hpp"

#include <future>
#include <memory>
#include <string>
#include <vector>

namespace arbor::workstation {

class Workstation;

// A priority-line row's vertical scale: linear from 0 to its largest value,
// or, when the values shown span more than two decades (one dominant branch,
// as ITri's often has), logarithmic from the smallest positive one.
struct PriorityScale {
    double top = 1;    // the row's full height
    double bottom = 0; // log scale from here; 0: linear
    // `least`: the smallest positive value shown.
    static PriorityScale of(double top, double least);
    double height(double value) const;    // 0..1 of the row
    double value_at(double height) const; // the inverse
};

class PriorityLineView {
public:
    void draw(Workstation &workstation);
    // Whether the last draw showed the rows (not "ordering": the branches
    // of a new decomposition are ordered off the UI thread first).
    bool showed_rows() const { return showed_rows_; }

private:
    struct Row {
        std::string simplifier; // short plugin name
        int measure = -1;       // topology::kPersistence...: that measure relative to the root; -1: the importance
        bool current = false;
        double top = 1;         // its largest value (over every branch)
    };
    // What the rows show, made off the UI thread: each row's largest value
    // and the `count` most important branches, in order.  Nothing per branch
    // is kept but that order: a noisy scan's decomposition has hundreds of
    // thousands of branches; ordering them took the UI thread 16-24 ms, a
    // frame over budget as the tree arrived.
    struct Ordering {
        std::shared_ptr<const pipeline::DecompositionResult> of;
        std::vector<Row> rows;
        std::vector<uint32_t> order;
    };
    static double value(const topology::BranchDecomposition &d, const Row &row, uint32_t branch);
    static Ordering order_branches(std::shared_ptr<const pipeline::DecompositionResult> decomposition,
                                   std::vector<Row> rows, std::size_t count);
    // Starts ordering `decomposition` unless an ordering is under way (a
    // newer one starts when it is done: a future's destructor would wait).
    void start_ordering(Workstation &ws, const std::shared_ptr<const pipeline::DecompositionResult> &decomposition,
                        std::size_t count);

    // The decomposition they were made for: a new decomposition (a new tree,
    // another simplifier) makes them again, a new cut of the same one (a
    // dragged threshold) does not.
    std::shared_ptr<const pipeline::DecompositionResult> rows_of_;
    std::vector<Row> rows_;
    std::vector<uint32_t> order_; // the current simplifier's most important branches, most important first
    std::future<Ordering> ordering_;
    std::shared_ptr<const pipeline::DecompositionResult> failed_; // the decomposition that could not be ordered
    bool showed_rows_ = false;
    std::string dragging_; // the row's simplifier while its threshold is dragged
};

} // namespace arbor::workstation
