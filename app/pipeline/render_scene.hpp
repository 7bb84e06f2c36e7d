// render_scene.hpp - what a render request points at, built once from the
// pipeline's results: the volume's record, the label map (and how its
// labels nest), the background and the revisions (of the filtered volume
// and of the labels), so the render stage and the turntable ask a
// renderer the same way.  The request points into this object: it is
// neither copied nor moved.
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
        // How the labels nest, for renderers that resolve a label per
        // sample: the cut's tree, whose branch k is label k.
        if (labels.cut && labels.cut->tree && labels.cut->tree->size() == label_count) {
            const arbor_branch_tree &tree = labels.cut->tree->record();
            map.parent = tree.parent;
            map.saddle_value = tree.saddle_value;
        }
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
