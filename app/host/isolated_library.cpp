#include "isolated_library.hpp"

#include "host_services.hpp"
#include "isolated_plugin.hpp"
#include "plugin_library.hpp"

#include <cstring>

namespace arbor {

using namespace isolation;

struct IsolatedLibrary::OwnedDescriptor {
    arbor_plugin_descriptor descriptor{};
    std::string id, kind, name, version, vendor, description, url;
    bool null[7] = {};
    void point()
    {
        const std::string *s[] = {&id, &kind, &name, &version, &vendor, &description, &url};
        const char **f[] = {&descriptor.id,      &descriptor.kind,        &descriptor.name, &descriptor.version,
                            &descriptor.vendor, &descriptor.description, &descriptor.url};
        for (int i = 0; i < 7; ++i)
            *f[i] = null[i] ? nullptr : s[i]->c_str();
    }
};

IsolatedLibrary::IsolatedLibrary(const std::filesystem::path &path, const IsolationSettings &settings)
    : IsolatedLibrary(path, settings, true)
{
    std::lock_guard lock(mutex_);
    process_ = start();
}

IsolatedLibrary::IsolatedLibrary(const std::filesystem::path &path, const IsolationSettings &settings, bool)
    : path_(path), name_(path.filename().string()), settings_(settings)
{
}

std::unique_ptr<IsolatedLibrary> IsolatedLibrary::begin(const std::filesystem::path &path,
                                                        const IsolationSettings &settings)
{
    std::unique_ptr<IsolatedLibrary> lib(new IsolatedLibrary(path, settings, true));
    lib->pending_ = lib->start_process();
    return lib;
}

void IsolatedLibrary::finish()
{
    std::lock_guard lock(mutex_);
    const Started started = std::move(pending_);
    pending_ = {};
    process_ = finish_start(started);
}

IsolatedLibrary::~IsolatedLibrary()
{
    std::lock_guard lock(mutex_);
    process_.reset();
}

// A new process asked to load the library.
IsolatedLibrary::Started IsolatedLibrary::start_process()
{
    Started started;
    try {
        started.process = std::make_shared<PluginProcess>(settings_, name_);
    } catch (const std::exception &e) {
        throw PluginRefused(std::string("cannot run isolated: ") + e.what());
    }
    ++starts_;
    MessageWriter w(started.process->window(0) + kRequestAt, kRequestBytes);
    w.put_string(path_.c_str());
    started.posted = started.process->post(0, Op::Load, w.size());
    return started;
}

// The load's answer; at the first start the library's descriptors are read
// (later starts load the same file).
std::shared_ptr<PluginProcess> IsolatedLibrary::finish_start(const Started &started)
{
    const std::shared_ptr<PluginProcess> &process = started.process;
    if (!process)
        throw PluginRefused("was never started");
    const std::lock_guard control(process->control_mutex);
    HostIdentity library_log(name_);
    const std::string failure = process->wait(0, started.posted, nullptr, library_log.get());
    if (!failure.empty())
        throw PluginRefused(failure + " while loading (dlopen, entry.init)");
    try {
        const ChannelHeader &h = process->header(0);
        MessageReader r(process->window(0) + kReplyAt, std::min(h.reply_size, kReplyBytes));
        const int32_t status = r.get<int32_t>();
        const std::string reason = r.get_string();
        if (status != 0)
            throw PluginRefused(reason);
        arbor_version v{};
        v.major = r.get<uint32_t>();
        v.minor = r.get<uint32_t>();
        v.patch = r.get<uint32_t>();
        const uint32_t count = r.get<uint32_t>();
        if (count > 1000)
            throw PluginRefused("claims " + std::to_string(count) + " plugins (at most 1000)");
        std::vector<std::unique_ptr<OwnedDescriptor>> found;
        for (uint32_t i = 0; i < count; ++i) {
            if (r.get<uint32_t>() == 0) {
                found.push_back(nullptr);
                continue;
            }
            auto d = std::make_unique<OwnedDescriptor>();
            d->descriptor.struct_size = r.get<uint32_t>();
            d->descriptor.flags = r.get<arbor_plugin_flags>();
            std::string *s[] = {&d->id, &d->kind, &d->name, &d->version, &d->vendor, &d->description, &d->url};
            for (int f = 0; f < 7; ++f)
                *s[f] = r.get_string(&d->null[f]);
            d->point();
            found.push_back(std::move(d));
        }
        if (starts_ == 1) {
            abi_version_ = v;
            descriptors_ = std::move(found);
            for (const auto &d : descriptors_)
                descriptor_pointers_.push_back(d ? &d->descriptor : nullptr);
        }
    } catch (const WireError &e) {
        throw PluginRefused(std::string("its process answered the load garbled: ") + e.what());
    }
    return process;
}

std::shared_ptr<PluginProcess> IsolatedLibrary::process()
{
    std::lock_guard lock(mutex_);
    if (!process_ || !process_->alive()) {
        process_.reset(); // the dead one's resources go first
        try {
            process_ = start();
        } catch (const PluginRefused &e) {
            throw std::runtime_error(std::string("could not be restarted: ") + e.what());
        }
        log_message(ARBOR_LOG_INFO, name_, "restarted in a new process (pid " + std::to_string(process_->pid()) + ")");
    }
    return process_;
}

arbor_status IsolatedLibrary::create_plugin(const arbor_host *host, const char *plugin_id, arbor_plugin **out)
{
    *out = nullptr;
    const arbor_plugin_descriptor *descriptor = nullptr;
    for (const arbor_plugin_descriptor *d : descriptor_pointers_)
        if (d && d->id && plugin_id && std::strcmp(d->id, plugin_id) == 0)
            descriptor = d;
    if (!descriptor)
        return ARBOR_ERROR_NOT_FOUND;
    return create_proxy_plugin(*this, host, descriptor, out);
}

} // namespace arbor
