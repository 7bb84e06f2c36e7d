// plugin_fixture.hpp - load the plugins built in this tree and import volumes
// through them, exactly as the host does (importer choice by probing, header
// check, host-allocated voxels).
#pragma once

#include "test_paths.hpp"

#include "core/volume.hpp"
#include "core/volume_header.hpp"
#include "host/param_text.hpp"
#include "host/plugin_registry.hpp"
#include "host/volume_import.hpp"

#include <map>
#include <memory>
#include <string>

namespace arbor::test {

// One registry per test process (loading is relatively expensive).
inline const PluginRegistry &built_plugins()
{
    static const std::unique_ptr<PluginRegistry> registry = [] {
        auto r = std::make_unique<PluginRegistry>();
        r->load_directories({plugin_dir()});
        return r;
    }();
    return *registry;
}

// Imports `path`; importer_id "" means choose by probing.  `params` are set
// as text, as the CLI would.  Throws what the host would report.
inline Volume import(const std::filesystem::path &path, const std::string &importer_id = "",
                     const std::map<std::string, std::string> &params = {},
                     uint64_t max_bytes = uint64_t{1} << 32)
{
    const PluginRegistry &registry = built_plugins();
    const std::string id = importer_id.empty() ? choose_importer(registry, path) : importer_id;
    PluginInstance importer = registry.create(id);
    for (const auto &[k, v] : params) {
        const arbor_param_desc *d = importer.find_param(k);
        if (!d)
            throw std::runtime_error(id + " has no parameter " + k);
        ParamText t = parse_param_value(*d, v);
        importer.set_param(k, t.value);
    }
    return import_volume(importer, path, nullptr, max_bytes);
}

} // namespace arbor::test
