// controls.hpp - every control of the workstation by a name, as the script's
// `set NAME VALUE` and the panels use them: the document's own choices
// (keep, threshold, simplifier, relation, generator, renderer, filter,
// azimuth, elevation, zoom...) and every parameter of the plugins the
// document uses, by the id their descriptions give ("flow-rate", "shape",
// "hues", or qualified: "residue-flow.shape").  Setting edits a copy of the
// document; the pipeline checks the values when it is set.
#pragma once

#include "pipeline/document.hpp"
#include "pipeline/plugin_catalog.hpp"

#include <string>
#include <vector>

namespace arbor::workstation {

// Sets control `name` of `document` (resolved: full plugin ids) to the value
// `text`.  Throws std::invalid_argument for an unknown name or a value that
// is not of the control's kind (the pipeline checks plugin values against
// their descriptions when the document is set).
void set_control(pipeline::Document &document, const std::string &name, const std::string &text,
                 const pipeline::PluginCatalog &catalog);

// The current value of control `name` as text (throws like set_control).
std::string control_value(const pipeline::Document &document, const std::string &name,
                          const pipeline::PluginCatalog &catalog);

// `text` as a finite number; std::invalid_argument naming `what` otherwise
// (the script's and the controls' arguments).
double parse_number(const std::string &text, const std::string &what);

// The names set_control takes for this document: the built-in ones, then
// each plugin parameter.
std::vector<std::string> control_names(const pipeline::Document &document, const pipeline::PluginCatalog &catalog);

} // namespace arbor::workstation
