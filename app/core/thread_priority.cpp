#include "thread_priority.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>

namespace arbor {

void lower_thread_priority(int nice)
{
    if (nice <= 0)
        return;
    // PRIO_PROCESS with a thread id addresses that one thread on Linux.
    const auto tid = static_cast<id_t>(syscall(SYS_gettid));
    errno = 0;
    const int current = getpriority(PRIO_PROCESS, tid);
    if (errno != 0)
        return;
    setpriority(PRIO_PROCESS, tid, current + nice > 19 ? 19 : current + nice);
}

} // namespace arbor
