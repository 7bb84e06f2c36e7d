// arbor/sdk/error.hpp - exceptions that carry an Arbor status code.
//
// Part of the optional C++ layer of the SDK: plugin code may throw
// arbor::sdk::Error anywhere; the boundary adapters (instance.hpp) turn it into
// the status code and the instance's last-error message.  No exception ever
// crosses the C ABI.
#pragma once

#include <arbor/abi.h>

#include <stdexcept>
#include <string>

namespace arbor::sdk {

class Error : public std::runtime_error {
public:
    Error(arbor_status status, const std::string &message)
        : std::runtime_error(message), status_(status) {}
    arbor_status status() const noexcept { return status_; }

private:
    arbor_status status_;
};

[[noreturn]] inline void fail(arbor_status status, const std::string &message)
{
    throw Error(status, message);
}

} // namespace arbor::sdk
