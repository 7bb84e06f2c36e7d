// usage_error.hpp - a wrong command line that only the command itself can
// see (a flag's value that does not fit, flags that do not go together):
// `arbor` exits with status 2 and the message, as for a flag CLI11 refuses.
#pragma once

#include <stdexcept>

namespace arbor::cli {

class UsageError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

} // namespace arbor::cli
