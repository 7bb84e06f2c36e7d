#include "viewpoint.hpp"

#include "core/cancelled.hpp"

#include <cmath>

namespace arbor::pipeline {

ViewpointChoice choose_viewpoint(const Geometry &geometry, const std::vector<double> &voxels,
                                 const ViewPreviewFn &preview, std::stop_token stop)
{
    constexpr uint32_t kPreview = 48;
    std::vector<std::pair<double, double>> directions;
    for (const double elevation : {0.0, 30.0, -30.0, 60.0})
        for (int a = 0; a < 8; ++a)
            directions.emplace_back(45.0 * a, elevation);
    directions.emplace_back(0.0, 90.0);
    // The geometric mean of the structures' visibility shares: a view
    // scores when none of them is hidden.  A few voxels (under a
    // ten-thousandth of the structures') cannot be shown from anywhere.
    double structures = 0;
    for (std::size_t b = 1; b < voxels.size(); ++b)
        structures += voxels[b];
    const auto score = [&](const RenderedImage &im) {
        double total = 0;
        for (double v : im.label_visibility)
            total += v;
        if (!(total > 0))
            return 0.0;
        double s = 0, counted = 0;
        for (std::size_t b = 1; b < im.label_visibility.size() && b < voxels.size(); ++b)
            if (voxels[b] >= 1e-4 * structures) {
                s += std::log(1e-3 + im.label_visibility[b] / total);
                counted += 1;
            }
        return counted > 0 ? std::exp(s / counted) : 0.0;
    };
    ViewpointChoice best;
    bool first = true;
    for (const auto &[azimuth, elevation] : directions) {
        throw_if_stopped(stop);
        Orbit o;
        o.azimuth = azimuth;
        o.elevation = elevation;
        const double s = score(preview(orbit_camera(geometry, o), kPreview));
        if (first) {
            best = {azimuth, elevation, s, s};
            first = false;
        } else if (s > best.score && s > 1.05 * best.anterior_score) {
            best.azimuth = azimuth;
            best.elevation = elevation;
            best.score = s;
        }
    }
    return best;
}

} // namespace arbor::pipeline
