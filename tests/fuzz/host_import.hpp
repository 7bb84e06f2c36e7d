// host_import.hpp - an importer plugin driven the way the host drives it
// (host/volume_import.cpp: read_header through the C ABI, the host's header
// checks, the allocation, read_voxels), for the importer harnesses.  The
// plugin library is linked into the harness instead of loaded, and reached
// through its entry point as the host reaches it.
#pragma once

#include <arbor/plugin.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

// The entry point of the plugin library linked into the harness.
extern "C" const arbor_plugin_entry arbor_entry;

namespace arbor::fuzz {

// The host's memory budget for one volume in the harnesses: headers claiming
// more are refused by the host, as on a small machine.
inline constexpr uint64_t kHostMaxBytes = uint64_t{64} << 20;

struct ImportCheck {
    // Bytes of voxels a header accepted by the importer may claim at most
    // (0: no bound).  NRRD, MetaImage and legacy VTK promise to refuse, before
    // the host allocates, a header whose file cannot hold its voxels.
    uint64_t header_bound = 0;
    // Parameters set (as text) before the import.
    std::map<std::string, std::string> params;
};

// Imports `path` with a new instance of plugin `id`.  Refusals (an error
// status with the plugin's message, the host's header checks) are the
// expected outcome of bad input; ARBOR_ERROR_INTERNAL, any other exception,
// or a header over `check.header_bound` is a finding.
void import_through_host(const std::string &id, const std::filesystem::path &path, const ImportCheck &check = {});

} // namespace arbor::fuzz
