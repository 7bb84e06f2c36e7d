// study_grid.hpp - the settings a comparison study sweeps: filter chains,
// simplifier settings (one plugin may appear with several parameter
// settings) and cuts.  The tree is computed once per filter chain, each
// simplifier decomposes it once, and every cut is made on that.
#pragma once

#include "pipeline/document.hpp"
#include "pipeline/plugin_catalog.hpp"

#include <string>
#include <vector>

namespace arbor::cli {

struct StudyFilter {
    std::vector<pipeline::PluginSetting> chain; // empty: the data as it is
    std::string label;                          // "none", "gaussian:sigma=1", "median:size=3+gaussian:sigma=1"
};

struct StudySimplifier {
    pipeline::PluginSetting setting;
    std::string label; // as the user wrote it: "n-measure:measures=persistence+volume"
};

struct StudyGrid {
    std::vector<StudyFilter> filters;
    std::vector<StudySimplifier> simplifiers;
    std::vector<pipeline::CutChoice> cuts;
};

// "itri,n-measure:measures=persistence+volume,pv:exponent=2,scale=3" ->
// {"itri", "n-measure:measures=persistence+volume", "pv:exponent=2,scale=3"}:
// a comma starts a new entry unless what follows is key=value without a
// plugin name (the previous entry's next parameter).
std::vector<std::string> simplifier_entries(const std::string &list);

// File-name-safe form of a label: "n-measure_measures-persistence+volume".
std::string file_label(const std::string &label);

} // namespace arbor::cli
