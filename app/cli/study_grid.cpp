#include "study_grid.hpp"
#include "usage_error.hpp"

#include <cctype>
#include <stdexcept>

namespace arbor::cli {

namespace {

std::string trimmed(std::string s)
{
    s.erase(0, s.find_first_not_of(" \t"));
    s.erase(s.find_last_not_of(" \t") + 1);
    return s;
}

} // namespace

std::vector<std::string> simplifier_entries(const std::string &list)
{
    std::vector<std::string> entries;
    std::size_t start = 0;
    while (start <= list.size()) {
        std::size_t end = list.find(',', start);
        if (end == std::string::npos)
            end = list.size();
        const std::string token = trimmed(list.substr(start, end - start));
        start = end + 1;
        if (token.empty())
            continue;
        const std::size_t eq = token.find('='), colon = token.find(':');
        const bool parameter = eq != std::string::npos && (colon == std::string::npos || colon > eq);
        if (parameter) {
            if (entries.empty() || entries.back().find(':') == std::string::npos)
                throw UsageError("--simplifiers: '" + token +
                                            "' is a parameter, but no simplifier before it takes parameters "
                                            "(write NAME:key=value)");
            entries.back() += "," + token;
        } else {
            entries.push_back(token);
        }
    }
    return entries;
}

std::string file_label(const std::string &label)
{
    std::string out;
    for (const char c : label) {
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+')
            out += c;
        else if (c == ':' || c == ',')
            out += '_';
        else if (c == '=')
            out += '-';
    }
    return out;
}

} // namespace arbor::cli
