// session.cpp - fuzzes reading a session document (app/pipeline/session:
// "arbor-session/1" JSON), checked against the installed plugins' parameter
// descriptions as `arbor run --session` and `arbor view` read it.  The input
// is the document's text; relative paths in it resolve against the
// harness's scratch folder.
//
// The plugins are the built ones (ARBOR_FUZZ_PLUGIN_DIR, from CMake).
#include "fuzz_support.hpp"

#include "pipeline/session.hpp"

#include <string>

namespace {

const arbor::pipeline::PluginCatalog &catalog()
{
    static const auto registry = [] {
        auto r = std::make_unique<arbor::PluginRegistry>();
        r->load_directories({ARBOR_FUZZ_PLUGIN_DIR});
        if (r->plugins().empty())
            arbor::fuzz::finding("no plugins in " + std::string(ARBOR_FUZZ_PLUGIN_DIR) +
                                 " (the harness needs the built plugins)");
        return r;
    }();
    static const arbor::pipeline::PluginCatalog catalog(*registry);
    return catalog;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char *>(data), size);
    try {
        arbor::pipeline::parse_session(text, arbor::fuzz::scratch_folder(), "session.json", catalog());
    } catch (const arbor::pipeline::SessionError &) {
        // Refused with a message naming the file and the problem.
    } catch (...) {
        arbor::fuzz::unexpected_exception(std::current_exception());
    }
    return 0;
}
