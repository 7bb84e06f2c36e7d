// denoise_filters.cpp - the OpenCV denoising filters, run before the contour
// tree is built so that noise does not become hundreds of thousands of
// branches (thesis §7.5):
//   org.arbor.filter.gaussian   3D Gaussian, separable, sigma in mm
//   org.arbor.filter.median     median per axial slice (3D medians: OpenCV has none)
//   org.arbor.filter.bilateral  bilateral per axial slice (edge-preserving)
//   org.arbor.filter.nlmeans    non-local means per axial slice, 8- and 16-bit
// Every filter keeps the voxel type, so the contour tree sees the same kind
// of values.
#include "slice_access.hpp"

#include <arbor/sdk/filter.hpp>
#include <arbor/sdk/instance.hpp>

#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace arbor::opencv_filters {

namespace {

constexpr arbor_plugin_descriptor descriptor(const char *id, const char *name, const char *description)
{
    return {sizeof(arbor_plugin_descriptor), ARBOR_PLUGIN_FLAG_NONE, id, ARBOR_KIND_FILTER, name, "1.0.0", "Arbor",
            description, ""};
}

const arbor_plugin_descriptor kGaussian = descriptor(
    "org.arbor.filter.gaussian", "Gaussian (3D)",
    "Separable 3D Gaussian smoothing with a standard deviation in millimetres, so anisotropic voxels are smoothed "
    "evenly in space.");
const arbor_plugin_descriptor kMedian = descriptor(
    "org.arbor.filter.median", "Median (per slice)",
    "Median of each voxel's square neighbourhood in its axial slice: removes speckle and keeps edges.");
const arbor_plugin_descriptor kBilateral = descriptor(
    "org.arbor.filter.bilateral", "Bilateral (per slice)",
    "Edge-preserving smoothing in each axial slice: neighbours count by distance and by value difference.");
const arbor_plugin_descriptor kNlMeans = descriptor(
    "org.arbor.filter.nlmeans", "Non-local means (per slice)",
    "Non-local means denoising of each axial slice (8- and 16-bit volumes): averages similar patches.");

// Runs body(i) for i in [0, count) on every core: this thread and one
// helper per further core take the next i in turn; this thread reports
// progress from `from` to `from + span` before each of its steps (and so is
// cancelled there).  The first exception stops the others' next steps and
// is rethrown here.  Plain threads, joined before returning, rather than
// OpenCV's or TBB's pools: their hand-over is visible to ThreadSanitizer
// in the host's tests.
template <class F>
void parallel_steps(int64_t count, const sdk::Task &task, const char *stage, double from, double span, F &&body)
{
    std::atomic<int64_t> next{0};
    std::atomic<bool> stop{false};
    std::mutex failed;
    std::exception_ptr error;
    const auto work = [&](bool reporting) {
        try {
            for (int64_t i = next++; i < count && !stop; i = next++) {
                if (reporting)
                    task.progress(from + span * static_cast<double>(i) / static_cast<double>(count), stage);
                body(i);
            }
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failed);
            if (!error)
                error = std::current_exception();
            stop = true;
        }
    };
    {
        const int64_t cores = std::max(1u, std::thread::hardware_concurrency());
        const int64_t helpers = std::min<int64_t>(count - 1, cores - 1);
        std::vector<std::jthread> threads;
        for (int64_t t = 0; t < helpers; ++t)
            threads.emplace_back(work, false);
        work(true);
    } // joined
    if (error)
        std::rethrow_exception(error);
}

// Runs `per_slice` on every axial slice, in parallel, with progress and
// cancellation.
template <class F>
void each_slice(const arbor_volume &in, arbor_volume &out, const sdk::Task &task, const char *stage, F &&per_slice)
{
    parallel_steps(in.dims[2], task, stage, 0.0, 1.0,
                   [&](int64_t k) { write_slice(out, k, per_slice(read_slice(in, k))); });
}

class Gaussian final : public sdk::Filter {
public:
    explicit Gaussian(const arbor_host *host)
        : Filter(kGaussian, host,
                 {sdk::ParamSpec::real("sigma", "Sigma", 1.0, 0.0, 100.0)
                      .unit("mm")
                      .hint("Standard deviation of the Gaussian, the same in every direction")})
    {
    }
    arbor_voxel_type output_type(const arbor_volume &in) override { return in.voxel_type; }
    void apply(const arbor_volume &in, arbor_volume &out, const sdk::Task &task) override
    {
        const double sigma = params().number("sigma");
        const auto kernel = [&](double spacing) {
            const double s = sigma / spacing; // in voxels
            const int half = std::max(1, static_cast<int>(std::ceil(3 * s)));
            return s > 0 ? cv::getGaussianKernel(2 * half + 1, s, CV_32F) : cv::Mat(1, 1, CV_32F, cv::Scalar(1));
        };
        const cv::Mat kx = kernel(in.spacing[0]), ky = kernel(in.spacing[1]), kz = kernel(in.spacing[2]);
        const int64_t nx = in.dims[0], ny = in.dims[1], nz = in.dims[2];
        // In-plane passes per slice into a float volume, then the z pass on
        // the volume seen as an nz x (nx*ny) matrix.
        // Slices, and column blocks of the z pass, go to all cores.
        cv::Mat volume(static_cast<int>(nz), static_cast<int>(nx * ny), CV_32F);
        parallel_steps(nz, task, "gaussian in-plane", 0.0, 0.6, [&](int64_t k) {
            cv::Mat s;
            read_slice(in, k).convertTo(s, CV_32F);
            cv::sepFilter2D(s, s, CV_32F, kx, ky, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
            std::memcpy(volume.ptr(static_cast<int>(k)), s.ptr(), sizeof(float) * nx * ny);
        });
        const cv::Mat one(1, 1, CV_32F, cv::Scalar(1));
        constexpr int64_t kColumns = 4096; // per block: nz x 4096 floats
        const int64_t blocks = (nx * ny + kColumns - 1) / kColumns;
        parallel_steps(blocks, task, "gaussian along slices", 0.6, 0.25, [&](int64_t b) {
            const int first = static_cast<int>(b * kColumns);
            cv::Mat block = volume.colRange(first, static_cast<int>(std::min(nx * ny, (b + 1) * kColumns)));
            // Isolated: a block's edges are not filtered into its neighbours
            // (the 1 x 1 row kernel reads no neighbour columns anyway).
            cv::sepFilter2D(block, block, CV_32F, one, kz, cv::Point(-1, -1), 0,
                            cv::BORDER_REPLICATE | cv::BORDER_ISOLATED);
        });
        const int depth = cv_depth(in.voxel_type);
        parallel_steps(nz, task, "gaussian", 0.85, 0.15, [&](int64_t k) {
            cv::Mat s(static_cast<int>(ny), static_cast<int>(nx), CV_32F, volume.ptr(static_cast<int>(k))), typed;
            s.convertTo(typed, CV_MAKETYPE(depth, 1)); // rounds and saturates integer types
            write_slice(out, k, typed);
        });
    }
};

class Median final : public sdk::Filter {
public:
    explicit Median(const arbor_host *host)
        : Filter(kMedian, host,
                 {sdk::ParamSpec::integer("size", "Window", 3, 3, 255)
                      .unit("voxels")
                      .hint("Odd window width; 16-bit and float volumes allow 3 or 5 (OpenCV)")})
    {
    }
    arbor_voxel_type output_type(const arbor_volume &in) override { return in.voxel_type; }
    void apply(const arbor_volume &in, arbor_volume &out, const sdk::Task &task) override
    {
        const int size = static_cast<int>(params().integer("size"));
        if (size % 2 == 0)
            sdk::fail(ARBOR_ERROR_OUT_OF_RANGE, "size must be odd");
        const int depth = cv_depth(in.voxel_type);
        if (depth != CV_8U && !(size <= 5 && (depth == CV_16U || depth == CV_16S || depth == CV_32F)))
            sdk::fail(ARBOR_ERROR_UNSUPPORTED, "OpenCV's median takes windows above 5 for 8-bit volumes only, and "
                                               "no " + std::string(arbor_voxel_type_name(in.voxel_type)) + " windows");
        each_slice(in, out, task, "median", [&](const cv::Mat &s) {
            cv::Mat r, f = s;
            if (depth == CV_16S) // medianBlur has no 16S: shift into 16U and back
                s.convertTo(f, CV_16U, 1.0, 32768.0);
            cv::medianBlur(f, r, size);
            if (depth == CV_16S)
                r.convertTo(r, CV_16S, 1.0, -32768.0);
            return r;
        });
    }
};

class Bilateral final : public sdk::Filter {
public:
    explicit Bilateral(const arbor_host *host)
        : Filter(kBilateral, host,
                 {sdk::ParamSpec::real("sigma-space", "Spatial sigma", 1.5, 0.1, 50.0)
                      .unit("voxels")
                      .hint("How far neighbours reach"),
                  sdk::ParamSpec::real("sigma-value", "Value sigma", 0.05, 1e-6, 1.0)
                      .hint("Value difference that halves a neighbour's weight, as a fraction of the volume's range")})
    {
    }
    arbor_voxel_type output_type(const arbor_volume &in) override { return in.voxel_type; }
    void apply(const arbor_volume &in, arbor_volume &out, const sdk::Task &task) override
    {
        // The value range, for a sigma that means the same on every volume.
        double lo = INFINITY, hi = -INFINITY;
        for (int64_t k = 0; k < in.dims[2]; ++k) {
            double a, b;
            cv::Mat s;
            read_slice(in, k).convertTo(s, CV_32F);
            cv::minMaxLoc(s, &a, &b);
            lo = std::min(lo, a);
            hi = std::max(hi, b);
        }
        const double sigma_value = params().number("sigma-value") * std::max(hi - lo, 1e-9);
        const double sigma_space = params().number("sigma-space");
        const int depth = cv_depth(in.voxel_type);
        each_slice(in, out, task, "bilateral", [&](const cv::Mat &s) {
            cv::Mat f, r, typed;
            s.convertTo(f, CV_32F); // bilateralFilter takes 8U and 32F
            cv::bilateralFilter(f, r, -1, sigma_value, sigma_space, cv::BORDER_REPLICATE);
            r.convertTo(typed, CV_MAKETYPE(depth, 1));
            return typed;
        });
    }
};

class NlMeans final : public sdk::Filter {
public:
    explicit NlMeans(const arbor_host *host)
        : Filter(kNlMeans, host,
                 {sdk::ParamSpec::real("h", "Strength h", 0.05, 1e-6, 1.0)
                      .hint("Filter strength as a fraction of the volume's range: larger removes more noise and "
                            "detail"),
                  sdk::ParamSpec::integer("patch", "Patch", 5, 3, 21).unit("voxels").hint("Odd patch width"),
                  sdk::ParamSpec::integer("search", "Search window", 15, 5, 51)
                      .unit("voxels")
                      .hint("Odd width of the window searched for similar patches")})
    {
    }
    arbor_voxel_type output_type(const arbor_volume &in) override { return in.voxel_type; }
    void apply(const arbor_volume &in, arbor_volume &out, const sdk::Task &task) override
    {
        if (in.voxel_type != ARBOR_VOXEL_U8 && in.voxel_type != ARBOR_VOXEL_U16)
            sdk::fail(ARBOR_ERROR_UNSUPPORTED, std::string("non-local means takes 8- and 16-bit unsigned volumes "
                                                           "(OpenCV), not ") + arbor_voxel_type_name(in.voxel_type));
        double max_value = 0;
        for (int64_t k = 0; k < in.dims[2]; ++k) {
            double a, b;
            cv::minMaxLoc(read_slice(in, k), &a, &b);
            max_value = std::max(max_value, b);
        }
        const float h = static_cast<float>(params().number("h") * std::max(max_value, 1.0));
        const int patch = static_cast<int>(params().integer("patch")) | 1,
                  search = static_cast<int>(params().integer("search")) | 1;
        each_slice(in, out, task, "non-local means", [&](const cv::Mat &s) {
            cv::Mat r;
            const std::vector<float> hs{h};
            cv::fastNlMeansDenoising(s, r, hs, patch, search, cv::NORM_L1);
            return r;
        });
    }
};

template <class T>
sdk::Instance *make(const arbor_host *host)
{
    return new T(host);
}

const sdk::PluginClass kFilters[] = {
    {&kGaussian, &make<Gaussian>},
    {&kMedian, &make<Median>},
    {&kBilateral, &make<Bilateral>},
    {&kNlMeans, &make<NlMeans>},
};

} // namespace

} // namespace arbor::opencv_filters

namespace {
using arbor::opencv_filters::kFilters;
} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kFilters)
