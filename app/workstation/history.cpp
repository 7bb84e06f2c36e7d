#include "history.hpp"

namespace arbor::workstation {

History::History(pipeline::Document initial, std::size_t limit)
    : limit_(limit < 2 ? 2 : limit), current_(std::move(initial))
{
    steps_.push_back({current_, "open"});
}

void History::commit(const std::string &what)
{
    if (current_ == steps_[position_].document)
        return;
    steps_.resize(position_ + 1);
    steps_.push_back({current_, what});
    if (steps_.size() > limit_)
        steps_.erase(steps_.begin());
    position_ = steps_.size() - 1;
}

std::string History::undo()
{
    // A drag not yet committed is undone to the step it started from.
    if (current_ != steps_[position_].document) {
        current_ = steps_[position_].document;
        return "the change in progress";
    }
    if (!can_undo())
        return "";
    const std::string what = steps_[position_].what;
    current_ = steps_[--position_].document;
    return what;
}

std::string History::redo()
{
    if (!can_redo())
        return "";
    current_ = steps_[++position_].document;
    return steps_[position_].what;
}

std::vector<std::string> History::names() const
{
    std::vector<std::string> out;
    for (const Step &s : steps_)
        out.push_back(s.what);
    return out;
}

} // namespace arbor::workstation
