// workstation_fixture.hpp - a Workstation on the built-in phantom through
// the plugins built in this tree, and waiting as the UI loop does.
#pragma once

#include "workstation/workstation.hpp"

#include "plugin_fixture.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

namespace arbor::workstation::test_support {

// Polls as the UI loop does until every job is done and the 3D view current.
inline void wait_idle(Workstation &ws, double seconds = 120)
{
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
        ws.poll();
        if (ws.idle())
            return;
        ASSERT_LT(std::chrono::steady_clock::now(), end) << "not idle after " << seconds << " s";
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

// The 64^3 head phantom opened in a `viewport` x `viewport` 3D view, CPU ray caster.
inline std::unique_ptr<Workstation> phantom_workstation(uint32_t viewport = 96, std::optional<std::size_t> keep = {})
{
    auto ws = std::make_unique<Workstation>(test::built_plugins(), pipeline::PipelineOptions{});
    ws->set_viewport(viewport, viewport);
    pipeline::Document d = ws->document();
    d.input.phantom = pipeline::PhantomInput{"head", 64};
    d.view.renderer.id = "cpu-raycast";
    d.cut.keep = keep;
    ws->open_document(d, "open the phantom");
    return ws;
}

// A noisy 160^3 phantom in a 48 x 48 view: its contour tree takes seconds,
// long enough to act while it is computed.
inline std::unique_ptr<Workstation> slow_phantom_workstation()
{
    auto ws = std::make_unique<Workstation>(test::built_plugins(), pipeline::PipelineOptions{});
    ws->set_viewport(48, 48);
    pipeline::Document d = ws->document();
    d.input.phantom = pipeline::PhantomInput{"head", 160, 4.0};
    d.view.renderer.id = "cpu-raycast";
    ws->open_document(d, "open");
    return ws;
}

} // namespace arbor::workstation::test_support
