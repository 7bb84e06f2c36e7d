// param_text.hpp - parameter values as text, for command-line flags and
// session files: "64,64,64" for a 3-component INT, "ramp" for a choice,
// "true" for a boolean.  Parsing checks the text against the description, so
// a bad flag is refused before the plugin sees it.
#pragma once

#include <arbor/params.h>

#include <string>

namespace arbor {

// A parsed value; `text` of the arbor_param_value points into `storage`.
struct ParamText {
    arbor_param_value value{};
    std::string storage;
};

// Throws std::invalid_argument with a message naming the parameter.
ParamText parse_param_value(const arbor_param_desc &desc, const std::string &text);

std::string format_param_value(const arbor_param_desc &desc, const arbor_param_value &value);
// "[0, 300]", "one of: ramp, hat, box", "text"
std::string describe_param_domain(const arbor_param_desc &desc);
// Default value as text.
std::string format_param_default(const arbor_param_desc &desc);

} // namespace arbor
