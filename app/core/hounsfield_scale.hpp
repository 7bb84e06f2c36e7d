// hounsfield_scale.hpp - whether a volume's values are Hounsfield units when
// its file does not say.  DICOM states the unit (Rescale Type, Modality);
// NIfTI, NRRD and MetaImage files converted from a CT usually keep the HU
// values but not the unit.  A CT in HU is recognisable from its values
// alone: the air in and around the body sits at -1000 HU, soft tissue near
// 0 to +60 HU, and nothing in an MR, a PET or an 8-bit windowed export puts
// a peak at -1000 with another at soft tissue.
#pragma once

#include "volume.hpp"

#include <optional>
#include <string>

namespace arbor {

struct HounsfieldEvidence {
    double air_peak = 0.0;        // centre of the fullest 20 HU bin from -1060 to -940
    double tissue_peak = 0.0;     // centre of the fullest 20 HU bin from -120 to +100
    double air_fraction = 0.0;    // of the samples from -1060 to -940 HU
    double tissue_fraction = 0.0; // of the samples from -150 to +150 HU

    // "12 % air, peak at -1010 HU; 31 % soft tissue, peak at 30 HU"
    std::string describe() const;
};

// The evidence when the physical values (the mapping applied) look like a CT
// in Hounsfield units, else nothing.  Both landmarks must be there: at
// least 1 % of the samples within 60 HU of -1000, and at least 5 % from -150
// to +150 HU with the fullest bin from -200 to +200 lying from -120 to +100
// and standing out as a peak, three times the mean bin from -900 to -300
// (lung, in a chest, is broad and lower there; a field spread evenly, like a
// phase map, has no peak).  Reads at most about 4 M voxels, evenly spread.
// The unit the mapping names is not consulted.
std::optional<HounsfieldEvidence> infer_hounsfield(const Volume &volume);

} // namespace arbor
