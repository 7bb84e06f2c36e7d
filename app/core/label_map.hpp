// label_map.hpp - one label per voxel (i fastest): the kept branch each voxel
// belongs to after simplification, an index into the cut's kept branches.
#pragma once

#include "huge_pages.hpp"

#include <cstdint>

namespace arbor {

using LabelMap = StreamedVector<uint32_t>;

} // namespace arbor
