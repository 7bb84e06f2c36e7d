// thread_priority.hpp - background work that yields to the user: the
// workstation runs its pipeline jobs and renders on threads with a higher
// nice value than its UI thread, so a frame is drawn on time even while
// every core ray-casts (threads those threads start, oneTBB's workers among
// them, inherit it: on Linux the nice value is per thread).
#pragma once

namespace arbor {

// Adds `nice` (1..19) to the calling thread's nice value; 0 does nothing.
// A failure (a system that does not allow it) leaves the priority as it was.
void lower_thread_priority(int nice);

} // namespace arbor
