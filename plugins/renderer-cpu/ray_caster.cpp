// ray_caster.cpp - org.arbor.renderer.cpu-raycast: emission-absorption ray
// casting on the CPU.  Front to back; trilinear values; post-classification
// with the transfer function of the sample's label, resolved by its value
// where its cell's voxels differ (so equal values in different structures
// get different colours, and structures meet along smooth isosurfaces);
// opacity corrected for the sample distance (and for the part of a step
// since the ray entered); Blinn-Phong shading with a headlight from the
// gradient at the sample, trilinear between the voxels'; early ray
// termination; empty-space skipping over 8^3 blocks.  arbor.renderer/2:
// regions of a frame, a coarse pass for interaction (a ray per n x n
// pixels, n chosen to reach a frame rate, interpolated, at twice the step),
// supersampling while idle; tiles of rows on a persistent oneTBB pool,
// cancellable within a tile.  On large volumes each ray prefetches the
// voxels a few samples ahead of it.  The sample loop is compiled once per
// kind of labels and gradient, so that a plain frame does not carry what a
// shaded, labelled one needs.
// What a new set of transfer functions costs is O(blocks) (block statistics
// are built per volume and labels revision) plus the boundary-emphasis
// reference (a sample of voxels).
#include "cancellation.hpp"
#include "cell_sample.hpp"
#include "classification.hpp"
#include "coarse_lattice.hpp"
#include "local_occlusion.hpp"
#include "optical_model.hpp"
#include "ray_geometry.hpp"
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

// The CPU ray caster's own parameters after the shared ones.
std::vector<sdk::ParamSpec> with_cpu_params(std::vector<sdk::ParamSpec> specs)
{
    specs.push_back(sdk::ParamSpec::integer("threads", "Threads", 0, 0, 256).hint("Worker threads; 0 uses every core"));
    return specs;
}

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

// Where the passes put their rays.
constexpr uint32_t kRows = 8; // rows per tile of work
// How many samples ahead a ray asks for the cache lines it will read: the
// loop itself keeps about two samples' loads in flight, so on a volume far
// larger than the caches it waited on memory (the CT head's coarse pass,
// 512 x 512 x 108: 88 ms a frame without, 67 ms with, on 2 cores).
constexpr double kAhead = 6;
// Rays prefetch on grids of at least this many voxels (values alone 16 MiB):
// on one the caches hold, prefetches only cost (6 % of a frame of a 64^3
// volume).
constexpr int64_t kPrefetchFrom = int64_t{1} << 22;

// Per tile of rays: what its rays contributed to each label.  Summed in
// tile order afterwards, so the sums (and the balance drawn from them) do
// not depend on which thread cast which tile.
using Slots = std::vector<std::vector<double>>;

void add_in_order(const Slots &slots, double scale, std::vector<double> &sum)
{
    for (const std::vector<double> &v : slots)
        for (std::size_t l = 0; l < v.size(); ++l)
            sum[l] += scale * v[l];
}

class RayCaster final : public sdk::Renderer {
public:
    explicit RayCaster(const arbor_host *host)
        : Renderer(kRayCasterDescriptor, host,
                   with_cpu_params(optical_model_params()), Interface::v2)
    {
        set_device(ARBOR_DEVICE_CPU, std::to_string(std::max(1u, std::thread::hardware_concurrency())) + " CPU threads");
    }

    void render_region(const arbor_render_request_v2 &request, arbor_image &out, const sdk::Task &task) override
    {
        const bool coarse = request.pass == ARBOR_RENDER_PASS_COARSE;
        const VoxelGrid &g = prepare(request, task);
        const Shading shading = Shading::from(params());
        Pass pass;
        pass.grid = &g;
        pass.occupancy = &occupancy_;
        pass.occlusion = shading.enabled ? static_cast<float>(params().number("ambient-occlusion")) : 0.0f;
        pass.shading = &shading;
        pass.camera = std::make_unique<Camera>(*request.camera, request.frame_width, request.frame_height);
        pass.termination = static_cast<float>(params().number("termination"));
        pass.jitter = params().flag("jitter");
        pass.sample_labels = params().flag("sample-labels");
        pass.sample_gradients = params().flag("sample-gradients");
        pass.background = request.background;
        pass.coarse = coarse;
        pass.step = step_ * (pass.coarse ? kCoarseStep : 1.0);
        pass.table = pass.coarse ? &coarse_table_ : &table_;
        pass.refined = pass.coarse ? &coarse_refined_table_ : &refined_table_;
        pass.sample_index = request.pass == ARBOR_RENDER_PASS_SUPERSAMPLE ? request.sample_index : 0;
        pass.cast = loop_for(g, shading, pass.sample_gradients);

        const unsigned threads = params().integer("threads") > 0 ? static_cast<unsigned>(params().integer("threads"))
                                                                 : std::max(1u, std::thread::hardware_concurrency());
        if (!arena_ || arena_threads_ != threads) {
            arena_ = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
            arena_threads_ = threads;
        }
        std::vector<double> visibility(table_.labels(), 0.0);
        Cancellation cancel(task);
        if (coarse)
            pass.pixels = coarse_rate_.pixels_for(request, params().number("coarse-rate"),
                                                  static_cast<double>(params().integer("coarse-pixels")));
        const auto started = std::chrono::steady_clock::now();
        arena_->execute([&] {
            if (pass.coarse)
                render_coarse(pass, request, out, cancel, visibility);
            else
                render_pixels(pass, request, out, cancel, visibility);
        });
        task.throw_if_cancelled();
        if (coarse)
            coarse_rate_.rendered(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
                                  static_cast<double>(out.width) * out.height);
        if (ARBOR_HAS_FIELD(arbor_image, out.struct_size, label_visibility_count) && out.label_visibility)
            for (uint32_t l = 0; l < out.label_visibility_count; ++l)
                out.label_visibility[l] = l < visibility.size() ? visibility[l] : 0.0;
    }

private:
    struct Pass {
        double pixels = kCoarseStart; // COARSE: one ray per pixels x pixels
        const VoxelGrid *grid = nullptr;
        const Occupancy *occupancy = nullptr;
        float occlusion = 0.0f; // local ambient occlusion's strength
        const Shading *shading = nullptr;
        const ClassTable *table = nullptr;
        const ClassTable *refined = nullptr; // a step of kRefine samples in a mixed cell
        std::unique_ptr<Camera> camera;
        float termination = 0.99f;
        bool jitter = true, coarse = false;
        bool sample_labels = true, sample_gradients = true; // resolved and interpolated at the sample
        double step = 1.0;
        const float *background = nullptr;
        uint32_t sample_index = 0; // supersampling: which offset within the pixel
        // The loop for this grid and these settings (cast<kLabels, kGradient>).
        Sample (RayCaster::*cast)(const Pass &, double, double, double, double *) const = nullptr;
    };

    // Brings every derived structure up to date with the request: the grid
    // (volume, labels), the block statistics, then what the transfer
    // functions decide (tables, empty blocks, boundary emphasis, occlusion).
    const VoxelGrid &prepare(const arbor_render_request_v2 &request, const sdk::Task &task)
    {
        const VoxelGrid &g =
            grid_.update(*request.volume, request.volume_revision, request.labels, request.labels_revision, task);
        const arbor_tf_set &tf = *request.transfer_functions;
        require_functions(g, tf);
        const bool grid_changed = grid_.generation() != blocks_generation_;
        if (grid_changed) {
            blocks_generation_ = ~uint64_t{0};
            blocks_.build(g, task);
            boundaries_.sample(g);
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
            refined_table_.build(tf, step / kRefine);
            coarse_refined_table_.build(tf, step * kCoarseStep / kRefine);
            // Which blocks are empty does not depend on the step: one grid
            // of flags serves both passes.
            occupancy_.build(blocks_, table_, {g.nx, g.ny, g.nz}, g.min_spacing);
            boundaries_.build(table_, emphasis);
            occlusion_current_ = false;
            table_print_ = print;
            step_ = step;
            emphasis_ = emphasis;
        }
        // The occlusion rays' tables only when they are cast: not on every
        // flow-rate step with the occlusion off.
        if (params().number("ambient-occlusion") > 0 && !occlusion_current_) {
            occlusion_.build(g, tf);
            occlusion_current_ = true;
        }
        return g;
    }

    // FULL and SUPERSAMPLE: a ray per pixel, each pixel written once, when
    // its ray is done (so a cancelled call leaves old or final pixels).
    void render_pixels(const Pass &pass, const arbor_render_request_v2 &request, arbor_image &out,
                       Cancellation &cancel, std::vector<double> &visibility) const
    {
        const uint32_t tiles = (out.height + kRows - 1) / kRows;
        // Allocated here: the pool's threads allocate nothing.
        Slots per_tile(tiles, std::vector<double>(visibility.size(), 0.0));
        const int64_t depth_stride = depth_stride_of(out);
        std::atomic<uint32_t> done{0};
        const std::array<double, 2> offset = pass.sample_index ? subpixel(pass.sample_index) : std::array{0.5, 0.5};
        const float blend = pass.sample_index ? 1.0f / static_cast<float>(pass.sample_index + 1) : 1.0f;
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, tiles, 1), [&](const tbb::blocked_range<uint32_t> &r) {
            for (uint32_t t = r.begin(); t != r.end(); ++t) {
                std::vector<double> &mine = per_tile[t];
                for (uint32_t y = t * kRows; y < std::min(out.height, (t + 1) * kRows); ++y) {
                    if (cancel.stopped())
                        return;
                    for (uint32_t x = 0; x < out.width; ++x) {
                        const uint32_t fx = request.region_x + x, fy = request.region_y + y;
                        const Sample s = (this->*pass.cast)(pass, fx + offset[0], fy + offset[1],
                                                            ray_offset(pass.jitter, pass.sample_index, fx, fy),
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
        add_in_order(per_tile, 1.0, visibility);
    }

    // COARSE: a ray per n x n block of the frame, each pixel bilinear
    // between the four rays around it.  The rays are cast first; the pixels
    // are written only when all are done.
    void render_coarse(const Pass &pass, const arbor_render_request_v2 &request, arbor_image &out,
                       Cancellation &cancel, std::vector<double> &visibility) const
    {
        const CoarseLattice lattice(request, pass.pixels);
        const int64_t w = lattice.columns(), h = lattice.rows();
        std::vector<Sample> rays(static_cast<std::size_t>(w * h));
        // Each coarse ray stands for pixels^2 pixels of the frame; the
        // visibility is scaled to the region's pixels below.
        Slots per_row(static_cast<std::size_t>(h), std::vector<double>(visibility.size(), 0.0));
        tbb::parallel_for(tbb::blocked_range<int64_t>(0, h, 2), [&](const tbb::blocked_range<int64_t> &r) {
            for (int64_t n = r.begin(); n != r.end(); ++n) {
                if (cancel.stopped())
                    return;
                std::vector<double> &mine = per_row[static_cast<std::size_t>(n)];
                for (int64_t m = 0; m < w; ++m) {
                    const double px = lattice.x(m), py = lattice.y(n);
                    rays[static_cast<std::size_t>(n * w + m)] =
                        (this->*pass.cast)(pass, px, py,
                                           ray_offset(pass.jitter, 0, static_cast<uint32_t>(px),
                                                      static_cast<uint32_t>(py)),
                                           mine.data());
                }
            }
        });
        if (cancel.stopped())
            return;
        add_in_order(per_row, static_cast<double>(out.width) * out.height / static_cast<double>(w * h), visibility);
        lattice.interpolate(rays, out);
    }

    // Where a sample's gradient comes from: none needed (neither shading
    // nor boundary emphasis), its nearest voxel's, the voxels' trilinear
    // (SampleGradient), on thick slices as on isotropic voxels
    // (IsotropicGradient).
    enum class Gradient { None, Voxel, Sample, Isotropic };
    using Loop = Sample (RayCaster::*)(const Pass &, double, double, double, double *) const;

    template <bool kLabels>
    static Loop loop_for(Gradient gradient)
    {
        switch (gradient) {
        case Gradient::None: return &RayCaster::cast<kLabels, Gradient::None>;
        case Gradient::Voxel: return &RayCaster::cast<kLabels, Gradient::Voxel>;
        case Gradient::Sample: return &RayCaster::cast<kLabels, Gradient::Sample>;
        case Gradient::Isotropic: break;
        }
        return &RayCaster::cast<kLabels, Gradient::Isotropic>;
    }

    Loop loop_for(const VoxelGrid &g, const Shading &shading, bool sample_gradients) const
    {
        const Gradient gradient = !(shading.enabled || boundaries_.active()) ? Gradient::None
                                  : !sample_gradients                         ? Gradient::Voxel
                                  : g.thick_slices                            ? Gradient::Isotropic
                                                                              : Gradient::Sample;
        return g.label.empty() ? loop_for<false>(gradient) : loop_for<true>(gradient);
    }

    // The ray through frame position (px, py), its first sample `offset` of
    // a step past the lattice.  `visibility`: per label, what this ray's
    // samples of it contribute (T * alpha) is added.
    //
    // kLabels: the grid has labels; kGradient: where a sample's gradient
    // comes from.  A loop compiled for each: with everything in one, the
    // transparent samples of a plain frame paid for the registers that
    // labels and gradients hold (spills; 33 % more instructions in the
    // unshaded frame than before issue 49, and its time).
    template <bool kLabels, Gradient kGradient>
    Sample cast(const Pass &pass, double px_frame, double py_frame, double offset_fraction, double *visibility) const
    {
        const VoxelGrid &g = *pass.grid;
        const ClassTable &table = *pass.table;
        const Occupancy &occupancy = *pass.occupancy;
        const float termination = pass.termination;
        const double step = pass.step, per_step = 1.0 / step;
        const float *background = pass.background;
        const Ray ray = pass.camera->ray(px_frame, py_frame);
        // The ray in voxel index space.
        const Vec3 o = mul(g.to_voxel, {ray.origin[0] - g.origin[0], ray.origin[1] - g.origin[1],
                                        ray.origin[2] - g.origin[2]});
        const Vec3 d = mul(g.to_voxel, ray.direction); // voxels per mm
        Vec3 per; // 1 / d, for skips
        for (int a = 0; a < 3; ++a)
            per[a] = std::fabs(d[a]) < 1e-12 ? 0.0 : 1.0 / d[a];
        // Clipped to the box around the blocks that can be visible at all.
        const auto [t0, t1] = chord(o, d, occupancy.content_low(), occupancy.content_high());
        // Where it enters and leaves through the volume's own faces (the
        // scan's field of view), the first and last samples stand for the
        // part of a step up to the face: a cut face does not speckle with
        // the jitter.
        const auto [v0, v1] = chord(o, d, {0.0, 0.0, 0.0},
                                    {static_cast<double>(g.nx - 1), static_cast<double>(g.ny - 1),
                                     static_cast<double>(g.nz - 1)});
        const bool enters_face = t0 > 0 && std::fabs(t0 - v0) < 1e-9, leaves_face = std::fabs(t1 - v1) < 1e-9;
        Along along(g, pass);
        along.offset_fraction = static_cast<float>(offset_fraction);
        along.visibility = visibility;
        for (int a = 0; a < 3; ++a)
            along.light[a] = static_cast<float>(-ray.direction[a]);
        Gathered gathered;
        // Start on the global sample lattice, so images do not shimmer as the
        // box is clipped, shifted by a fixed per-pixel fraction of a step.
        const double offset = offset_fraction * step;
        double t = std::ceil((t0 - offset) / step) * step + offset;
        // The samples that stand for part of a step (one test per sample).
        const double partial_first = enters_face ? t : -std::numeric_limits<double>::infinity();
        const double partial_from = leaves_face ? t1 - step : std::numeric_limits<double>::infinity();
        const int64_t last_i = along.last[0], last_j = along.last[1], last_k = along.last[2];
        const bool labelled = kLabels && along.labelled;
        // Where structures meet, a structure thinner than a step (a thin
        // shell's region between its saddle's isosurfaces) would be missed
        // between samples, or caught by one sample in a few (speckle): a
        // step in a mixed cell whose labels differ across it is taken as
        // kRefine samples; not in the coarse pass, a preview that must keep
        // its frame rate.
        const bool refine = kLabels && along.resolve && !pass.coarse;
        const bool prefetch = g.nx * g.ny * g.nz >= kPrefetchFrom;
        const VoxelGrid::Strides cell_strides = g.strides();
        const int64_t dj = cell_strides.j, dk = cell_strides.k;
        const float opaque = 1.0f - termination; // the transmittance where a ray stops
        while (t <= t1 && gathered.transmittance > opaque) {
            const double px = o[0] + t * d[0], py = o[1] + t * d[1], pz = o[2] + t * d[2];
            const int64_t i = std::min(static_cast<int64_t>(px), last_i);
            const int64_t j = std::min(static_cast<int64_t>(py), last_j);
            const int64_t k = std::min(static_cast<int64_t>(pz), last_k);
            if (occupancy.empty(i >> 3, j >> 3, k >> 3)) { // kBlock = 8
                t = skip_block(o, per, t, step, per_step, offset, i, j, k);
                continue;
            }
            if (prefetch) {
                // The cell kAhead samples on (clamped into the grid): its
                // values' four rows, and its label word.
                const double ahead = t + kAhead * step;
                const int64_t ai = std::clamp(static_cast<int64_t>(o[0] + ahead * d[0]), int64_t{0}, last_i);
                const int64_t aj = std::clamp(static_cast<int64_t>(o[1] + ahead * d[1]), int64_t{0}, last_j);
                const int64_t ak = std::clamp(static_cast<int64_t>(o[2] + ahead * d[2]), int64_t{0}, last_k);
                const std::size_t cell = g.index(ai, aj, ak);
                const float *value = g.value.data() + cell;
                const Surface *surface = g.surface.data() + cell;
                for (const int64_t row : {int64_t{0}, dj, dk, dk + dj})
                    __builtin_prefetch(value + row);
                // Gradient words where a sample's gradient reads them: its
                // nearest voxel's, in two rows of the four (all four cost
                // more on the many samples that do not show); all four rows
                // for the trilinear gradient.
                if constexpr (kGradient == Gradient::Voxel) {
                    __builtin_prefetch(surface);
                    __builtin_prefetch(surface + dk + dj);
                } else if constexpr (kGradient == Gradient::Sample) {
                    for (const int64_t row : {int64_t{0}, dj, dk, dk + dj})
                        __builtin_prefetch(surface + row);
                } else if constexpr (kGradient == Gradient::Isotropic) {
                    // The rows before and after the cell's, in both slices.
                    for (const int64_t row : {-dj, 2 * dj, dk - dj, dk + 2 * dj})
                        __builtin_prefetch(value + row);
                }
                if (labelled)
                    g.label.prefetch(cell);
            }
            if (refine && (g.label.word(g.index(i, j, k)) & 1u) && labels_vary(pass, o, d, t, t0, t1, along)) {
                gathered = integrate_refined<kGradient>(pass, o, d, t, t0, t1, along, gathered);
            } else {
                // A sample stands for the step around it; at a face, for
                // the part of it inside.
                float steps = 1.0f;
                if (t == partial_first || t > partial_from) [[unlikely]] {
                    if (t == partial_first)
                        steps += static_cast<float>((t - t0) / step) - 0.5f;
                    if (t > partial_from)
                        steps += static_cast<float>((t1 - t) / step) - 0.5f;
                }
                integrate<kLabels, kGradient>(pass, table, i, j, k, static_cast<float>(px - i),
                                              static_cast<float>(py - j), static_cast<float>(pz - k), steps, t, along,
                                              gathered);
            }
            t += step;
        }
        if (gathered.label_share > 0)
            visibility[gathered.label] += gathered.label_share;
        Sample out;
        const float rest = gathered.transmittance;
        for (int ch = 0; ch < 3; ++ch)
            out.rgba[ch] = std::min(1.0f, gathered.acc[ch] + rest * background[ch] * background[3]);
        out.rgba[3] = std::min(1.0f, 1.0f - rest + rest * background[3]);
        out.depth = gathered.depth;
        return out;
    }

    // What a ray's samples share.
    struct Along {
        Along(const VoxelGrid &g, const Pass &pass)
            : high{static_cast<double>(g.nx - 1), static_cast<double>(g.ny - 1), static_cast<double>(g.nz - 1)},
              last{std::max<int64_t>(g.nx - 2, 0), std::max<int64_t>(g.ny - 2, 0), std::max<int64_t>(g.nz - 2, 0)},
              strides(g.strides()), labelled(!g.label.empty()),
              resolve(labelled && pass.sample_labels && !g.tree.empty())
        {
            for (int c = 0; c < 9; ++c)
                inverse[c] = static_cast<float>(g.to_voxel[c]);
        }
        float inverse[9];           // rows of M^-1 = columns of M^-T
        float light[3] = {0, 0, 0}; // towards the camera
        double *visibility = nullptr; // per label, T * alpha
        float offset_fraction = 0;
        const double high[3];    // the last voxel index along each axis
        const int64_t last[3];   // the last cell's
        const VoxelGrid::Strides strides;
        const bool labelled, resolve; // labels; resolved per sample
    };

    // What a ray has gathered so far: a value that is passed, never pointed
    // at, so that it stays in registers across the sample loop (it used to
    // be a member of Along, whose address the refined path takes: every
    // sample stored and reloaded it).
    struct Gathered {
        float acc[3] = {0, 0, 0}; // premultiplied colour
        // What passes the samples so far: 1 - opacity.  Its product is the
        // loop's one chain from sample to sample (a multiplication), where
        // opacity += (1 - opacity) alpha was three operations long.
        float transmittance = 1;
        float depth = std::numeric_limits<float>::infinity();
        // T * alpha of the label of the latest samples, added to the ray's
        // visibility when the label changes (not a store per sample).
        uint32_t label = 0;
        double label_share = 0;
    };

    // Sample m of kRefine across the step around t: its cell and its place
    // in it.  Within half a step of a sample inside: clamped into the grid.
    struct SubSample {
        double t;
        int64_t c[3];
        float f[3];
    };
    static SubSample sub_sample(const Pass &pass, const Vec3 &o, const Vec3 &d, double t, int m, const Along &along)
    {
        SubSample s;
        s.t = t + (m + 0.5 - 0.5 * kRefine) * (pass.step / kRefine);
        for (int a = 0; a < 3; ++a) {
            const double at = std::clamp(o[a] + s.t * d[a], 0.0, along.high[a]);
            s.c[a] = std::min(static_cast<int64_t>(at), along.last[a]);
            s.f[a] = static_cast<float>(at - static_cast<double>(s.c[a]));
        }
        return s;
    }

    // Whether the labels of the step around t, in a cell where structures
    // meet, differ between its kRefine samples: a boundary between
    // structures (or a structure thinner than the step) crosses the step.
    // Most steps in mixed cells lie on one side of it and are taken as one
    // sample (the CT head's full frame: 3.0 s when every such step was
    // refined).  Out of line: the rarer path.
    [[gnu::noinline]] bool labels_vary(const Pass &pass, const Vec3 &o, const Vec3 &d, double t, double t0,
                                       double t1, const Along &along) const
    {
        const VoxelGrid &g = *pass.grid;
        bool any = false;
        uint32_t first = 0;
        // The samples mostly share a cell: its extreme corners once.
        std::size_t seen = ~std::size_t{0};
        Cell::Ends ends{0, 0};
        for (int m = 0; m < kRefine; ++m) {
            const SubSample s = sub_sample(pass, o, d, t, m, along);
            if (s.t < t0 || s.t > t1)
                continue;
            const std::size_t base = g.index(s.c[0], s.c[1], s.c[2]);
            const uint32_t word = g.label.word(base);
            uint32_t label = word >> 1;
            if (word & 1u) {
                if (base != seen) {
                    ends = Cell::extremes(g, base, along.strides);
                    seen = base;
                }
                const Cell cell(g, base, along.strides, s.f[0], s.f[1], s.f[2]);
                label = g.tree.resolve(ends.low, ends.high, cell.value());
            }
            if (any && label != first)
                return true;
            any = true;
            first = label;
        }
        return false;
    }

    // The step around t where labels differ across it, as kRefine samples
    // (out of line: the rarer path).
    template <Gradient kGradient>
    [[gnu::noinline]] Gathered integrate_refined(const Pass &pass, const Vec3 &o, const Vec3 &d, double t, double t0,
                                                 double t1, const Along &along, Gathered gathered) const
    {
        for (int m = 0; m < kRefine && gathered.transmittance > 1.0f - pass.termination; ++m) {
            const SubSample s = sub_sample(pass, o, d, t, m, along);
            if (s.t < t0 || s.t > t1)
                continue;
            integrate<true, kGradient>(pass, *pass.refined, s.c[0], s.c[1], s.c[2], s.f[0], s.f[1], s.f[2], 1.0f, s.t,
                                       along, gathered);
        }
        return gathered;
    }

    // The sample at voxel position c + f (c its cell's lowest voxel, f in
    // [0, 1]^3) composited into the ray: its value, label and gradient
    // from its cell, classified by `table`, opacity 1 - (1 - a)^steps,
    // shaded, at distance t.
    template <bool kLabels, Gradient kGradient>
    [[gnu::always_inline]] void integrate(const Pass &pass, const ClassTable &table, int64_t ci, int64_t cj,
                                          int64_t ck, float fx, float fy, float fz, float steps, double t,
                                          const Along &along, Gathered &gathered) const
    {
        const VoxelGrid &g = *pass.grid;
        const Shading &shading = *pass.shading;
        const VoxelGrid::Strides s = along.strides;
        const std::size_t base = g.index(ci, cj, ck);
        const Cell cell(g, base, s, fx, fy, fz);
        const float value = cell.value();
        // With labels or gradients per sample off: the nearest voxel's.
        const std::size_t nearest =
            base + static_cast<std::size_t>((fx >= 0.5f ? s.i : 0) + (fy >= 0.5f ? s.j : 0) + (fz >= 0.5f ? s.k : 0));
        uint32_t label = 0;
        if constexpr (kLabels) {
            if (along.resolve) {
                const uint32_t word = g.label.word(base);
                label = word & 1u ? Cell::resolved_label(g, base, s, value) : word >> 1;
            } else {
                label = g.label[nearest];
            }
        }
        const float *colour = table.lookup_shown(label, value);
        if (!colour || !(colour[3] > 0.0f))
            return;
        // The normal is v * unit (unit 0: no direction to shade by).
        float v[3] = {0, 0, 0}, unit = 0, gradient = 0; // unless shaded or emphasised
        if constexpr (kGradient == Gradient::Isotropic) {
            const int64_t at[3] = {ci, cj, ck};
            const IsotropicGradient at_sample(g, base, s, at, along.inverse, cell);
            v[0] = at_sample.direction[0], v[1] = at_sample.direction[1], v[2] = at_sample.direction[2];
            unit = at_sample.inverse_length;
            gradient = at_sample.magnitude;
        } else if constexpr (kGradient == Gradient::Sample) {
            const SampleGradient at_sample(g, base, s, cell);
            v[0] = at_sample.direction[0], v[1] = at_sample.direction[1], v[2] = at_sample.direction[2];
            unit = at_sample.inverse_length;
            gradient = at_sample.magnitude;
        } else if constexpr (kGradient == Gradient::Voxel) {
            const Surface &surface = g.surface[nearest];
            v[0] = surface.normal[0], v[1] = surface.normal[1], v[2] = surface.normal[2];
            unit = surface.normal[0] | surface.normal[1] | surface.normal[2] ? 1.0f / 127.0f : 0.0f;
            gradient = surface.gradient;
        }
        constexpr bool kSurfaces = kGradient != Gradient::None;
        float m =
            kSurfaces && boundaries_.active() ? boundaries_.factor(static_cast<uint8_t>(gradient + 0.5f)) : 1.0f;
        if (steps != 1.0f) {
            const float a = colour[3] * m;
            m *= a < 1.0f ? (1.0f - std::pow(1.0f - a, steps)) / a : 1.0f;
        }
        const float alpha = colour[3] * m;
        float r = colour[0] * m, gr = colour[1] * m, b = colour[2] * m;
        const float w = gathered.transmittance;
        if (kSurfaces && shading.enabled && unit > 0.0f) {
            const float facing = (v[0] * along.light[0] + v[1] * along.light[1] + v[2] * along.light[2]) * unit;
            const float ndl = std::min(1.0f, std::fabs(facing));
            // Headlight: the half vector is the light direction.
            const float spec = shading.highlight[static_cast<std::size_t>(ndl * 256.0f)] * alpha;
            float lit = shading.ambient + shading.diffuse * ndl;
            if (pass.occlusion > 0 && w * alpha >= LocalOcclusion::kContribution) {
                // The side of the surface the viewer sees.
                const float sign = facing >= 0.0f ? unit : -unit;
                const float side[3] = {sign * v[0], sign * v[1], sign * v[2]};
                const double p[3] = {static_cast<double>(ci) + fx, static_cast<double>(cj) + fy,
                                     static_cast<double>(ck) + fz};
                lit *= 1.0f -
                       pass.occlusion * (1.0f - occlusion_.visibility(g, boundaries_, p, side, along.offset_fraction));
            }
            r = r * lit + spec;
            gr = gr * lit + spec;
            b = b * lit + spec;
        }
        gathered.acc[0] += w * r;
        gathered.acc[1] += w * gr;
        gathered.acc[2] += w * b;
        gathered.transmittance *= 1.0f - alpha;
        if (label != gathered.label) {
            along.visibility[gathered.label] += gathered.label_share;
            gathered.label = label;
            gathered.label_share = 0;
        }
        gathered.label_share += w * alpha;
        if (gathered.transmittance <= 0.5f && gathered.depth == std::numeric_limits<float>::infinity())
            gathered.depth = static_cast<float>(t); // rays start at the camera (plane): t is the distance
    }

    // Where the ray o + t d (t >= 0) is inside the box [lo, hi]: t0 > t1
    // when it misses.
    static std::pair<double, double> chord(const Vec3 &o, const Vec3 &d, const std::array<double, 3> &lo,
                                           const std::array<double, 3> &hi)
    {
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
        return {t0, t1};
    }

    // The first position of the ray's own (offset) lattice past the block
    // holding cell (i, j, k): skipping keeps each ray's jitter.
    // Multiplications by the ray's inverse direction and step, not
    // divisions: a skip lies on the chain from sample to sample (the next
    // position waits for it), and three divisions and a fourth made it
    // several samples long.  `per` holds 1 / d (0 where the ray runs along
    // the axis's planes), per_step 1 / step.
    static double skip_block(const Vec3 &o, const Vec3 &per, double t, double step, double per_step, double offset,
                             int64_t i, int64_t j, int64_t k)
    {
        const int64_t cell[3] = {i, j, k};
        double exit = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
            if (per[a] == 0.0)
                continue;
            const int64_t b = cell[a] / Occupancy::kBlock;
            const double bound = per[a] > 0 ? static_cast<double>((b + 1) * Occupancy::kBlock)
                                            : static_cast<double>(b * Occupancy::kBlock) - 1e-9;
            exit = std::min(exit, (bound - o[a]) * per[a]);
        }
        // Rounded down a millionth of a step: a lattice point on the
        // block's face is never skipped (at worst one sample more in the
        // empty block, which skips again).
        return std::max(t + step, std::ceil((exit - offset) * per_step - 1e-6) * step + offset);
    }

    VoxelGridCache grid_;
    BlockStatistics blocks_;
    uint64_t blocks_generation_ = ~uint64_t{0};
    ClassTable table_, coarse_table_, refined_table_, coarse_refined_table_;
    Occupancy occupancy_;
    BoundaryEmphasis boundaries_;
    LocalOcclusion occlusion_;
    bool occlusion_current_ = false; // built for the current tables
    uint64_t table_print_ = 0;
    double step_ = -1.0, emphasis_ = -1.0;
    CoarseRate coarse_rate_;
    std::unique_ptr<tbb::task_arena> arena_; // the pool the tiles run on (oneTBB's threads persist)
    unsigned arena_threads_ = 0;
};

} // namespace

sdk::Instance *create_ray_caster(const arbor_host *host)
{
    return new RayCaster(host);
}

} // namespace arbor::raycast
