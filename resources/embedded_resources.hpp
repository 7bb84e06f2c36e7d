// embedded_resources.hpp - files from resources/ compiled into the binary.
#pragma once

#include <optional>
#include <string_view>

namespace arbor {

// Contents of an embedded file by its path under resources/
// ("phantoms/head.json"), or nullopt.
std::optional<std::string_view> embedded_resource(std::string_view name);

} // namespace arbor
