// counting_surface.hpp - a FrameSurface with no OpenGL behind it, for tests
// of how the progressive view uses one: it counts the calls, and its
// canvas names no texture (a renderer asked to draw there fails).
#pragma once

#include "pipeline/frame_surface.hpp"

#include <atomic>

namespace arbor::test {

struct CountingSurface final : pipeline::FrameSurface {
    std::atomic<int> made_current{0}, released{0}, canvases{0}, snapshots{0};

    void make_current() override { ++made_current; }
    void release_current() override { ++released; }
    GlFrame canvas(uint32_t width, uint32_t height) override
    {
        ++canvases;
        return {0, width, height};
    }
    std::shared_ptr<const GlFrame> snapshot() override
    {
        ++snapshots;
        return std::make_shared<GlFrame>();
    }
};

} // namespace arbor::test
