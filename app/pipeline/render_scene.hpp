// render_scene.hpp - what a render request points at, built once from the
// pipeline's results: the volume's record, the label map, the background
// and the revisions (of the filtered volume and of the labels), so the
// render stage and the turntable ask a renderer the same way.  The request
// points into this object: it is neither copied nor moved.
#pragma once

#include "stage_results.hpp"

namespace arbor::pipeline {

struct RenderScene {
    RenderScene(const FilterResult &filtered, const LabelsResult &labels, uint32_t label_count,
                const std::array<double, 4> &background)
        : view(filtered.volume->view())
    {
        map.struct_size = sizeof map;
        map.label_count = label_count;
        for (int a = 0; a < 3; ++a)
            map.dims[a] = filtered.volume->geometry().dims[a];
        map.labels = labels.labels.data();
        request.struct_size = sizeof request;
        request.volume = &view;
        request.labels = &map;
        for (std::size_t i = 0; i < 4; ++i)
            request.background[i] = static_cast<float>(background[i]);
        request.volume_revision = filtered.revision;
        request.labels_revision = labels.revision;
    }
    RenderScene(const RenderScene &) = delete;
    RenderScene &operator=(const RenderScene &) = delete;

    arbor_volume view;
    arbor_label_map map{};
    arbor_render_request request{}; // transfer functions and camera: the caller's
};

} // namespace arbor::pipeline
