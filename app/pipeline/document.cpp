#include "document.hpp"
#include "stage_results.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace arbor::pipeline {

Document default_document()
{
    Document d;
    d.simplifier.id = "itri";
    d.appearance.depictor.id = "inclusion";
    d.appearance.generator.id = "residue-flow";
    d.appearance.legend.id = "neighbour";
    d.view.renderer.id = "auto"; // PluginCatalog::renderer_choice
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

CutChoice CutChoice::parse(const std::string &text)
{
    CutChoice c;
    if (text == "knee")
        return c;
    std::istringstream in(text);
    std::string word;
    double x = 0;
    if (in >> word >> x && in.eof()) {
        if (word == "keep" && x >= 1 && x == std::floor(x)) {
            c.keep = static_cast<std::size_t>(x);
            return c;
        }
        if (word == "threshold" && x >= 0 && x <= 1) {
            c.threshold = x;
            return c;
        }
    }
    throw std::invalid_argument("'" + text + "' is not a cut (\"keep N\", \"threshold T\" or \"knee\")");
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
