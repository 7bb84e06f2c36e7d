// context_state.hpp - what the OpenGL ray caster keeps in one context: its
// drawing objects, the ray targets and the volume's textures, with the
// generations of the data each texture was uploaded from.  The plugin has
// one for its own offscreen context (arbor.renderer/2) and one for the
// host's context (arbor.renderer-gl/1); names die in their own context.
#pragma once

#include "raycast_programs.hpp"
#include "volume_textures.hpp"

#include <array>
#include <cstdint>

namespace arbor::glraycast {

inline constexpr uint64_t kNotUploaded = ~uint64_t{0};

struct ContextState {
    VertexArray vao;
    Framebuffer fbo;        // the ray targets
    Framebuffer output_fbo; // the host's texture (arbor.renderer-gl/1)
    // Targets 0 and 1: colour and depth of the rays; 2-9: visibility.
    std::array<Texture, 10> targets;
    GLsizei target_width = 0, target_height = 0;
    RaycastPrograms programs;
    VolumeTextures textures;
    // What the textures hold: the grid's generation and values generation,
    // and the classification tables' generation.
    uint64_t grid = kNotUploaded, values = kNotUploaded, tables = kNotUploaded;

    // The vertex array and framebuffers, made once (the context is current).
    void make_objects()
    {
        if (vao)
            return;
        GLuint v = 0, f[2] = {0, 0};
        glGenVertexArrays(1, &v);
        glGenFramebuffers(2, f);
        VertexArray made_vao(v);
        Framebuffer made_fbo(f[0]), made_output(f[1]);
        check_gl("creating the framebuffer"); // on failure the names die here, in this context
        vao = std::move(made_vao);
        fbo = std::move(made_fbo);
        output_fbo = std::move(made_output);
    }
};

} // namespace arbor::glraycast
