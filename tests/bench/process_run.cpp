#include "process_run.hpp"

#include "core/stopwatch.hpp"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

extern char **environ;

namespace arbor::bench {

ProcessRun run_process(const std::vector<std::string> &argv)
{
    ProcessRun run;
    std::vector<char *> args;
    for (const std::string &a : argv)
        args.push_back(const_cast<char *>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    Stopwatch clock;
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
        run.error = "cannot start " + argv[0] + ": " + std::strerror(spawned);
        return run;
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    run.seconds = clock.lap();
    const std::string what = argv.size() > 1 ? argv[0] + " " + argv[1] : argv[0];
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
        run.ok = true;
    else if (WIFSIGNALED(status))
        run.error = what + " killed by signal " + std::to_string(WTERMSIG(status));
    else
        run.error = what + " exited with status " + std::to_string(WEXITSTATUS(status));
    return run;
}

} // namespace arbor::bench
