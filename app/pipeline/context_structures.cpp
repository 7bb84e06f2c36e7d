#include "context_structures.hpp"

namespace arbor::pipeline {

ContextReason context_reason(const topology::LabelShape &shape, bool maximum, bool root)
{
    if (root)
        return ContextReason::None;
    if (maximum && shape.outside_body >= kOutsideBody)
        return ContextReason::OutsideBody;
    if (shape.cut_fraction >= kCutByFieldOfView)
        return ContextReason::CutByFieldOfView;
    return ContextReason::None;
}

const char *describe(ContextReason reason)
{
    switch (reason) {
    case ContextReason::OutsideBody: return "outside the body";
    case ContextReason::CutByFieldOfView: return "cut by the field of view";
    case ContextReason::None: break;
    }
    return "";
}

} // namespace arbor::pipeline
