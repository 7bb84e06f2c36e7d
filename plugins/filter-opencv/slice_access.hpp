// slice_access.hpp - a volume's axial slices (k fixed) as OpenCV matrices:
// copied out of any strides into a contiguous CV type, and back.
#pragma once

#include <arbor/volume.h>

#include <opencv2/core.hpp>

namespace arbor::opencv_filters {

// The OpenCV depth of a voxel type, or -1 (32-bit integers and doubles
// are processed as CV_32F / CV_64F by the filters that allow it).
int cv_depth(arbor_voxel_type type);

// Slice k as a ny x nx matrix of the volume's own type.
cv::Mat read_slice(const arbor_volume &v, int64_t k);
void write_slice(arbor_volume &v, int64_t k, const cv::Mat &slice);

} // namespace arbor::opencv_filters
