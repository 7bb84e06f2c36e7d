// turntable.hpp - a volume turning once about its vertical axis, frame by
// frame, through the pipeline's renderer: what `arbor render --orbit N`
// writes as a video.  The transfer functions, their balance and the
// framing are the pipeline's render of the document (computed once, at the
// document's view); each frame then only turns the camera about the volume's
// centre (framed by the first frame's zoom: a turntable does not re-centre)
// and renders it at the quality asked for.
#pragma once

#include "pipeline.hpp"

#include <functional>
#include <stop_token>
#include <vector>

namespace arbor::pipeline {

enum class TurntableQuality { coarse, full, supersampled };

struct TurntableOptions {
    uint32_t frames = 36;
    TurntableQuality quality = TurntableQuality::full;
    uint32_t supersamples = 4; // supersampled: passes after the full one
};

struct TurntableFrame {
    uint32_t index = 0;
    double azimuth = 0;          // degrees
    RenderedImage image;
    std::vector<double> pass_seconds; // per pass: coarse, or full then each supersample
    double seconds = 0;               // the whole frame
};

// Renders the frames in order, handing each to `sink` as it is done.
// Throws what the pipeline or the renderer throws (Cancelled when stopped).
void render_turntable(Pipeline &pipeline, const TurntableOptions &options,
                      const std::function<void(const TurntableFrame &)> &sink, std::stop_token stop = {});

// "coarse", "full", "supersampled"; parse throws std::invalid_argument.
const char *quality_name(TurntableQuality q);
TurntableQuality parse_quality(const std::string &text);

} // namespace arbor::pipeline
