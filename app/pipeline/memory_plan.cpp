#include "memory_plan.hpp"

#include <algorithm>

#include "core/available_memory.hpp"
#include "core/volume_header.hpp"
#include "topology/topology_pipeline.hpp"

#include <stdexcept>

namespace arbor::pipeline {

namespace {

// Bytes a voxel that every run keeps beside the volume: the contour tree's
// vertex_arc and the cut's label map, 4 each.
constexpr uint64_t kKeptBytesPerVoxel = 8;

} // namespace

std::string admit_volume(const arbor_volume &header, const Document &document)
{
    const uint64_t voxels = static_cast<uint64_t>(header.dims[0]) * header.dims[1] * header.dims[2];
    const uint64_t size = arbor_voxel_size(header.voxel_type);
    const bool filtered = !document.filters.empty() || document.auto_denoise;
    const uint64_t needed = voxels * (size * (filtered ? 2 : 1) + kKeptBytesPerVoxel);
    std::string detail = format_bytes(voxels * size) + " of voxels";
    if (filtered)
        detail += ", as much again filtered";
    detail += ", " + format_bytes(voxels * kKeptBytesPerVoxel) + " of segmentation and labels";
    const std::string problem = check_memory(
        needed, "a run on " + dims_text(header.dims) + " " + arbor_voxel_type_name(header.voxel_type) + " voxels",
        detail);
    if (problem.empty())
        return "";
    return problem + " (before its contour tree, which needs " +
           format_bytes(topology::least_contour_tree_work_bytes(voxels, header.voxel_type)) +
           " more unless cached); crop or downsample the volume, or free memory";
}

void require_tree_memory(const Volume &volume)
{
    const uint64_t needed = topology::least_contour_tree_work_bytes(volume.voxel_count(), volume.type());
    const std::string problem = check_memory(
        needed, "the contour tree of " + dims_text(volume.geometry().dims.data()) + " voxels",
        std::to_string(needed / std::max<uint64_t>(1, volume.voxel_count())) + " bytes a voxel of work space");
    if (!problem.empty())
        throw std::runtime_error(problem + "; crop or downsample the volume, or free memory");
}

} // namespace arbor::pipeline
