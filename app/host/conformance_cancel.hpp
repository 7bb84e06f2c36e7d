// conformance_cancel.hpp - cancelling a plugin call while it runs, for
// `arbor plugin-check`: the task is cancelled a moment after the call
// starts, and what is measured is how long the plugin went on after that.
// host.h asks plugins to poll task->cancelled at least every tenth of a
// second of work and then to return ARBOR_ERROR_CANCELLED.
#pragma once

#include <arbor/arbor.h>

#include <chrono>
#include <functional>

namespace arbor {

struct CancelOutcome {
    arbor_status status = ARBOR_OK;
    bool cancelled = false;   // false: the call returned before the cancel came
    double seconds_after = 0; // from the cancel to the call's return
    double seconds = 0;       // the whole call
};

// Runs `call` with a task that is cancelled `after` into the call.
CancelOutcome cancel_mid_call(const std::function<arbor_status(arbor_task *)> &call,
                              std::chrono::milliseconds after);

} // namespace arbor
