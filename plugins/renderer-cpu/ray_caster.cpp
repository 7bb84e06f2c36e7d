// ray_caster.cpp - org.arbor.renderer.cpu-raycast: emission-absorption ray
// casting on the CPU.  Front to back; trilinear values; post-classification
// with the transfer function of the label of the nearest voxel (so equal
// values in different structures get different colours); opacity corrected
// for the sample distance; Blinn-Phong shading with a headlight from
// per-voxel gradient directions; early ray termination; empty-space
// skipping over 8^3 blocks.  arbor.renderer/2: regions of a frame, a
// coarse pass for interaction (a ray per n x n pixels, n chosen to reach a
// frame rate, interpolated, at twice the step, through a half-resolution
// copy of large volumes), supersampling while idle; tiles of rows on a persistent
// oneTBB pool, cancellable within a tile.  What a new set of transfer
// functions costs is O(blocks) (block statistics are built per volume and
// labels revision) plus the boundary-emphasis reference (a sample of
// voxels).
#include "cancellation.hpp"
#include "classification.hpp"
#include "voxel_grid.hpp"

#include <arbor/sdk/renderer.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <thread>

namespace arbor::raycast {

extern const arbor_plugin_descriptor kRayCasterDescriptor;

const arbor_plugin_descriptor kRayCasterDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.renderer.cpu-raycast",
    ARBOR_KIND_RENDERER,
    "CPU ray caster",
    "1.0.0",
    "Arbor",
    "Emission-absorption ray casting on all CPU cores with label-aware post-classification, Blinn-Phong "
    "shading, early ray termination and empty-space skipping; tiles, a coarse pass and supersampling for "
    "interaction (arbor.renderer/2).",
    "",
};

namespace {

struct Ray {
    Vec3 origin, direction; // LPS mm; direction unit length
};

// Pixel (x, y) -> ray, row 0 at the top.
class Camera {
public:
    Camera(const arbor_camera &c, uint32_t width, uint32_t height) : c_(c)
    {
        f_ = normalize({c.focal_point[0] - c.position[0], c.focal_point[1] - c.position[1],
                        c.focal_point[2] - c.position[2]});
        r_ = normalize(cross(f_, {c.view_up[0], c.view_up[1], c.view_up[2]}));
        if (!(std::hypot(r_[0], r_[1], r_[2]) > 0.5)) // view-up along the view direction
            r_ = normalize(cross(f_, std::fabs(f_[2]) < 0.9 ? Vec3{0, 0, 1} : Vec3{0, 1, 0}));
        u_ = cross(r_, f_);
        aspect_ = static_cast<double>(width) / height;
        width_ = width;
        height_ = height;
        half_ = c.projection == ARBOR_PROJECTION_PERSPECTIVE ? std::tan(c.view_angle * M_PI / 360.0) : c.parallel_scale;
    }

    // The ray through frame position (px, py) in pixels: pixel (x, y)
    // spans [x, x + 1) x [y, y + 1), its centre is (x + 0.5, y + 0.5).
    Ray ray(double px, double py) const
    {
        const double sx = (2.0 * px / width_ - 1.0) * aspect_ * half_;
        const double sy = (1.0 - 2.0 * py / height_) * half_;
        const Vec3 p{c_.position[0], c_.position[1], c_.position[2]};
        if (c_.projection == ARBOR_PROJECTION_PERSPECTIVE)
            return {p, normalize({f_[0] + sx * r_[0] + sy * u_[0], f_[1] + sx * r_[1] + sy * u_[1],
                                  f_[2] + sx * r_[2] + sy * u_[2]})};
        return {{p[0] + sx * r_[0] + sy * u_[0], p[1] + sx * r_[1] + sy * u_[1], p[2] + sx * r_[2] + sy * u_[2]}, f_};
    }

    static Vec3 cross(const Vec3 &a, const Vec3 &b)
    {
        return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    }
    static Vec3 normalize(const Vec3 &v)
    {
        const double l = std::hypot(v[0], v[1], v[2]);
        return l > 0 ? Vec3{v[0] / l, v[1] / l, v[2] / l} : v;
    }

private:
    arbor_camera c_;
    Vec3 f_{}, r_{}, u_{};
    double aspect_ = 1, half_ = 1;
    uint32_t width_ = 1, height_ = 1;
};

struct Shading {
    bool enabled = true;
    float ambient = 0.3f, diffuse = 0.7f;
    // specular * ndl^shininess for ndl = i / 256: no pow() per sample.
    std::array<float, 258> highlight{};

    void tabulate(float specular, float shininess)
    {
        for (std::size_t i = 0; i < highlight.size(); ++i)
            highlight[i] = specular * std::pow(std::min(1.0f, i / 256.0f), shininess);
    }
};

// FNV-1a over the bytes of the transfer functions: the occupancy grid is
// rebuilt when they change.
uint64_t fingerprint(const arbor_tf_set &tf, double step)
{
    uint64_t h = 1469598103934665603ull;
    const auto mix = [&](const void *p, std::size_t n) {
        const auto *b = static_cast<const unsigned char *>(p);
        for (std::size_t i = 0; i < n; ++i)
            h = (h ^ b[i]) * 1099511628211ull;
    };
    mix(tf.domain, sizeof(double) * 2 * tf.branch_count);
    mix(tf.lut, sizeof(float) * 4 * tf.lut_size * tf.branch_count);
    mix(&tf.opacity_unit_distance, sizeof(double));
    mix(&step, sizeof step);
    return h;
}

// One ray's result.
struct Sample {
    float rgba[4];
    float depth;
};

// Where the passes put their rays.
// Pixels per coarse ray (along each side): 4 until timings say otherwise,
// then one of 2, 2.5, ... 8.
constexpr double kCoarseStart = 4, kCoarseMin = 2, kCoarseMax = 8, kCoarseStepBy = 0.5;
constexpr double kCoarseStep = 2.0;    // at this many times the full step
constexpr uint32_t kRows = 8;          // rows per tile of work
constexpr int64_t kHalfFrom = int64_t{1} << 22; // voxels from which the coarse pass samples a half-resolution grid

// The R2 sequence (Roberts): well spread offsets within a pixel for the
// supersample passes.
std::array<double, 2> subpixel(uint32_t n)
{
    constexpr double g = 1.32471795724474602596, a1 = 1.0 / g, a2 = 1.0 / (g * g);
    return {std::fmod(0.5 + a1 * n, 1.0), std::fmod(0.5 + a2 * n, 1.0)};
}

// Per worker of the arena: what its rays contributed to each label.
using Slots = std::vector<std::vector<double>>;
std::vector<double> &slot(Slots &slots)
{
    const int i = tbb::this_task_arena::current_thread_index();
    return slots[static_cast<std::size_t>(i >= 0 ? i : 0) % slots.size()];
}

class RayCaster final : public sdk::Renderer {
public:
    explicit RayCaster(const arbor_host *host)
        : Renderer(kRayCasterDescriptor, host,
                   {sdk::ParamSpec::real("sample-distance", "Sample distance", 0.5, 0.01, 10.0)
                        .unit("voxels")
                        .hint("Distance between samples along a ray, in units of the smallest voxel spacing"),
                    sdk::ParamSpec::boolean("shading", "Shading", true)
                        .hint("Blinn-Phong shading from the gradient, lit from the camera"),
                    sdk::ParamSpec::real("ambient", "Ambient", 0.3, 0.0, 1.0).group("Shading"),
                    sdk::ParamSpec::real("diffuse", "Diffuse", 0.7, 0.0, 1.0).group("Shading"),
                    sdk::ParamSpec::real("specular", "Specular", 0.25, 0.0, 1.0).group("Shading"),
                    sdk::ParamSpec::real("shininess", "Shininess", 24.0, 1.0, 256.0).group("Shading"),
                    sdk::ParamSpec::real("boundary-emphasis", "Boundary emphasis", 0.8, 0.0, 1.0)
                        .hint("Scale opacity by the steepness of the field (gradient magnitude), so structures read "
                              "as surfaces and homogeneous interiors thin out; 0 turns it off"),
                    sdk::ParamSpec::real("ambient-occlusion", "Ambient occlusion", 0.0, 0.0, 1.0)
                        .group("Shading")
                        .hint("Darken samples by how filled with opacity the space around them is (local ambient "
                              "occlusion): crevices and folds read without shadows; 0 turns it off"),
                    sdk::ParamSpec::real("termination", "Early termination opacity", 0.99, 0.5, 1.0)
                        .hint("A ray stops once its accumulated opacity reaches this"),
                    sdk::ParamSpec::boolean("jitter", "Jitter", true)
                        .hint("Offset each ray's first sample by a per-pixel fraction of a step: noise instead "
                              "of wood-grain rings"),
                    sdk::ParamSpec::integer("threads", "Threads", 0, 0, 256)
                        .hint("Worker threads; 0 uses every core"),
                    sdk::ParamSpec::real("coarse-rate", "Coarse frame rate", 22.0, 1.0, 240.0)
                        .unit("frames/s")
                        .group("Interaction")
                        .hint("The coarse pass (while the user drags) chooses how many pixels share a ray, from "
                              "2 x 2 to 8 x 8 in steps of half a pixel, to reach this rate, from the time its last "
                              "whole frames took"),
                    sdk::ParamSpec::integer("coarse-pixels", "Coarse pixels per ray", 0, 0, 16)
                        .group("Interaction")
                        .hint("A fixed n: one coarse ray per n x n pixels; 0 chooses n from the coarse frame rate")},
                   Interface::v2)
    {
    }

    void render_region(const arbor_render_request_v2 &request, arbor_image &out, const sdk::Task &task) override
    {
        const VoxelGrid &g = prepare(request, task);
        Shading shading;
        shading.enabled = params().flag("shading");
        shading.ambient = static_cast<float>(params().number("ambient"));
        shading.diffuse = static_cast<float>(params().number("diffuse"));
        shading.tabulate(static_cast<float>(params().number("specular")), static_cast<float>(params().number("shininess")));
        Pass pass;
        const bool coarse = request.pass == ARBOR_RENDER_PASS_COARSE;
        const bool half = coarse && !half_.value.empty();
        pass.grid = half ? &half_ : &g;
        pass.occupancy = half ? &half_occupancy_ : &occupancy_;
        pass.occlusion = half ? 0.0f : shading_occlusion_;
        pass.shading = &shading;
        pass.camera = std::make_unique<Camera>(*request.camera, request.frame_width, request.frame_height);
        pass.termination = static_cast<float>(params().number("termination"));
        pass.jitter = params().flag("jitter");
        pass.background = request.background;
        pass.coarse = coarse;
        pass.step = step_ * (pass.coarse ? kCoarseStep : 1.0);
        pass.table = pass.coarse ? &coarse_table_ : &table_;
        pass.sample_index = request.pass == ARBOR_RENDER_PASS_SUPERSAMPLE ? request.sample_index : 0;

        const unsigned threads = params().integer("threads") > 0 ? static_cast<unsigned>(params().integer("threads"))
                                                                 : std::max(1u, std::thread::hardware_concurrency());
        if (!arena_ || arena_threads_ != threads) {
            arena_ = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
            arena_threads_ = threads;
        }
        // Visibility per worker slot of the arena, allocated here: the pool's
        // threads allocate nothing.
        Slots visibility(static_cast<std::size_t>(arena_->max_concurrency()),
                         std::vector<double>(table_.labels(), 0.0));
        Cancellation cancel(task);
        // The coarse pass's pixels per ray: fixed, or what reaches the rate
        // judged by the frame before.  It changes only at a call whose
        // region starts at (0, 0), the first tile of a frame: the tiles of
        // one frame agree.
        const bool adaptive = params().integer("coarse-pixels") == 0;
        if (coarse && adaptive && request.region_x == 0 && request.region_y == 0 && frame_pixels_ > 0) {
            adapt_coarse(frame_seconds_ * request.frame_width * request.frame_height / frame_pixels_,
                         1.0 / params().number("coarse-rate"));
            frame_seconds_ = frame_pixels_ = 0;
        }
        pass.pixels = adaptive ? coarse_pixels_ : static_cast<double>(params().integer("coarse-pixels"));
        const auto started = std::chrono::steady_clock::now();
        arena_->execute([&] {
            if (pass.coarse)
                render_coarse(pass, request, out, cancel, visibility);
            else
                render_pixels(pass, request, out, cancel, visibility);
        });
        task.throw_if_cancelled();
        if (coarse) {
            frame_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            frame_pixels_ += static_cast<double>(out.width) * out.height;
        }
        if (ARBOR_HAS_FIELD(arbor_image, out.struct_size, label_visibility_count) && out.label_visibility) {
            std::vector<double> sum(table_.labels(), 0.0);
            for (const std::vector<double> &v : visibility)
                for (std::size_t l = 0; l < v.size(); ++l)
                    sum[l] += v[l];
            for (uint32_t l = 0; l < out.label_visibility_count; ++l)
                out.label_visibility[l] = l < sum.size() ? sum[l] : 0.0;
        }
    }

private:
    // After a coarse frame that took `seconds`: the fewest pixels per
    // ray whose frames are predicted to take at most `budget` (a frame's
    // time goes with its rays, 1 / n^2).  A smoothed time, so one slow frame
    // does not make the picture jump.
    void adapt_coarse(double seconds, double budget)
    {
        const double n = coarse_pixels_;
        coarse_seconds_ = coarse_seconds_ > 0 ? 0.5 * coarse_seconds_ + 0.5 * seconds : seconds;
        const double per_ray_area = coarse_seconds_ * n * n; // the frame's time at one ray per pixel
        double next = kCoarseMax;
        for (double m = kCoarseMin; m <= kCoarseMax; m += kCoarseStepBy)
            if (per_ray_area / (m * m) <= budget) {
                next = m;
                break;
            }
        if (next != coarse_pixels_) {
            coarse_seconds_ *= (n * n) / (next * next);
            coarse_pixels_ = next;
        }
    }

    struct Pass {
        double pixels = kCoarseStart; // COARSE: one ray per pixels x pixels
        const VoxelGrid *grid = nullptr;
        const Occupancy *occupancy = nullptr;
        float occlusion = 0.0f; // ambient occlusion's strength (full resolution only)
        const Shading *shading = nullptr;
        const ClassTable *table = nullptr;
        std::unique_ptr<Camera> camera;
        float termination = 0.99f;
        bool jitter = true, coarse = false;
        double step = 1.0;
        const float *background = nullptr;
        uint32_t sample_index = 0; // supersampling: which offset within the pixel
    };

    // Brings every derived structure up to date with the request: the grid
    // (volume, labels), the block statistics, then what the transfer
    // functions decide (tables, empty blocks, boundary emphasis, occlusion).
    const VoxelGrid &prepare(const arbor_render_request_v2 &request, const sdk::Task &task)
    {
        const VoxelGrid &g =
            grid_.update(*request.volume, request.volume_revision, request.labels, request.labels_revision, task);
        const arbor_tf_set &tf = *request.transfer_functions;
        if (g.max_label >= tf.branch_count)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "label " + std::to_string(g.max_label) +
                                                        " has no transfer function (" +
                                                        std::to_string(tf.branch_count) + " given)");
        const bool grid_changed = grid_.generation() != blocks_generation_;
        if (grid_changed) {
            blocks_generation_ = ~uint64_t{0};
            blocks_.build(g, task);
            // Large volumes get a half-resolution copy for the coarse pass:
            // an eighth of the memory its rays wander through.
            half_ = VoxelGrid{};
            if (g.nx * g.ny * g.nz >= kHalfFrom) {
                downsample(g, half_, task);
                half_blocks_.build(half_, task);
            }
            blocks_generation_ = grid_.generation();
        }
        const double step = params().number("sample-distance") * g.min_spacing;
        const double emphasis = params().number("boundary-emphasis");
        // The transfer functions' identity: their revision, or their bytes
        // when the host does not know it.
        const uint64_t print = request.transfer_functions_revision != 0
                                   ? request.transfer_functions_revision * 0x9E3779B97F4A7C15ull
                                   : fingerprint(tf, step) | 1;
        if (grid_changed || print != table_print_ || step != step_ || emphasis != emphasis_) {
            table_print_ = 0;
            table_.build(tf, step);
            coarse_table_.build(tf, step * kCoarseStep);
            occupancy_.build(blocks_, table_, {g.nx, g.ny, g.nz});
            if (!half_.value.empty())
                half_occupancy_.build(half_blocks_, coarse_table_, {half_.nx, half_.ny, half_.nz});
            boundaries_.build(g, table_, emphasis);
            occlusion_.clear();
            table_print_ = print;
            step_ = step;
            emphasis_ = emphasis;
        }
        const float occlusion = static_cast<float>(params().number("ambient-occlusion"));
        if (occlusion > 0 && !occlusion_.built())
            occlusion_.build(g, table_, boundaries_);
        shading_occlusion_ = occlusion_.built() ? occlusion : 0.0f;
        return g;
    }

    // FULL and SUPERSAMPLE: a ray per pixel, each pixel written once, when
    // its ray is done (so a cancelled call leaves old or final pixels).
    void render_pixels(const Pass &pass, const arbor_render_request_v2 &request, arbor_image &out,
                       Cancellation &cancel, Slots &visibility) const
    {
        const uint32_t tiles = (out.height + kRows - 1) / kRows;
        const int64_t depth_stride = depth_stride_of(out);
        std::atomic<uint32_t> done{0};
        const std::array<double, 2> offset = pass.sample_index ? subpixel(pass.sample_index) : std::array{0.5, 0.5};
        const float blend = pass.sample_index ? 1.0f / static_cast<float>(pass.sample_index + 1) : 1.0f;
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, tiles, 1), [&](const tbb::blocked_range<uint32_t> &r) {
            std::vector<double> &mine = slot(visibility);
            for (uint32_t t = r.begin(); t != r.end(); ++t) {
                for (uint32_t y = t * kRows; y < std::min(out.height, (t + 1) * kRows); ++y) {
                    if (cancel.stopped())
                        return;
                    for (uint32_t x = 0; x < out.width; ++x) {
                        const uint32_t fx = request.region_x + x, fy = request.region_y + y;
                        const Sample s = cast(pass, fx + offset[0], fy + offset[1], ray_offset(pass, fx, fy),
                                              mine.data());
                        float *px = out.rgba + static_cast<int64_t>(y) * out.row_stride + 4 * static_cast<int64_t>(x);
                        if (pass.sample_index) {
                            for (int c = 0; c < 4; ++c)
                                px[c] += blend * (s.rgba[c] - px[c]);
                        } else {
                            std::memcpy(px, s.rgba, sizeof s.rgba);
                            if (out.depth)
                                out.depth[static_cast<int64_t>(y) * depth_stride + x] = s.depth;
                        }
                    }
                }
                const uint32_t d = ++done;
                if ((d & 7) == 0)
                    cancel.progress(static_cast<double>(d) / tiles, "ray casting");
            }
        });
    }

    // COARSE: a ray per n x n block of the frame (at the
    // block's centre, so tiles agree), each pixel bilinear between the four
    // rays around it.  The rays are cast first; the pixels are written only
    // when all are done.
    void render_coarse(const Pass &pass, const arbor_render_request_v2 &request, arbor_image &out,
                       Cancellation &cancel, Slots &visibility) const
    {
        const double f = pass.pixels;
        const auto count = [&](uint32_t side) { return std::max<int64_t>(1, static_cast<int64_t>(std::ceil(side / f))); };
        const int64_t columns = count(request.frame_width), rows = count(request.frame_height);
        // The ray lattice position of frame pixel centre p: (p - f / 2) / f.
        const auto lattice = [&](double p, int64_t n) { return std::clamp((p - f / 2) / f, 0.0, double(n - 1)); };
        const int64_t m0 = static_cast<int64_t>(lattice(request.region_x + 0.5, columns)),
                      m1 = std::min<int64_t>(columns - 1,
                                             static_cast<int64_t>(lattice(request.region_x + out.width - 0.5, columns)) + 1),
                      n0 = static_cast<int64_t>(lattice(request.region_y + 0.5, rows)),
                      n1 = std::min<int64_t>(rows - 1,
                                             static_cast<int64_t>(lattice(request.region_y + out.height - 0.5, rows)) + 1);
        const int64_t w = m1 - m0 + 1, h = n1 - n0 + 1;
        std::vector<Sample> rays(static_cast<std::size_t>(w * h));
        // Each coarse ray stands for pixels^2 pixels of the frame; the
        // visibility is scaled to the region's pixels below.
        Slots raw(visibility.size(), std::vector<double>(table_.labels(), 0.0));
        tbb::parallel_for(tbb::blocked_range<int64_t>(0, h, 2), [&](const tbb::blocked_range<int64_t> &r) {
            std::vector<double> &mine = slot(raw);
            for (int64_t n = r.begin(); n != r.end(); ++n) {
                if (cancel.stopped())
                    return;
                for (int64_t m = 0; m < w; ++m) {
                    const double px = (m0 + m) * f + f / 2, py = (n0 + n) * f + f / 2;
                    rays[static_cast<std::size_t>(n * w + m)] =
                        cast(pass, px, py, ray_offset(pass, static_cast<uint32_t>(px), static_cast<uint32_t>(py)),
                             mine.data());
                }
            }
        });
        if (cancel.stopped())
            return;
        const double per_ray = static_cast<double>(out.width) * out.height / static_cast<double>(w * h);
        for (const std::vector<double> &v : raw)
            for (std::size_t l = 0; l < v.size(); ++l)
                visibility[0][l] += per_ray * v[l];
        const int64_t depth_stride = depth_stride_of(out);
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, out.height, kRows), [&](const tbb::blocked_range<uint32_t> &r) {
            for (uint32_t y = r.begin(); y != r.end(); ++y) {
                const double v = lattice(request.region_y + y + 0.5, rows) - static_cast<double>(n0);
                const int64_t b = std::min<int64_t>(static_cast<int64_t>(v), h - 1), b1 = std::min<int64_t>(b + 1, h - 1);
                const float fy = static_cast<float>(v - static_cast<double>(b));
                float *row = out.rgba + static_cast<int64_t>(y) * out.row_stride;
                for (uint32_t x = 0; x < out.width; ++x) {
                    const double u = lattice(request.region_x + x + 0.5, columns) - static_cast<double>(m0);
                    const int64_t a = std::min<int64_t>(static_cast<int64_t>(u), w - 1), a1 = std::min<int64_t>(a + 1, w - 1);
                    const float fx = static_cast<float>(u - static_cast<double>(a));
                    const Sample &s00 = rays[static_cast<std::size_t>(b * w + a)], &s10 = rays[static_cast<std::size_t>(b * w + a1)],
                                 &s01 = rays[static_cast<std::size_t>(b1 * w + a)], &s11 = rays[static_cast<std::size_t>(b1 * w + a1)];
                    for (int c = 0; c < 4; ++c) {
                        const float top = s00.rgba[c] + fx * (s10.rgba[c] - s00.rgba[c]);
                        const float bottom = s01.rgba[c] + fx * (s11.rgba[c] - s01.rgba[c]);
                        row[4 * x + c] = std::clamp(top + fy * (bottom - top), 0.0f, 1.0f);
                    }
                    if (out.depth) // the nearest ray's depth: depths do not interpolate across edges
                        out.depth[static_cast<int64_t>(y) * depth_stride + x] =
                            (fy < 0.5f ? (fx < 0.5f ? s00 : s10) : (fx < 0.5f ? s01 : s11)).depth;
                }
            }
        });
    }

    static int64_t depth_stride_of(const arbor_image &out)
    {
        return ARBOR_HAS_FIELD(arbor_image, out.struct_size, depth_stride) && out.depth_stride > 0
                   ? out.depth_stride
                   : static_cast<int64_t>(out.width);
    }

    // The fraction of a step the ray of frame pixel (x, y) starts at: fixed
    // per pixel (noise, not rings), moved on by each supersample.
    static double ray_offset(const Pass &pass, uint32_t x, uint32_t y)
    {
        if (!pass.jitter)
            return 0.0;
        const double h = pixel_hash(x, y);
        return pass.sample_index ? std::fmod(h + 0.61803398874989485 * pass.sample_index, 1.0) : h;
    }

    // The ray through frame position (px, py), its first sample `offset` of
    // a step past the lattice.  `visibility`: per label, what this ray's
    // samples of it contribute (T * alpha) is added.
    Sample cast(const Pass &pass, double px_frame, double py_frame, double offset_fraction, double *visibility) const
    {
        const VoxelGrid &g = *pass.grid;
        const Shading &shading = *pass.shading;
        const ClassTable &table = *pass.table;
        const Occupancy &occupancy = *pass.occupancy;
        const float termination = pass.termination;
        const double step = pass.step;
        const float *background = pass.background;
        const Ray ray = pass.camera->ray(px_frame, py_frame);
        // The ray in voxel index space, clipped to the box of voxel centres.
        const Vec3 o = mul(g.to_voxel, {ray.origin[0] - g.origin[0], ray.origin[1] - g.origin[1],
                                        ray.origin[2] - g.origin[2]});
        const Vec3 d = mul(g.to_voxel, ray.direction); // voxels per mm
        // Clipped to the box around the blocks that can be visible at all.
        const std::array<double, 3> &lo = occupancy.content_low(), &hi = occupancy.content_high();
        double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
            if (std::fabs(d[a]) < 1e-12) {
                if (o[a] < lo[a] || o[a] > hi[a])
                    t1 = -1;
                continue;
            }
            double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
            if (ta > tb)
                std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
        }
        float acc[4] = {0, 0, 0, 0};
        float depth = std::numeric_limits<float>::infinity();
        const float light[3] = {static_cast<float>(-ray.direction[0]), static_cast<float>(-ray.direction[1]),
                                static_cast<float>(-ray.direction[2])};
        // Start on the global sample lattice, so images do not shimmer as the
        // box is clipped, shifted by a fixed per-pixel fraction of a step.
        const double offset = offset_fraction * step;
        double t = std::ceil((t0 - offset) / step) * step + offset;
        const int64_t last_i = std::max<int64_t>(g.nx - 2, 0), last_j = std::max<int64_t>(g.ny - 2, 0),
                      last_k = std::max<int64_t>(g.nz - 2, 0);
        const bool labelled = !g.label.empty();
        while (t <= t1 && acc[3] < termination) {
            const double px = o[0] + t * d[0], py = o[1] + t * d[1], pz = o[2] + t * d[2];
            const int64_t i = std::min(static_cast<int64_t>(px), last_i);
            const int64_t j = std::min(static_cast<int64_t>(py), last_j);
            const int64_t k = std::min(static_cast<int64_t>(pz), last_k);
            if (occupancy.empty(i >> 3, j >> 3, k >> 3)) { // kBlock = 8
                t = skip_block(o, d, t, step, i, j, k);
                continue;
            }
            const float fx = static_cast<float>(px - i), fy = static_cast<float>(py - j), fz = static_cast<float>(pz - k);
            const float value = trilinear(g, i, j, k, fx, fy, fz);
            // The nearest voxel carries the label and the normal.
            const std::size_t nearest =
                labelled || shading.enabled || boundaries_.active()
                    ? g.index(i + (fx >= 0.5f && g.nx > 1), j + (fy >= 0.5f && g.ny > 1), k + (fz >= 0.5f && g.nz > 1))
                    : 0;
            const uint32_t label = labelled ? g.label[nearest] : 0u;
            const float *c = table.lookup(label, value);
            if (c[3] > 0.0f) {
                const float m = boundaries_.active() ? boundaries_.factor(g.gradient[nearest]) : 1.0f;
                const float alpha = c[3] * m;
                float r = c[0] * m, gr = c[1] * m, b = c[2] * m;
                if (shading.enabled) {
                    const int8_t *nv = &g.normal[3 * nearest];
                    if (nv[0] | nv[1] | nv[2]) {
                        const float nx = nv[0] / 127.0f, ny = nv[1] / 127.0f, nz = nv[2] / 127.0f;
                        const float ndl = std::fabs(nx * light[0] + ny * light[1] + nz * light[2]);
                        // Headlight: the half vector is the light direction.
                        const float spec = shading.highlight[static_cast<std::size_t>(ndl * 256.0f)] * alpha;
                        float lit = shading.ambient + shading.diffuse * ndl;
                        if (pass.occlusion > 0)
                            lit *= 1.0f - pass.occlusion * occlusion_.at(i, j, k);
                        r = r * lit + spec;
                        gr = gr * lit + spec;
                        b = b * lit + spec;
                    }
                }
                const float w = 1.0f - acc[3];
                acc[0] += w * r;
                acc[1] += w * gr;
                acc[2] += w * b;
                acc[3] += w * alpha;
                visibility[label] += w * alpha;
                if (acc[3] >= 0.5f && depth == std::numeric_limits<float>::infinity())
                    depth = static_cast<float>(t); // rays start at the camera (plane): t is the distance
            }
            t += step;
        }
        Sample out;
        const float rest = 1.0f - acc[3];
        for (int ch = 0; ch < 3; ++ch)
            out.rgba[ch] = std::min(1.0f, acc[ch] + rest * background[ch] * background[3]);
        out.rgba[3] = std::min(1.0f, acc[3] + rest * background[3]);
        out.depth = depth;
        return out;
    }

    // A fixed pseudo-random number in [0, 1) per pixel (integer hash).
    static double pixel_hash(uint32_t x, uint32_t y)
    {
        uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u;
        h ^= h >> 15;
        h *= 0x2c1b3c6du;
        h ^= h >> 12;
        return (h & 0xffffff) / 16777216.0;
    }

    static float trilinear(const VoxelGrid &g, int64_t i, int64_t j, int64_t k, float fx, float fy, float fz)
    {
        const int64_t di = g.nx > 1 ? 1 : 0, dj = g.ny > 1 ? g.nx : 0, dk = g.nz > 1 ? g.nx * g.ny : 0;
        const float *v = &g.value[g.index(i, j, k)];
        const float c00 = v[0] + fx * (v[di] - v[0]);
        const float c10 = v[dj] + fx * (v[dj + di] - v[dj]);
        const float c01 = v[dk] + fx * (v[dk + di] - v[dk]);
        const float c11 = v[dk + dj] + fx * (v[dk + dj + di] - v[dk + dj]);
        const float c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
        return c0 + fz * (c1 - c0);
    }

    // The first lattice position past the block holding cell (i, j, k).
    static double skip_block(const Vec3 &o, const Vec3 &d, double t, double step, int64_t i, int64_t j, int64_t k)
    {
        const int64_t cell[3] = {i, j, k};
        double exit = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
            if (std::fabs(d[a]) < 1e-12)
                continue;
            const int64_t b = cell[a] / Occupancy::kBlock;
            const double bound = d[a] > 0 ? static_cast<double>((b + 1) * Occupancy::kBlock)
                                          : static_cast<double>(b * Occupancy::kBlock) - 1e-9;
            exit = std::min(exit, (bound - o[a]) / d[a]);
        }
        return std::max(t + step, std::ceil(exit / step) * step);
    }

    VoxelGridCache grid_;
    BlockStatistics blocks_;
    uint64_t blocks_generation_ = ~uint64_t{0};
    VoxelGrid half_; // empty below kHalfFrom voxels
    BlockStatistics half_blocks_;
    ClassTable table_, coarse_table_;
    Occupancy occupancy_, half_occupancy_;
    BoundaryEmphasis boundaries_;
    AmbientOcclusion occlusion_;
    float shading_occlusion_ = 0.0f;
    uint64_t table_print_ = 0;
    double step_ = -1.0, emphasis_ = -1.0;
    double coarse_pixels_ = kCoarseStart;
    double coarse_seconds_ = 0.0;              // smoothed time of a whole coarse frame
    double frame_seconds_ = 0, frame_pixels_ = 0; // the coarse frame being rendered, tile by tile
    std::unique_ptr<tbb::task_arena> arena_; // the pool the tiles run on (oneTBB's threads persist)
    unsigned arena_threads_ = 0;
};

} // namespace

sdk::Instance *create_ray_caster(const arbor_host *host)
{
    return new RayCaster(host);
}

} // namespace arbor::raycast
