// viewpoint.hpp - a camera direction chosen by the topology (the thesis'
// third item of future work): the orbit direction from which the most
// important inner structures are best seen.  Small previews from 33
// directions around the volume (every 45 degrees of azimuth at four
// elevations, and from above); each is scored by the geometric mean of the
// kept non-root branches' visibility shares (but for structures of a few
// voxels, which no view shows): a view scores when none of the structures is
// hidden.  The anterior view is kept unless another is at
// least 5 % better, so a scan is not turned for nothing.
#pragma once

#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <functional>
#include <stop_token>
#include <vector>

namespace arbor::pipeline {

struct ViewpointChoice {
    double azimuth = 0.0, elevation = 0.0;
    double score = 0.0, anterior_score = 0.0;
};

using ViewPreviewFn = std::function<RenderedImage(const arbor_camera &camera, uint32_t size)>;

// `voxels`: per branch how many voxels it labels (the root's is ignored).
ViewpointChoice choose_viewpoint(const Geometry &geometry, const std::vector<double> &voxels,
                                 const ViewPreviewFn &preview, std::stop_token stop = {});

} // namespace arbor::pipeline
