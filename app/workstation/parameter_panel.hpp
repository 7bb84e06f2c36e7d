// parameter_panel.hpp - the controls of every stage, generated in this one
// place from the plugins' own parameter descriptions (arbor/params.h), so a
// third party's plugin gets its panel without code of ours: the input
// filter, the simplifier, the relationship depicted, the transfer-function
// generator (flow rate Q as a slider, shape, hue template), the legend and
// the renderer, each a choice of the installed plugins of its kind and its
// parameters (sliders within their ranges - over ten times the default
// where the range is far wider, Ctrl+click for any value - logarithmic where
// the plugin says so, check boxes, choices, text; ADVANCED ones folded away).  A drag is
// one undo step: the value follows the slider live and is recorded when it
// is released.
#pragma once

#include "pipeline/document.hpp"

#include <string>

namespace arbor::workstation {

class Workstation;

class ParameterPanel {
public:
    void draw(Workstation &workstation);

private:
    // One plugin choice and its parameters; true when `setting` changed.
    // `live`: the change is a drag in progress.
    bool plugin_controls(Workstation &ws, const char *kind, const char *label, pipeline::PluginSetting &setting,
                         bool optional, bool &live, std::string &what);
};

} // namespace arbor::workstation
