// tissue_hues.hpp - on a CT, whose values are Hounsfield units, each branch's
// hue family follows its tissue, so that colour means what a radiologist
// expects: bone ivory, contrast-filled vessels and the heart red, soft
// tissue flesh, fat yellow, lung and airways blue-grey.  Within a family the
// hues are spread over the family's narrow sector (a one-sector harmonic
// template), so neighbouring structures of one tissue stay apart, and
// lightness and vividness keep the thesis' rules (6.14, 6.15) within the
// family's ranges.
//
// A branch's tissue is read from its values: the mean over its region,
// f_min + hypervolume / volume (ARBOR_MEASURE_HYPERVOLUME sums f - f_min), in
// the HU bins of the usual landmarks; a peak whose extremum reaches 700 HU
// or more is bone whatever its mean (its partial volumes pull the mean of a
// thin cortex down into the contrast bin).  The root is the body as a whole:
// its visible part is the skin and the soft tissue under it.
#pragma once

#include <arbor/sdk/branch_tree.hpp>
#include <arbor/transfer_function.h>

#include <string>
#include <vector>

namespace arbor::tf {

struct HueFamily {
    const char *name;
    double hue, width;                    // HSV hue in degrees; the sector's width
    double lightness_min, lightness_max;  // CIELAB L*
    double vividness_min, vividness_max;
};

// lung and airways, fat, soft tissue, contrast, bone.
const std::vector<HueFamily> &hue_families();

struct TissueChoice {
    std::size_t family = 0; // into hue_families()
    std::string why;        // "mean 640 HU, peak 1450 HU"
};

// Whether the request's volume holds Hounsfield units: its unit says so (a
// CT's DICOM rescale), or, with no unit given (a NIfTI or MetaImage CT), its
// background, the air around the body, peaks within 100 HU of -1000 and
// its values reach 200 (soft tissue and more).  `why` says which.
bool holds_hounsfield_units(const arbor_tf_request &request, std::string *why = nullptr);

// One per branch; requires the volume and hypervolume columns.
std::vector<TissueChoice> choose_tissues(const sdk::BranchTreeView &tree, const arbor_tf_request &request);

} // namespace arbor::tf
