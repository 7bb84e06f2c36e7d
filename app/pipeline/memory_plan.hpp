// memory_plan.hpp - what a run will need of memory, checked before the
// allocations it is about: a whole-body CT that cannot fit is refused with
// the figure it would need, in seconds, instead of swapping for minutes or
// being killed by the kernel half-way through its contour tree.
#pragma once

#include "document.hpp"

#include "core/volume.hpp"

#include <arbor/volume.h>

#include <string>

namespace arbor::pipeline {

// At the header, before the voxels are read: the voxels, a filtered copy
// when the document filters (or may denoise automatically), and the 8 bytes
// a voxel every run keeps (the tree's segmentation and the label map).  ""
// when it fits, else the sentence to refuse with.  The contour tree's own
// work space is checked when it is computed (a cached tree needs none).
std::string admit_volume(const arbor_volume &header, const Document &document);

// Before the contour tree is computed: throws std::runtime_error naming
// what the tree of `volume` needs at the least (topology_pipeline.hpp:
// streamed for 8- and 16-bit volumes, sweeps one after the other for the
// rest) and what is available when it does not fit.
void require_tree_memory(const Volume &volume);

} // namespace arbor::pipeline
