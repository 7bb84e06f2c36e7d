// isolated_plugin.hpp - the proxy arbor_plugin of an isolated library
// (isolated_library.hpp): an instance in the plugin's process, reached
// through its own channel.
#pragma once

#include <arbor/arbor.h>

namespace arbor {

class IsolatedLibrary;

// Creates the instance in the library's process and a proxy for it in
// *out; on failure *out is NULL and the reason is logged through `host`.
arbor_status create_proxy_plugin(IsolatedLibrary &library, const arbor_host *host,
                                 const arbor_plugin_descriptor *descriptor, arbor_plugin **out);

} // namespace arbor
