// ct_tissue.hpp - the tissues a range of Hounsfield units spans, so a report
// can say what a branch of a CT is ("fat, soft tissue") rather than only its
// numbers.  The bins are contiguous and follow the usual radiological
// landmarks: air -1000, lung about -850 to -500, fat -120 to -90, water 0,
// soft tissue and blood 20 to 80, iodinated contrast 150 to 300 and more,
// cancellous bone from about 300, cortical bone above 1000.  Boundaries
// between bins are where partial volumes of their neighbours meet.
#pragma once

#include <string>
#include <vector>

namespace arbor {

struct CtTissue {
    const char *name;
    double low_hu, high_hu; // [low, high)
};

// air, lung, fat, soft tissue, contrast, bone, in increasing HU.
const std::vector<CtTissue> &ct_tissues();

// The names of the tissues whose bins meet [low_hu, high_hu], in order.
std::vector<std::string> ct_tissues_spanned(double low_hu, double high_hu);

} // namespace arbor
