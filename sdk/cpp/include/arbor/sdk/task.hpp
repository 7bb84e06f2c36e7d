// arbor/sdk/task.hpp - C++ view of an arbor_task (progress, cancellation,
// host memory).  Part of the optional C++ layer of the SDK.
#pragma once

#include <arbor/host.h>

#include "error.hpp"

#include <cstdint>

namespace arbor::sdk {

class Task {
public:
    explicit Task(arbor_task *task) : task_(task) {}

    // Reports progress; throws Error(ARBOR_ERROR_CANCELLED) when the host
    // asked to cancel.
    void progress(double fraction, const char *stage = nullptr) const
    {
        if (task_ && task_->progress && task_->progress(task_, fraction, stage))
            fail(ARBOR_ERROR_CANCELLED, "cancelled");
    }

    bool cancelled() const { return task_ && task_->cancelled && task_->cancelled(task_); }

    void throw_if_cancelled() const
    {
        if (cancelled())
            fail(ARBOR_ERROR_CANCELLED, "cancelled");
    }

    // Host-owned memory for variable-size outputs; throws when refused.
    void *allocate(std::uint64_t size) const
    {
        void *p = (task_ && task_->allocate) ? task_->allocate(task_, size) : nullptr;
        if (!p)
            fail(ARBOR_ERROR_OUT_OF_MEMORY, "the host refused " + std::to_string(size) + " bytes");
        return p;
    }

private:
    arbor_task *task_;
};

} // namespace arbor::sdk
