// visibility_balance.hpp - opacity set from what the picture shows
// (after Correa and Ma's visibility-driven transfer functions).  A transfer
// function's opacities say how dense each structure should look, but what a
// structure contributes to the image also depends on its size and on what
// lies in front of it: a thick outer shell takes the picture, a thin inner
// bone is lost.  So the pipeline renders small previews from fixed views,
// measures each branch's visibility share, and scales each branch's optical
// depth until
//   - every kept structure gets at least `floor` of the picture,
//   - the outermost (the root branch: the body as a whole, its skin) between
//     `root_floor` and `root_cap`,
//   - a thin sheet or shell (compactness below 0.2: a fat layer, a skull, a
//     headrest) at most `sheet_cap`: layers are what one sees through,
//   - what is not the patient's anatomy inside the field of view - an
//     object outside the body (a headrest, a table, a frame; see
//     core/body_region.hpp) or a slab the field of view cut (a fifth or more
//     of its surface on the scan's border: an arm, the top of a head cut by
//     the last slice) - at most `context_cap`, and no floor: it stays as
//     faint context, where it is, rather than taking the picture,
//   - the content, where anything is seen, is opaque enough to read as
//     surfaces (`coverage` of mean opacity; made denser for that are only
//     the structures not already above their share, so coverage never
//     undoes a floor),
// changing nothing else: shares already within bounds keep their ratios, so
// what the generator decided (the residue flow's peeling by Q) stays.  What
// the caps give up is not all forced onto the few structures left free: none
// grows past three times its share before the balance (or the floor), and
// what is then left goes back to the sheets held at their cap (the CT head's
// skull); without that limit its nasal cavity, the one structure left free
// once its headrest became context, took a third of the picture.  A
// structure that stays hidden however dense it gets lies inside others:
// then its ancestors in the branch tree (but the root) are thinned, as the
// residue flow's Q would peel them - unless it is too small to be worth it
// (under a ten-thousandth of the labelled voxels): a few voxels do not take a
// hemisphere away.
//
// A selected structure (`focus`: a click in the workstation, `--select`) is
// what the person wants to see, in its context (Viola et al.'s
// importance-driven rendering).  The picture without the selection is
// balanced first; from there the selection's floor is `focus_floor`, its
// ancestors are peeled as soon as it is short of that floor, and the others
// (its context) are thinned to make room, but to no less than half their
// optical depth in that picture: thinning what does not hide it only
// darkens the picture around it.  (On brain1 the others hide little of the
// tumour: without them its visibility would be 11 % higher.  Thinned
// without that bound, the picture went nearly black around a selected jaw
// on the CT head.)
//
// The views are fixed (anterior, left, superior), so the result does not
// change as the camera orbits; the pipeline computes it once per set of
// transfer functions and labels.
#pragma once

#include "core/volume.hpp"
#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <functional>
#include <stop_token>
#include <vector>

namespace arbor::pipeline {

struct BalanceTargets {
    double floor = 0.02;    // least share of a kept non-root structure
    double root_floor = 0.12; // least share of the root branch: the body stays in the picture
    double root_cap = 0.35;   // most share of the root branch
    double sheet_cap = 0.25;  // most share of a thin sheet or shell
    double context_cap = 0.02; // most share of an object outside the body or a slab the field of view cut
    double coverage = 0.7;  // mean opacity over the pixels where anything is seen
    int32_t focus = -1;       // a selected structure (not the root), or -1
    double focus_floor = 0.25; // least share of the selected structure: focus and context
};

struct BalanceResult {
    std::vector<double> scale;                  // per branch: its optical depth's multiplier
    std::vector<double> shares_before, shares_after; // visibility shares over the previews
    int iterations = 0;
};

// Renders `tf` from `camera` at `size` x `size` pixels (the final render's
// renderer, labels and volume).
using PreviewFn = std::function<RenderedImage(const TransferFunctions &tf, const arbor_camera &camera, uint32_t size)>;

// Throws when the previews measure no visibility (a renderer that does not
// report it): then there is nothing to balance on.
// Per branch: its parent in the branch tree (-1 for the root), how many
// voxels it labels, whether it is a thin sheet or shell, and whether it is
// context (not anatomy, or cut by the field of view).
struct BranchLayout {
    std::vector<int32_t> parent;
    std::vector<double> voxels;
    std::vector<bool> sheet;
    std::vector<bool> context; // outside the body, or cut by the field of view (may be empty: none)
};

BalanceResult balance_visibility(const TransferFunctions &tf, const BranchLayout &layout, const Geometry &geometry,
                                 const PreviewFn &preview, const BalanceTargets &targets = {},
                                 std::stop_token stop = {});

} // namespace arbor::pipeline
