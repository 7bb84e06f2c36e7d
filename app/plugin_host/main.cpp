// `arbor-plugin-host`: the process an isolated plugin library runs in.
// Started by the host (host/plugin_process.cpp), never by people:
//
//   arbor-plugin-host --arena-fd 3 --arena-bytes N --lifeline-fd 4 --memory-limit BYTES --library NAME
//
// It maps the arena the host shares, loads the library when asked on
// channel 0 and serves it there ([main-thread] calls: init, descriptors,
// create, deinit); each instance gets a thread on its own channel
// (instance_server.hpp).  It leaves when the host is gone (its lifeline
// pipe reads end-of-file), ignores the terminal's Ctrl-C (the host turns it
// into cancellation of the calls in progress), keeps
// its data segment under the memory limit (a runaway allocation fails
// here, not in the host), and announces a fatal signal in the arena before
// it dies of it, so the host learns at once.
#include "channel_services.hpp"
#include "instance_server.hpp"

#include "host/descriptor_rules.hpp"
#include "host/isolation_wire.hpp"

#include <arbor/arbor.h>

#include <dlfcn.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <thread>

using namespace arbor;
using namespace arbor::isolation;
using namespace arbor::plugin_host;

namespace {

uint8_t *g_arena = nullptr;
uint64_t g_window_bytes = 0;

uint8_t *window(uint32_t channel) { return g_arena + kArenaHeaderBytes + g_window_bytes * channel; }
ChannelHeader &header(uint32_t channel) { return *reinterpret_cast<ChannelHeader *>(window(channel)); }

// Announce the signal, wake every waiting host thread, then die of it.
void on_fatal_signal(int signal)
{
    auto &arena = *reinterpret_cast<ArenaHeader *>(g_arena);
    arena.crash_signal.store(signal);
    for (uint32_t c = 0; c < kMaxChannels; ++c)
        futex_wake(header(c).reply);
    ::signal(signal, SIG_DFL);
    raise(signal);
}

void install_fatal_handlers()
{
    static char stack[64 * 1024];
    stack_t ss{};
    ss.ss_sp = stack;
    ss.ss_size = sizeof stack;
    sigaltstack(&ss, nullptr);
    for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) {
        struct sigaction action {};
        action.sa_handler = on_fatal_signal;
        action.sa_flags = SA_ONSTACK | SA_NODEFER;
        sigaction(s, &action, nullptr);
    }
}

struct Library {
    void *handle = nullptr;
    const arbor_plugin_entry *entry = nullptr;
    bool initialised = false;
};

// Loads the library and describes its plugins into the reply.
int32_t load(Library &lib, const std::string &path, const ChannelLog &log, MessageWriter &w, std::string &reason)
{
    lib.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!lib.handle) {
        const char *e = dlerror();
        reason = std::string("cannot be loaded: ") + (e ? e : "unknown dlopen error");
        return 1;
    }
    const void *symbol = dlsym(lib.handle, ARBOR_ENTRY_SYMBOL);
    if (!symbol) {
        reason = "has no '" ARBOR_ENTRY_SYMBOL "' entry symbol; not an Arbor plugin";
        return 1;
    }
    lib.entry = static_cast<const arbor_plugin_entry *>(symbol);
    if (reason = check_entry_record(lib.entry); !reason.empty())
        return 1;
    const arbor_status s = lib.entry->init(log.get(), path.c_str());
    if (s != ARBOR_OK) {
        reason = std::string("init failed (") + arbor_status_name(s) + ")";
        return 1;
    }
    lib.initialised = true;
    const uint32_t count = lib.entry->plugin_count();
    if (count == 0) {
        reason = "holds no plugins";
        return 1;
    }
    w.put(lib.entry->abi_version.major);
    w.put(lib.entry->abi_version.minor);
    w.put(lib.entry->abi_version.patch);
    w.put(count);
    for (uint32_t i = 0; i < count && i <= 1000; ++i) {
        const arbor_plugin_descriptor *d = lib.entry->plugin_descriptor(i);
        w.put<uint32_t>(d ? 1 : 0);
        if (!d)
            continue;
        w.put(d->struct_size);
        w.put(d->flags);
        for (const char *s : {d->id, d->kind, d->name, d->version, d->vendor, d->description})
            w.put_string(s, 4096);
        w.put_string(ARBOR_HAS_FIELD(arbor_plugin_descriptor, d->struct_size, url) ? d->url : nullptr, 4096);
    }
    return 0;
}

struct Instance {
    std::unique_ptr<ChannelLog> log;
    std::unique_ptr<InstanceServer> server;
};

} // namespace

int main(int argc, char **argv)
{
    int fd = -1, lifeline = -1;
    uint64_t arena_bytes = 0, memory_limit = 0;
    std::string library_name = "?";
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--arena-fd")
            fd = std::atoi(argv[i + 1]);
        else if (a == "--arena-bytes")
            arena_bytes = std::strtoull(argv[i + 1], nullptr, 10);
        else if (a == "--lifeline-fd")
            lifeline = std::atoi(argv[i + 1]);
        else if (a == "--memory-limit")
            memory_limit = std::strtoull(argv[i + 1], nullptr, 10);
        else if (a == "--library")
            library_name = argv[i + 1];
    }
    if (fd < 0 || arena_bytes < kArenaHeaderBytes) {
        std::fprintf(stderr, "arbor-plugin-host: started by Arbor to run an isolated plugin; not for direct use\n");
        return 2;
    }
    if (lifeline >= 0)
        std::thread([lifeline] {
            char byte;
            while (read(lifeline, &byte, 1) != 0 && errno == EINTR) {
            }
            _exit(0); // end of file: the host is gone
        }).detach();
    signal(SIGINT, SIG_IGN);
    signal(SIGQUIT, SIG_IGN);
    prctl(PR_SET_NAME, "arbor-plugin", 0, 0, 0);
    rlimit no_core{0, 0};
    setrlimit(RLIMIT_CORE, &no_core);
    if (memory_limit) {
        rlimit data{memory_limit, memory_limit};
        setrlimit(RLIMIT_DATA, &data);
    }
    void *map = mmap(nullptr, arena_bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_NORESERVE, fd, 0);
    if (map == MAP_FAILED) {
        std::perror("arbor-plugin-host: mapping the shared arena");
        return 4;
    }
    close(fd);
    g_arena = static_cast<uint8_t *>(map);
    const auto &arena = *reinterpret_cast<const ArenaHeader *>(g_arena);
    if (arena.magic != kArenaMagic)
        return 5;
    g_window_bytes = arena.window_bytes;
    install_fatal_handlers();

    Library lib;
    ChannelLog library_log(&header(0));
    std::map<uint32_t, Instance> instances;
    ChannelHeader &h = header(0);
    uint32_t seen = 0;
    for (bool running = true; running;) {
        while (h.request.load(std::memory_order_acquire) == seen)
            futex_wait(h.request, seen, -1);
        seen = h.request.load(std::memory_order_acquire);
        MessageReader r(window(0) + kRequestAt, std::min(h.request_size, kRequestBytes));
        MessageWriter w(window(0) + kReplyAt, kReplyBytes);
        MessageWriter out(window(0) + kReplyAt + 8192, kReplyBytes - 8192);
        int32_t status = 0;
        std::string reason;
        try {
            switch (static_cast<Op>(h.op)) {
            case Op::Load:
                status = load(lib, r.get_string(), library_log, out, reason);
                break;
            case Op::Create: {
                const uint32_t channel = r.get<uint32_t>();
                const std::string id = r.get_string();
                if (channel == 0 || channel >= kMaxChannels || instances.count(channel) || !lib.initialised)
                    throw std::runtime_error("a create request for a channel in use");
                Instance instance;
                instance.log = std::make_unique<ChannelLog>(&header(channel));
                arbor_plugin *plugin = nullptr;
                status = lib.entry->create_plugin(instance.log->get(), id.c_str(), &plugin);
                if (status != ARBOR_OK) {
                    reason = "could not create an instance (" + std::string(arbor_status_name(status)) + ")";
                    break;
                }
                if (reason = check_instance_record(plugin); !reason.empty()) {
                    status = ARBOR_ERROR_INTERNAL; // a malformed record: leak it rather than crash
                    break;
                }
                instance.server = std::make_unique<InstanceServer>(plugin, &header(channel), window(channel));
                try {
                    instance.server->describe(out);
                } catch (const std::exception &e) {
                    status = ARBOR_ERROR_INTERNAL;
                    reason = e.what();
                    break; // the server (and the instance) go with `instance`
                }
                instances.emplace(channel, std::move(instance));
                break;
            }
            case Op::Destroy:
                instances.erase(r.get<uint32_t>());
                break;
            case Op::Unload:
                instances.clear();
                if (lib.initialised)
                    lib.entry->deinit();
                lib.initialised = false;
                running = false;
                break;
            default:
                throw std::runtime_error("an unknown request on the library channel");
            }
        } catch (const std::exception &e) {
            status = ARBOR_ERROR_INTERNAL;
            reason = std::string("arbor-plugin-host: ") + e.what();
        }
        w.put(status);
        w.put_string(reason.substr(0, 4000));
        const uint64_t head = w.size();
        if (status == 0)
            std::memmove(window(0) + kReplyAt + head, window(0) + kReplyAt + 8192, out.size());
        h.reply_size = head + (status == 0 ? out.size() : 0);
        h.reply.store(seen, std::memory_order_release);
        futex_wake(h.reply);
    }
    return 0;
}
