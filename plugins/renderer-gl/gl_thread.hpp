// gl_thread.hpp - the thread an OpenGL context is current on.  The host may
// call a renderer from a different thread each time (renderer.h); every GL
// call of this plugin runs here instead, one job at a time.
#pragma once

#include "egl_context.hpp"

#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace arbor::glraycast {

class GlThread {
public:
    // Starts the thread and makes its context; throws what that threw.
    GlThread();
    // Ends the thread; the context is destroyed there.  Delete GL objects
    // with run() before.
    ~GlThread();
    GlThread(const GlThread &) = delete;
    GlThread &operator=(const GlThread &) = delete;

    // Runs job on the thread and waits; rethrows what it threw.
    void run(const std::function<void()> &job);
    const EglContext &context() const { return *context_; }

private:
    void loop();

    std::unique_ptr<EglContext> context_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void()> *job_ = nullptr;
    std::exception_ptr failure_;
    bool finished_ = false, stop_ = false, started_ = false;
    std::thread thread_;
};

} // namespace arbor::glraycast
