// gl_ray_caster.cpp - org.arbor.renderer.gl-raycast: the CPU ray caster's
// optical model in a GLSL 3.3 fragment shader (resources/shaders).  The
// volume, labels, normals, empty blocks and per-label lookup tables are
// textures, rebuilt when the request's revisions say they changed; the
// classification tables come from the same code as the CPU ray caster's
// (plugins/raycast).  It renders offscreen, into framebuffer objects of an
// EGL context (no window, no X server), on a thread of its own; tiles,
// the coarse pass and supersampling follow arbor.renderer/2, as the CPU
// ray caster's do, and it says whether its OpenGL is hardware.  Through
// arbor.renderer-gl/1 it renders the same passes into a texture of the
// host's own context instead (a workstation shows them without a read
// back), with a second set of GL objects made in that context.
#include "context_state.hpp"
#include "gl_thread.hpp"

#include <block_statistics.hpp>
#include <coarse_lattice.hpp>
#include <optical_model.hpp>
#include <ray_geometry.hpp>

#include <arbor/sdk/renderer.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

namespace arbor::glraycast {

extern const arbor_plugin_descriptor kGlRayCasterDescriptor;

const arbor_plugin_descriptor kGlRayCasterDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.renderer.gl-raycast",
    ARBOR_KIND_RENDERER,
    "OpenGL ray caster",
    "1.0.0",
    "Arbor",
    "The CPU ray caster's optical model (label-aware post-classification, boundary emphasis, Blinn-Phong, "
    "local ambient occlusion, empty-space skipping) in a GLSL 3.3 shader, offscreen through EGL or into the host's OpenGL "
    "context; tiles, a coarse pass and supersampling (arbor.renderer/2, arbor.renderer-gl/1).",
    "",
};

namespace {

using raycast::Sample;

constexpr GLsizei kBandRows = 64; // rows per draw: cancellation and progress between draws
constexpr uint32_t kLabelsPerVisibilityDraw = 32;

// What one draw casts: a grid of rays, fragment (x, y) at frame position
// base + (x, y) * spacing + subpixel.
struct RayGrid {
    GLsizei width = 0, height = 0;
    double base_x = 0, base_y = 0, spacing = 1;
    double subpixel_x = 0.5, subpixel_y = 0.5;
    double shift = 0;   // supersampling: fract(golden * sample)
    bool coarse = false;
};

class GlRayCaster final : public sdk::Renderer {
public:
    explicit GlRayCaster(const arbor_host *host)
        : Renderer(kGlRayCasterDescriptor, host, raycast::optical_model_params(), Interface::v2)
    {
        offer_device(); // the context is made when first needed: creating an instance stays cheap
        offer_gl();
    }

    ~GlRayCaster() override
    {
        // The host's context is not current here: what render_gl made in it
        // is the host's to release first (release_gl), else it leaks.
        (void)host_.release();
        if (!gl_)
            return;
        gl_->run([&] { own_.reset(); }); // GL names die on the thread their context is current on
    }

    void render_region(const arbor_render_request_v2 &request, arbor_image &out, const sdk::Task &task) override
    {
        start();
        const raycast::VoxelGrid &g = prepare(request, task);
        const uint32_t sample = request.pass == ARBOR_RENDER_PASS_SUPERSAMPLE ? request.sample_index : 0;
        const bool want_visibility =
            ARBOR_HAS_FIELD(arbor_image, out.struct_size, label_visibility_count) && out.label_visibility;
        std::vector<double> visibility(table_.labels(), 0.0);
        const auto started = std::chrono::steady_clock::now();

        std::unique_ptr<raycast::CoarseLattice> lattice;
        const RayGrid grid = ray_grid(request, lattice);
        const std::size_t rays = static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height);
        std::vector<float> rgba(4 * rays), depth(rays);
        bool finished = false;
        gl_->run([&] {
            ContextState &s = *own_;
            sync(s, g);
            s.textures.bind(grid.coarse);
            if (!cast(s, request, g, grid, task, 0, false))
                return;
            read_image(grid, rgba.data(), depth.data());
            if (want_visibility) {
                for (uint32_t base = 0; base < table_.labels(); base += kLabelsPerVisibilityDraw) {
                    if (!cast(s, request, g, grid, task, base, true))
                        return;
                    read_visibility(grid, base, visibility);
                }
            }
            finished = true;
        });
        task.throw_if_cancelled();
        if (!finished)
            sdk::fail(ARBOR_ERROR_CANCELLED, "cancelled");
        // Every pixel is written only now: a cancelled call left them all.
        if (lattice) {
            std::vector<Sample> samples(rays);
            for (std::size_t r = 0; r < rays; ++r) {
                std::memcpy(samples[r].rgba, &rgba[4 * r], sizeof samples[r].rgba);
                samples[r].depth = depth[r] < 0 ? std::numeric_limits<float>::infinity() : depth[r];
            }
            lattice->interpolate(samples, out);
            const double per_ray = static_cast<double>(out.width) * out.height / static_cast<double>(rays);
            for (double &v : visibility)
                v *= per_ray;
            coarse_rate_.rendered(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
                                  static_cast<double>(out.width) * out.height);
        } else {
            write_pixels(rgba, depth, sample, out);
        }
        if (want_visibility)
            for (uint32_t l = 0; l < out.label_visibility_count; ++l)
                out.label_visibility[l] = l < visibility.size() ? visibility[l] : 0.0;
    }

    // arbor.renderer-gl/1: the same rays in the host's context (current
    // on this thread), then written into its texture by the present pass.
    void render_gl(const arbor_render_request_v2 &request, const arbor_gl_target &target,
                   const sdk::Task &task) override
    {
        const raycast::VoxelGrid &g = prepare(request, task);
        const auto started = std::chrono::steady_clock::now();
        std::unique_ptr<raycast::CoarseLattice> lattice;
        const RayGrid grid = ray_grid(request, lattice);
        if (!host_)
            host_ = std::make_unique<ContextState>();
        ContextState &s = *host_;
        s.make_objects();
        sync(s, g);
        s.textures.bind(grid.coarse);
        if (!cast(s, request, g, grid, task, 0, false))
            sdk::fail(ARBOR_ERROR_CANCELLED, "cancelled"); // the target is not touched before the present pass
        present(s, request, grid, target);
        if (lattice)
            coarse_rate_.rendered(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
                                  static_cast<double>(request.region_width) * request.region_height);
    }

    void release_gl() override { host_.reset(); }

    void find_device() override { start(); }

private:
    // The OpenGL thread, context and framebuffer, made on first use; what
    // failed is said then (no EGL, no OpenGL 3.3), and again at each try.
    void start()
    {
        if (gl_)
            return;
        auto gl = std::make_unique<GlThread>();
        gl->run([&] {
            auto s = std::make_unique<ContextState>();
            s->make_objects(); // on failure s dies here, on this thread
            own_ = std::move(s);
        });
        const EglContext &c = gl->context();
        set_device(c.software() ? ARBOR_DEVICE_SOFTWARE_GPU : ARBOR_DEVICE_GPU, c.description());
        gl_ = std::move(gl);
    }

    // The rays a pass casts over the request's region: a ray per pixel, or
    // the coarse pass's lattice (then `lattice` is set).
    RayGrid ray_grid(const arbor_render_request_v2 &request, std::unique_ptr<raycast::CoarseLattice> &lattice)
    {
        RayGrid grid;
        if (request.pass == ARBOR_RENDER_PASS_COARSE) {
            const double pixels = coarse_rate_.pixels_for(request, params().number("coarse-rate"),
                                                          static_cast<double>(params().integer("coarse-pixels")));
            lattice = std::make_unique<raycast::CoarseLattice>(request, pixels);
            grid.width = static_cast<GLsizei>(lattice->columns());
            grid.height = static_cast<GLsizei>(lattice->rows());
            grid.base_x = lattice->x(0);
            grid.base_y = lattice->y(0);
            grid.spacing = pixels;
            grid.subpixel_x = grid.subpixel_y = 0;
            grid.coarse = true;
            return grid;
        }
        grid.width = static_cast<GLsizei>(request.region_width);
        grid.height = static_cast<GLsizei>(request.region_height);
        grid.base_x = request.region_x;
        grid.base_y = request.region_y;
        if (const uint32_t sample = request.pass == ARBOR_RENDER_PASS_SUPERSAMPLE ? request.sample_index : 0) {
            const auto offset = raycast::subpixel(sample);
            grid.subpixel_x = offset[0];
            grid.subpixel_y = offset[1];
            grid.shift = std::fmod(raycast::kSupersampleShift * sample, 1.0);
        }
        return grid;
    }

    // The grid, block statistics and tables up to date with the request
    // (on the calling thread, all cores); sync() uploads them to a context.
    const raycast::VoxelGrid &prepare(const arbor_render_request_v2 &request, const sdk::Task &task)
    {
        const raycast::VoxelGrid &g =
            grid_.update(*request.volume, request.volume_revision, request.labels, request.labels_revision, task);
        const arbor_tf_set &tf = *request.transfer_functions;
        raycast::require_functions(g, tf);
        const bool grid_changed = grid_.generation() != prepared_grid_;
        if (grid_changed) {
            prepared_grid_ = kNotUploaded;
            blocks_.build(g, task);
            boundaries_.sample(g);
        }
        const double step = params().number("sample-distance") * g.min_spacing;
        const double emphasis = params().number("boundary-emphasis");
        const raycast::Shading shading = raycast::Shading::from(params());
        const uint64_t print = request.transfer_functions_revision;
        if (grid_changed || print == 0 || print != tf_revision_ || step != step_ || emphasis != emphasis_ ||
            shading.highlight != shading_.highlight) {
            tf_revision_ = 0;
            table_.build(tf, step);
            coarse_table_.build(tf, step * raycast::kCoarseStep);
            refined_table_.build(tf, step / raycast::kRefine);
            coarse_refined_table_.build(tf, step * raycast::kCoarseStep / raycast::kRefine);
            occupancy_.build(blocks_, table_, {g.nx, g.ny, g.nz}, g.min_spacing);
            boundaries_.build(table_, emphasis);
            occlusion_current_ = false;
            ++tables_generation_;
            tf_revision_ = print;
            step_ = step;
            emphasis_ = emphasis;
            shading_ = shading;
        }
        occlusion_strength_ = static_cast<float>(params().number("ambient-occlusion"));
        // The occlusion rays' tables only when they are cast: not on every
        // flow-rate step with the occlusion off.
        if (occlusion_strength_ > 0 && !occlusion_current_) {
            occlusion_.build(g, tf);
            occlusion_current_ = true;
            ++tables_generation_;
        }
        prepared_grid_ = grid_.generation();
        return g;
    }

    // The textures of context state s up to date with what prepare() made
    // (s's context current).
    void sync(ContextState &s, const raycast::VoxelGrid &g)
    {
        if (s.grid != grid_.generation()) {
            s.grid = kNotUploaded;
            if (s.values != grid_.values_generation()) { // not for new labels alone
                s.values = kNotUploaded;
                s.textures.upload_volume(g);
                s.values = grid_.values_generation();
            }
            s.textures.upload_labels(g);
            s.grid = grid_.generation();
        }
        if (s.tables != tables_generation_) {
            s.tables = kNotUploaded;
            s.textures.upload_blocks(occupancy_);
            s.textures.upload_tables({table_, coarse_table_, refined_table_, coarse_refined_table_}, occlusion_,
                                     boundaries_, shading_);
            s.tables = tables_generation_;
        }
    }

    // One kind of draw over the grid, in bands of rows, into s's targets:
    // colour and depth, or (seen) what labels [base, base + 32)
    // contributed.  False when cancelled.
    bool cast(ContextState &s, const arbor_render_request_v2 &request, const raycast::VoxelGrid &g,
              const RayGrid &grid, const sdk::Task &task, uint32_t base, bool seen)
    {
        const raycast::Shading shading = raycast::Shading::from(params());
        unsigned variant = 0;
        if (s.textures.labelled())
            variant |= kLabelled;
        if (s.textures.resolvable() && params().flag("sample-labels"))
            variant |= kResolve | (grid.coarse ? 0u : kRefined);
        if (params().flag("sample-gradients"))
            variant |= kSmooth | (g.thick_slices ? kIsotropic : 0u);
        if (shading.enabled)
            variant |= kShaded;
        if (boundaries_.active())
            variant |= kBoundary;
        if (params().flag("jitter"))
            variant |= kJitter;
        if (shading.enabled && occlusion_strength_ > 0)
            variant |= kOcclusion;
        if (seen)
            variant |= kVisibility;
        const GLuint program = s.programs.get(variant);
        glUseProgram(program);
        set_uniforms(program, request, g, grid, base, shading);
        const int targets = seen ? 8 : 2;
        bind_targets(s, grid.width, grid.height, targets, seen);
        glViewport(0, 0, grid.width, grid.height);
        glDisable(GL_BLEND);
        glEnable(GL_SCISSOR_TEST);
        glBindVertexArray(s.vao.get());
        const GLsizei bands = (grid.height + kBandRows - 1) / kBandRows;
        for (GLsizei b = 0; b < bands; ++b) {
            glScissor(0, b * kBandRows, grid.width, std::min(kBandRows, grid.height - b * kBandRows));
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glFinish();
            if (task.cancelled())
                return false;
            task.progress((b + 1.0) / bands, seen ? "measuring visibility" : "ray casting");
        }
        glDisable(GL_SCISSOR_TEST);
        check_gl("ray casting");
        return true;
    }

    // The colour and depth cast() drew, read back.
    static void read_image(const RayGrid &grid, float *rgba, float *depth)
    {
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glReadPixels(0, 0, grid.width, grid.height, GL_RGBA, GL_FLOAT, rgba);
        glReadBuffer(GL_COLOR_ATTACHMENT1);
        glReadPixels(0, 0, grid.width, grid.height, GL_RED, GL_FLOAT, depth);
        check_gl("reading the image back");
    }

    // What labels [base, base + 32) contributed (cast() with seen), summed
    // over the grid and added to visibility.
    static void read_visibility(const RayGrid &grid, uint32_t base, std::vector<double> &visibility)
    {
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        std::vector<float> read(4 * static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height));
        for (int k = 0; k < 8; ++k) {
            glReadBuffer(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k));
            glReadPixels(0, 0, grid.width, grid.height, GL_RGBA, GL_FLOAT, read.data());
            double sum[4] = {0, 0, 0, 0};
            for (std::size_t p = 0; p < read.size(); p += 4)
                for (int c = 0; c < 4; ++c)
                    sum[c] += read[p + static_cast<std::size_t>(c)];
            for (int c = 0; c < 4; ++c) {
                const std::size_t label = base + 4 * static_cast<std::size_t>(k) + static_cast<std::size_t>(c);
                if (label < visibility.size())
                    visibility[label] += sum[c];
            }
        }
        check_gl("reading the visibility back");
    }

    // The rays cast() drew into the host's texture, over the request's
    // region: copied, blended (supersample) or interpolated (coarse).
    void present(ContextState &s, const arbor_render_request_v2 &request, const RayGrid &grid,
                 const arbor_gl_target &target)
    {
        const GLuint program = s.programs.present();
        glUseProgram(program);
        const auto at = [&](const char *name) { return glGetUniformLocation(program, name); };
        glUniform1i(at("u_rays"), 0);
        glUniform2i(at("u_ray_count"), grid.width, grid.height);
        glUniform2f(at("u_region"), static_cast<float>(request.region_x), static_cast<float>(request.region_y));
        glUniform1i(at("u_coarse"), grid.coarse ? 1 : 0);
        glUniform2f(at("u_lattice_base"), static_cast<float>(grid.base_x), static_cast<float>(grid.base_y));
        glUniform1f(at("u_spacing"), static_cast<float>(grid.spacing));
        const bool blend = request.pass == ARBOR_RENDER_PASS_SUPERSAMPLE;
        glUniform1i(at("u_clamp"), blend ? 0 : 1);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, s.targets[0].get());
        glBindFramebuffer(GL_FRAMEBUFFER, s.output_fbo.get());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.texture, 0);
        const GLenum buffer = GL_COLOR_ATTACHMENT0;
        glDrawBuffers(1, &buffer);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the host's texture cannot be rendered into (GL_RGBA8, "
                                                    "GL_RGBA16F or GL_RGBA32F of the frame's size)");
        glViewport(0, 0, static_cast<GLsizei>(target.width), static_cast<GLsizei>(target.height));
        glEnable(GL_SCISSOR_TEST);
        glScissor(static_cast<GLint>(request.region_x), static_cast<GLint>(request.region_y),
                  static_cast<GLsizei>(request.region_width), static_cast<GLsizei>(request.region_height));
        if (blend) {
            // out = out + (sample - out) / (sample_index + 1), as in arbor.renderer/2
            const float weight = 1.0f / static_cast<float>(request.sample_index + 1);
            glEnable(GL_BLEND);
            glBlendColor(0, 0, 0, weight);
            glBlendFunc(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
        }
        glBindVertexArray(s.vao.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        check_gl("writing the host's texture");
    }

    void set_uniforms(GLuint program, const arbor_render_request_v2 &request, const raycast::VoxelGrid &g,
                      const RayGrid &grid, uint32_t base, const raycast::Shading &shading)
    {
        const auto at = [&](const char *name) { return glGetUniformLocation(program, name); };
        const auto vec3 = [&](const char *name, const raycast::Vec3 &v) {
            glUniform3f(at(name), static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
        };
        glUniform1i(at("u_values"), unit::values);
        glUniform1i(at("u_labels"), unit::labels);
        glUniform1i(at("u_normals"), unit::normals);
        glUniform1i(at("u_blocks"), unit::blocks);
        glUniform1i(at("u_lut"), unit::lut);
        glUniform1i(at("u_ranges"), unit::ranges);
        glUniform1i(at("u_factors"), unit::factors);
        glUniform1i(at("u_occlusion"), unit::occlusion);
        glUniform1i(at("u_tree"), unit::tree);
        glUniform1i(at("u_refined"), unit::refined);
        glUniform1f(at("u_gradient_scale"), g.gradient_scale);
        glUniform1f(at("u_flat_gradient"), g.flat_gradient);
        glUniform3f(at("u_resample_scale"), g.resample_scale[0], g.resample_scale[1], g.resample_scale[2]);
        glUniform1f(at("u_occlusion_strength"), occlusion_strength_);
        glUniform3fv(at("u_occlusion_world"), raycast::LocalOcclusion::kDirections, occlusion_.world()[0].data());
        glUniform3fv(at("u_occlusion_step"), raycast::LocalOcclusion::kDirections, occlusion_.steps()[0].data());
        glUniform3i(at("u_dims"), static_cast<GLint>(g.nx), static_cast<GLint>(g.ny), static_cast<GLint>(g.nz));
        vec3("u_origin", g.origin);
        float to_voxel[9];
        for (int i = 0; i < 9; ++i)
            to_voxel[i] = static_cast<float>(g.to_voxel[i]);
        glUniformMatrix3fv(at("u_to_voxel"), 1, GL_TRUE, to_voxel); // row-major
        const auto &lo = occupancy_.content_low(), &hi = occupancy_.content_high();
        vec3("u_content_low", {lo[0], lo[1], lo[2]});
        vec3("u_content_high", {hi[0], hi[1], hi[2]});
        const raycast::Camera camera(*request.camera, request.frame_width, request.frame_height);
        vec3("u_eye", camera.position());
        vec3("u_forward", camera.forward());
        vec3("u_right", camera.right());
        vec3("u_up", camera.up());
        glUniform1i(at("u_perspective"), camera.perspective() ? 1 : 0);
        glUniform1f(at("u_half"), static_cast<float>(camera.half_height()));
        glUniform1f(at("u_aspect"), static_cast<float>(camera.aspect()));
        glUniform2f(at("u_frame"), static_cast<float>(request.frame_width), static_cast<float>(request.frame_height));
        glUniform2f(at("u_base"), static_cast<float>(grid.base_x), static_cast<float>(grid.base_y));
        glUniform1f(at("u_spacing"), static_cast<float>(grid.spacing));
        glUniform2f(at("u_subpixel"), static_cast<float>(grid.subpixel_x), static_cast<float>(grid.subpixel_y));
        glUniform1f(at("u_shift"), static_cast<float>(grid.shift));
        glUniform1f(at("u_step"), static_cast<float>(step_ * (grid.coarse ? raycast::kCoarseStep : 1.0)));
        glUniform1f(at("u_termination"), static_cast<float>(params().number("termination")));
        glUniform4fv(at("u_background"), 1, request.background);
        glUniform1f(at("u_ambient"), shading.ambient);
        glUniform1f(at("u_diffuse"), shading.diffuse);
        glUniform1i(at("u_visibility_base"), static_cast<GLint>(base));
    }

    // Colour and depth targets (or eight visibility targets) of at least
    // width x height on the framebuffer.
    static void bind_targets(ContextState &s, GLsizei width, GLsizei height, int count, bool visibility)
    {
        if (width > s.target_width || height > s.target_height) {
            s.target_width = std::max(width, s.target_width);
            s.target_height = std::max(height, s.target_height);
            for (Texture &t : s.targets)
                t.reset();
        }
        glBindFramebuffer(GL_FRAMEBUFFER, s.fbo.get());
        GLenum buffers[8];
        for (int k = 0; k < 8; ++k) {
            // Targets 0 and 1: colour and depth; 2-9: visibility.
            const int index = visibility ? 2 + k : k;
            if (k < count) {
                Texture &t = s.targets[static_cast<std::size_t>(index)];
                if (!t) {
                    t = make_texture();
                    glBindTexture(GL_TEXTURE_2D, t.get());
                    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
                    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
                    const bool single = !visibility && k == 1;
                    glTexImage2D(GL_TEXTURE_2D, 0, single ? GL_R32F : GL_RGBA32F, s.target_width, s.target_height, 0,
                                 single ? GL_RED : GL_RGBA, GL_FLOAT, nullptr);
                    check_gl("allocating the image");
                }
                glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k), GL_TEXTURE_2D,
                                       t.get(), 0);
                buffers[k] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k);
            } else {
                glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k), GL_TEXTURE_2D, 0, 0);
                buffers[k] = GL_NONE;
            }
        }
        glDrawBuffers(8, buffers);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("the offscreen framebuffer is incomplete");
    }

    // FULL writes the pixels; SUPERSAMPLE blends the new sample in.
    static void write_pixels(const std::vector<float> &rgba, const std::vector<float> &depth, uint32_t sample,
                             arbor_image &out)
    {
        const int64_t depth_stride = raycast::depth_stride_of(out);
        const float blend = sample ? 1.0f / static_cast<float>(sample + 1) : 1.0f;
        for (uint32_t y = 0; y < out.height; ++y) {
            float *row = out.rgba + static_cast<int64_t>(y) * out.row_stride;
            const float *in = &rgba[4 * static_cast<std::size_t>(y) * out.width];
            if (sample) {
                for (uint32_t i = 0; i < 4 * out.width; ++i)
                    row[i] += blend * (in[i] - row[i]);
                continue;
            }
            for (uint32_t i = 0; i < 4 * out.width; ++i)
                row[i] = std::clamp(in[i], 0.0f, 1.0f);
            if (out.depth)
                for (uint32_t x = 0; x < out.width; ++x) {
                    const float d = depth[static_cast<std::size_t>(y) * out.width + x];
                    out.depth[static_cast<int64_t>(y) * depth_stride + x] =
                        d < 0 ? std::numeric_limits<float>::infinity() : d;
                }
        }
    }

    std::unique_ptr<GlThread> gl_;
    std::unique_ptr<ContextState> own_;  // in gl_'s context
    std::unique_ptr<ContextState> host_; // in the host's (arbor.renderer-gl/1)

    raycast::VoxelGridCache grid_;
    raycast::BlockStatistics blocks_;
    raycast::ClassTable table_, coarse_table_, refined_table_, coarse_refined_table_;
    raycast::Occupancy occupancy_;
    raycast::BoundaryEmphasis boundaries_;
    raycast::LocalOcclusion occlusion_;
    float occlusion_strength_ = 0.0f;
    bool occlusion_current_ = false; // occlusion_ built for the current tables
    raycast::Shading shading_;
    raycast::CoarseRate coarse_rate_;
    uint64_t prepared_grid_ = kNotUploaded; // the grid generation blocks_ and boundaries_ were built for
    uint64_t tables_generation_ = 0;
    uint64_t tf_revision_ = 0;
    double step_ = -1.0, emphasis_ = -1.0;
};

} // namespace

sdk::Instance *create_gl_ray_caster(const arbor_host *host)
{
    return new GlRayCaster(host);
}

} // namespace arbor::glraycast
