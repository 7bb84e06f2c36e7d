#include "document.hpp"

#include "stage_results.hpp"

#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace arbor::pipeline {

Document default_document()
{
    Document d;
    // Full ids: a third party's plugin that shares a short name ("itri")
    // must not change what the defaults mean.
    d.simplifier.id = "org.arbor.simplifier.itri";
    d.appearance.depictor.id = "org.arbor.depictor.inclusion";
    d.appearance.generator.id = "org.arbor.tf.residue-flow";
    d.appearance.legend.id = "org.arbor.depictor.neighbour";
    d.view.renderer.id = "auto"; // PluginCatalog::renderer_choice
    return d;
}

bool is_input_uri(const std::string &text)
{
    const std::size_t colon = text.find("://");
    if (colon == std::string::npos || colon == 0)
        return false;
    for (std::size_t i = 0; i < colon; ++i)
        if (!(std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '+' || text[i] == '-' || text[i] == '.'))
            return false;
    return std::isalpha(static_cast<unsigned char>(text[0])) != 0;
}

PluginSetting parse_plugin_spec(const std::string &spec, const std::string &what)
{
    PluginSetting s;
    const std::size_t colon = spec.find(':');
    s.id = spec.substr(0, colon);
    if (s.id.empty())
        throw std::invalid_argument(what + " '" + spec + "': no plugin named");
    if (colon == std::string::npos)
        return s;
    const std::string rest = spec.substr(colon + 1);
    if (rest.find_first_not_of(" \t") == std::string::npos)
        return s;
    std::size_t start = 0;
    while (start <= rest.size()) {
        const std::size_t comma = rest.find(',', start);
        std::string pair = rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        pair.erase(0, pair.find_first_not_of(" \t"));
        pair.erase(pair.find_last_not_of(" \t") + 1);
        const std::size_t eq = pair.find('=');
        if (eq == std::string::npos || eq == 0)
            throw std::invalid_argument(what + " " + spec + ": '" + pair + "' is not key=value");
        s.params[pair.substr(0, eq)] = pair.substr(eq + 1);
        if (comma == std::string::npos)
            break;
        start = comma + 1;
    }
    return s;
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
