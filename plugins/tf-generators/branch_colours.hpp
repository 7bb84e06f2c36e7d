// branch_colours.hpp - one colour per branch (thesis §6.5): hues from the
// root down, evenly over the wheel or inside a harmonic template; CIELAB
// lightness from depth and subtree size (6.14); vividness rising with depth,
// scaled by ITri importance (6.15, see branch_colours.cpp); the HSV colour of that hue with that lightness and
// vividness found by bisection (colour_space.hpp).
#pragma once

#include "colour_space.hpp"
#include "harmonic_template.hpp"
#include "tissue_hues.hpp"

#include <arbor/depictor.h>
#include <arbor/sdk/branch_tree.hpp>

#include <map>
#include <tuple>
#include <vector>

namespace arbor::tf {

struct ColourSettings {
    HarmonicTemplate hues = HarmonicTemplate::parse("full");
    double lightness_min = 45.0, lightness_max = 85.0; // CIELAB L*
    double vividness_min = 0.25, vividness_max = 1.0;
};

struct BranchColour {
    double hue = 0.0, lightness = 0.0, vividness = 0.0; // the targets
    Rgb rgb{};                                           // straight sRGB
};

// Colours already found, by (hue, L*, vividness): regenerating after a
// change of opacity parameters finds every colour here.
class ColourCache {
public:
    const LightVivid &find(double hue, double lightness, double vividness);

private:
    std::map<std::tuple<double, double, double>, LightVivid> colours_;
};

// `depiction` (may be NULL) overrides hues and scales vividness.  With
// `tissues` (one per branch, may be NULL) each branch's hue is spread over
// its family's sector among the branches of that family, and its lightness
// and vividness, found by the same rules, are mapped into the family's
// ranges (tissue_hues.hpp); `settings.hues` is then not used.
std::vector<BranchColour> branch_colours(const sdk::BranchTreeView &tree, const ColourSettings &settings,
                                         const arbor_depiction *depiction, ColourCache &cache,
                                         const std::vector<TissueChoice> *tissues = nullptr);

// ITri importance of every branch scaled to [0, 1] for vividness: each
// branch's ITri over the largest among its siblings (itself included), as
// the residue flow distributes opacity among siblings; 1 for the root.  A
// scale over the whole tree would leave all but the largest structures
// grey: ITri spans orders of magnitude, and small inner structures (a
// tumour) are exactly the ones to show vividly.
std::vector<double> vividness_importance(const sdk::BranchTreeView &tree);

} // namespace arbor::tf
