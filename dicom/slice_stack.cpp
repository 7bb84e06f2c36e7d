#include "slice_stack.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <stdexcept>

namespace arbor::dicom {

namespace {

double dot(const Vec3 &a, const Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::string mm(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g mm", v);
    return buf;
}

std::string number(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.5g", v);
    return buf;
}

// "106 gaps of 1.5 mm, 1 of 1 mm": gap lengths rounded to 0.01 mm, most common first.
std::string gap_histogram(const std::vector<double> &gaps)
{
    std::map<long, int> counts;
    for (double g : gaps)
        ++counts[std::lround(g * 100)];
    std::vector<std::pair<int, long>> order;
    for (auto [g, n] : counts)
        order.emplace_back(n, g);
    std::sort(order.rbegin(), order.rend());
    std::string out;
    for (std::size_t i = 0; i < order.size() && i < 4; ++i)
        out += (i ? ", " : "") + std::to_string(order[i].first) + (i ? " of " : " gaps of ") +
               mm(static_cast<double>(order[i].second) / 100);
    if (order.size() > 4)
        out += ", ...";
    return out;
}

} // namespace

Vec3 slice_normal(const std::array<double, 6> &o)
{
    const Vec3 r = {o[0], o[1], o[2]};
    const Vec3 c = {o[3], o[4], o[5]};
    if (std::abs(dot(r, r) - 1) > 1e-3 || std::abs(dot(c, c) - 1) > 1e-3 || std::abs(dot(r, c)) > 1e-3)
        throw std::runtime_error("Image Orientation (Patient) is not two orthogonal unit vectors");
    Vec3 n = {r[1] * c[2] - r[2] * c[1], r[2] * c[0] - r[0] * c[2], r[0] * c[1] - r[1] * c[0]};
    const double len = std::sqrt(dot(n, n));
    for (double &x : n)
        x /= len;
    return n;
}

SliceStack plan_slice_stack(const std::vector<Vec3> &positions, const std::array<double, 6> &orientation,
                            const std::array<double, 2> &pixel_spacing, double single_spacing,
                            const StackPolicy &policy)
{
    if (positions.empty())
        throw std::runtime_error("no frames to stack");
    SliceStack stack;
    stack.normal = slice_normal(orientation);
    const Vec3 &n = stack.normal;
    const std::size_t count = positions.size();
    std::vector<std::size_t> order(count);
    std::iota(order.begin(), order.end(), 0);
    std::vector<double> z(count);
    for (std::size_t i = 0; i < count; ++i)
        z[i] = dot(positions[i], n);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return z[a] < z[b]; });

    stack.origin = positions[order[0]];
    if (count == 1) {
        stack.spacing = single_spacing;
        stack.slices.push_back({order[0], order[0], 0.0});
        return stack;
    }

    std::vector<double> gaps(count - 1);
    for (std::size_t i = 0; i + 1 < count; ++i)
        gaps[i] = z[order[i + 1]] - z[order[i]];
    std::vector<double> sorted = gaps;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double typical = sorted[sorted.size() / 2];

    // Two frames at one position: several acquisitions, echoes or phases.
    const double same = std::max(1e-3, 0.05 * typical);
    std::size_t crowded = 0; // positions holding more than one frame
    for (std::size_t i = 0; i < gaps.size(); ++i)
        if (gaps[i] < same && (i == 0 || gaps[i - 1] >= same))
            ++crowded;
    if (crowded > 0 || !(typical > 0))
        throw std::runtime_error(
            std::to_string(std::max<std::size_t>(crowded, 1)) + " slice position(s) hold more than one image (" +
            std::to_string(count) + " images in all; several acquisitions, echoes or time points "
            "in one series?); cannot stack them into one volume");

    const double tolerance = std::max(0.005, 0.02 * typical);
    std::vector<std::size_t> missing; // indices of gaps that skip slices
    bool irregular = false;
    for (std::size_t i = 0; i < gaps.size(); ++i) {
        if (gaps[i] > 1.5 * typical)
            missing.push_back(i);
        else if (std::abs(gaps[i] - typical) > tolerance)
            irregular = true;
    }
    const double extent = z[order.back()] - z[order.front()];

    if (!missing.empty()) {
        long absent = 0;
        for (std::size_t i : missing)
            absent += std::lround(gaps[i] / typical) - 1;
        const std::size_t first = missing.front();
        const std::string where = "between positions " + mm(z[order[first]]) + " and " +
                                  mm(z[order[first + 1]]) + " along the normal (a gap of " +
                                  mm(gaps[first]) + " where slices are " + mm(typical) + " apart)";
        const std::string what = "about " + std::to_string(absent) + " slice(s) missing in " +
                                 std::to_string(missing.size()) + " gap(s), first " + where;
        if (!policy.fill_missing)
            throw std::runtime_error(what + "; refused, because filling them would invent data "
                                            "(choose missing-slices = interpolate to fill them by "
                                            "linear interpolation)");
        stack.notes.push_back(what + "; filled by linear interpolation");
    }
    if (irregular && !policy.resample_irregular)
        throw std::runtime_error("slice gaps are irregular (" + gap_histogram(gaps) +
                                 "); refused (choose irregular-slices = resample to resample them)");

    if (irregular || !missing.empty()) {
        const long m = std::lround(extent / typical) + 1;
        stack.spacing = extent / static_cast<double>(m - 1);
        std::size_t j = 0;
        for (long k = 0; k < m; ++k) {
            const double zk = z[order.front()] + static_cast<double>(k) * stack.spacing;
            while (j + 2 < count && z[order[j + 1]] <= zk)
                ++j;
            const double za = z[order[j]], zb = z[order[j + 1]];
            double t = std::clamp((zk - za) / (zb - za), 0.0, 1.0);
            if (t < 1e-6)
                stack.slices.push_back({order[j], order[j], 0.0});
            else if (t > 1 - 1e-6)
                stack.slices.push_back({order[j + 1], order[j + 1], 0.0});
            else
                stack.slices.push_back({order[j], order[j + 1], t});
        }
        if (irregular)
            stack.notes.push_back("slice gaps are irregular (" + gap_histogram(gaps) + "); resampled to " +
                                  std::to_string(m) + " slices " + number(stack.spacing) +
                                  " mm apart by linear interpolation along the slice normal");
    } else {
        stack.spacing = extent / static_cast<double>(count - 1);
        for (std::size_t i : order)
            stack.slices.push_back({i, i, 0.0});
    }

    // Gantry tilt: frames slide in-plane as they go along the normal.
    const Vec3 r = {orientation[0], orientation[1], orientation[2]};
    const Vec3 c = {orientation[3], orientation[4], orientation[5]};
    std::vector<std::array<double, 2>> offsets(count);
    double largest = 0.0, largest_pixels = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
        Vec3 d;
        for (int a = 0; a < 3; ++a)
            d[static_cast<std::size_t>(a)] = positions[i][static_cast<std::size_t>(a)] -
                                             stack.origin[static_cast<std::size_t>(a)];
        offsets[i] = {dot(d, r), dot(d, c)};
        const double len = std::hypot(offsets[i][0], offsets[i][1]);
        largest = std::max(largest, len);
        largest_pixels = std::max(largest_pixels, std::max(std::abs(offsets[i][0]) / pixel_spacing[1],
                                                           std::abs(offsets[i][1]) / pixel_spacing[0]));
    }
    if (largest_pixels > 0.05) {
        const double degrees = std::atan2(largest, extent) * 180.0 / 3.14159265358979323846;
        const std::string what = "gantry tilt of about " + number(degrees) +
                                 " degrees (slices shifted in-plane by up to " + mm(largest) + ")";
        if (!policy.correct_tilt)
            throw std::runtime_error(what + "; refused (choose gantry-tilt = correct to shift each "
                                            "slice back)");
        stack.frame_offsets = std::move(offsets);
        stack.notes.push_back(what + "; corrected by shifting each slice back in-plane with bilinear "
                                     "interpolation onto an orthogonal grid (voxels shifted in from "
                                     "outside the scan take the lowest value)");
    }
    return stack;
}

} // namespace arbor::dicom
