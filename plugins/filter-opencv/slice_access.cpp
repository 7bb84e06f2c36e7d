#include "slice_access.hpp"

#include <arbor/sdk/error.hpp>

#include <cstring>

namespace arbor::opencv_filters {

int cv_depth(arbor_voxel_type type)
{
    switch (type) {
    case ARBOR_VOXEL_U8: return CV_8U;
    case ARBOR_VOXEL_I8: return CV_8S;
    case ARBOR_VOXEL_U16: return CV_16U;
    case ARBOR_VOXEL_I16: return CV_16S;
    case ARBOR_VOXEL_I32: return CV_32S;
    case ARBOR_VOXEL_F32: return CV_32F;
    case ARBOR_VOXEL_F64: return CV_64F;
    default: return -1;
    }
}

cv::Mat read_slice(const arbor_volume &v, int64_t k)
{
    const int depth = cv_depth(v.voxel_type);
    if (depth < 0)
        sdk::fail(ARBOR_ERROR_UNSUPPORTED, "OpenCV has no matrix type for unsigned 32-bit voxels");
    cv::Mat m(static_cast<int>(v.dims[1]), static_cast<int>(v.dims[0]), CV_MAKETYPE(depth, 1));
    const std::size_t size = arbor_voxel_size(v.voxel_type);
    const char *base = static_cast<const char *>(v.voxels) + k * v.strides[2];
    for (int j = 0; j < m.rows; ++j) {
        const char *row = base + j * v.strides[1];
        if (v.strides[0] == static_cast<int64_t>(size)) // rows are contiguous: one copy each
            std::memcpy(m.ptr(j), row, size * m.cols);
        else
            for (int i = 0; i < m.cols; ++i)
                std::memcpy(m.ptr(j) + i * size, row + i * v.strides[0], size);
    }
    return m;
}

void write_slice(arbor_volume &v, int64_t k, const cv::Mat &slice)
{
    const std::size_t size = arbor_voxel_size(v.voxel_type);
    char *base = static_cast<char *>(v.voxels) + k * v.strides[2];
    for (int j = 0; j < slice.rows; ++j) {
        char *row = base + j * v.strides[1];
        if (v.strides[0] == static_cast<int64_t>(size))
            std::memcpy(row, slice.ptr(j), size * slice.cols);
        else
            for (int i = 0; i < slice.cols; ++i)
                std::memcpy(row + i * v.strides[0], slice.ptr(j) + i * size, size);
    }
}

} // namespace arbor::opencv_filters
