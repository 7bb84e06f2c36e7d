#include "document.hpp"
#include "stage_results.hpp"

#include <sstream>

namespace arbor::pipeline {

Document default_document()
{
    Document d;
    d.simplifier.id = "itri";
    d.appearance.depictor.id = "inclusion";
    d.appearance.generator.id = "residue-flow";
    d.appearance.legend.id = "neighbour";
    d.view.renderer.id = "cpu-raycast";
    return d;
}

std::string CutChoice::describe() const
{
    std::ostringstream s;
    if (keep)
        s << "keep " << *keep;
    else if (threshold)
        s << "threshold " << *threshold;
    else
        s << "knee";
    return s.str();
}

CutChoice CutResult::effective() const
{
    if (!knee)
        return requested;
    CutChoice c;
    c.keep = knee->keep;
    return c;
}

} // namespace arbor::pipeline
