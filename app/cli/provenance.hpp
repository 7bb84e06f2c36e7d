// provenance.hpp - what every JSON report carries so that its result can be
// reproduced and two studies told apart: Arbor's version and commit, the
// command line, the input (path, importer as used, content checksum, or the
// phantom's recipe), the filter chain as data, and every plugin that took
// part with its version, library and all its parameter values (defaults
// included, simplifiers too).  No time of day and no timings: the same
// command on the same data writes the same bytes.
#pragma once

#include "cli_context.hpp"

#include "pipeline/document.hpp"
#include "pipeline/plugin_catalog.hpp"
#include "pipeline/stage_results.hpp"

#include <string>
#include <utility>
#include <vector>

namespace arbor::io {
class JsonWriter;
}

namespace arbor::cli {

// "0.1.0" and the commit the binary was built from.
std::string arbor_version();
std::string arbor_commit();

struct ProvenanceParts {
    const pipeline::ImportResult *import = nullptr;
    pipeline::InputChoice input;                // the phantom recipe, when there is one
    std::vector<pipeline::PluginSetting> filters; // as applied
    // The plugins that took part, by role ("simplifier", "generator"...),
    // with their settings as resolved (every parameter's value).
    std::vector<std::pair<std::string, pipeline::PluginSetting>> plugins;
};

// Writes the "provenance" member.
void write_provenance(io::JsonWriter &j, const Context &context, const pipeline::PluginCatalog &catalog,
                      const ProvenanceParts &parts);
// The same member's value, as text (a JSON object), for reports built as a
// document first.
std::string provenance_text(const Context &context, const pipeline::PluginCatalog &catalog,
                            const ProvenanceParts &parts);

// The parts of a document a pipeline ran: the import, the filters as
// applied, and every plugin the document names (simplifier, depictor,
// generator, renderer; resolved, with every parameter).
ProvenanceParts provenance_of(const pipeline::Document &resolved, const pipeline::ImportResult *import,
                              const std::vector<pipeline::PluginSetting> &filters_applied);

} // namespace arbor::cli
