// raycast_programs.hpp - the ray casting shader (resources/shaders,
// embedded at build time) compiled once per variant: which of LABELLED,
// RESOLVE, REFINE, SMOOTH, FIELD, SHADED, BOUNDARY, JITTER, VISIBILITY and
// OCCLUSION it is built with; and the present program
// (arbor.renderer-gl/1).
#pragma once

#include "gl_objects.hpp"

#include <map>
#include <string>

namespace arbor::glraycast {

enum Variant : unsigned {
    kLabelled = 1u << 0,
    kShaded = 1u << 1,
    kBoundary = 1u << 2,
    kJitter = 1u << 3,
    kVisibility = 1u << 4,
    kOcclusion = 1u << 5,
    kResolve = 1u << 6, // labels per sample
    kSmooth = 1u << 7,  // gradients per sample
    kIsotropic = 1u << 8, // on thick slices: the gradient as on isotropic voxels
    kRefined = 1u << 9, // a step in a mixed cell as four samples (not coarse)
};

class RaycastPrograms {
public:
    // The program of this variant, compiled and linked on first use.
    GLuint get(unsigned variant);
    // The program that writes a pass's rays into the host's frame texture.
    GLuint present();
    void clear()
    {
        programs_.clear();
        present_.reset();
    }

private:
    std::map<unsigned, Program> programs_;
    Program present_;
};

} // namespace arbor::glraycast
