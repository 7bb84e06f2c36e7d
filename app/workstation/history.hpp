// history.hpp - undo and redo of the user's choices.  Every change is a
// whole Document (plain values, cheap to copy), so undoing is setting the
// previous one back; a slider drag is one step, not one per frame: the
// front records only when the drag ends (commit), while set() moves the
// live value.
#pragma once

#include "pipeline/document.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace arbor::workstation {

class History {
public:
    explicit History(pipeline::Document initial, std::size_t limit = 200);

    // The document now shown (committed or being dragged).
    const pipeline::Document &current() const { return current_; }
    // Moves the live value without recording a step.
    void set(const pipeline::Document &document) { current_ = document; }
    // Records the live value as a step named `what` ("flow-rate 150"), when
    // it differs from the last recorded one; drops the redo steps.
    void commit(const std::string &what);
    // A recorded change to `document` at once.
    void apply(const pipeline::Document &document, const std::string &what)
    {
        set(document);
        commit(what);
    }

    bool can_undo() const { return position_ > 0; }
    bool can_redo() const { return position_ + 1 < steps_.size(); }
    // The step undone or redone ("" when there was none); current() is then
    // the document before or after it.
    std::string undo();
    std::string redo();
    // The steps' names, oldest first.
    std::vector<std::string> names() const;

private:
    struct Step {
        pipeline::Document document;
        std::string what;
    };
    std::vector<Step> steps_;
    std::size_t position_ = 0;
    std::size_t limit_;
    pipeline::Document current_;
};

} // namespace arbor::workstation
