#include "plugin_instance.hpp"

#include "core/cancelled.hpp"

#include <map>

namespace arbor {

namespace {

// One mutex per serialised plugin id, for the life of the process.
std::mutex &plugin_mutex(const std::string &id)
{
    static std::mutex table_mutex;
    static std::map<std::string, std::unique_ptr<std::mutex>> table;
    std::lock_guard lock(table_mutex);
    std::unique_ptr<std::mutex> &m = table[id];
    if (!m)
        m = std::make_unique<std::mutex>();
    return *m;
}

} // namespace

PluginInstance::PluginInstance(arbor_plugin *plugin, std::unique_ptr<HostIdentity> host)
    : plugin_(plugin), host_(std::move(host))
{
    if (plugin_ && plugin_->descriptor && plugin_->descriptor->id &&
        (plugin_->descriptor->flags & ARBOR_PLUGIN_FLAG_SERIALIZE))
        serial_ = &plugin_mutex(plugin_->descriptor->id);
}

std::unique_lock<std::mutex> PluginInstance::serial() const
{
    return serial_ ? std::unique_lock<std::mutex>(*serial_) : std::unique_lock<std::mutex>();
}

PluginInstance::~PluginInstance()
{
    release();
}

PluginInstance::PluginInstance(PluginInstance &&other) noexcept
    : plugin_(other.plugin_), serial_(other.serial_), host_(std::move(other.host_))
{
    other.plugin_ = nullptr;
}

PluginInstance &PluginInstance::operator=(PluginInstance &&other) noexcept
{
    if (this != &other) {
        release();
        plugin_ = other.plugin_;
        serial_ = other.serial_;
        host_ = std::move(other.host_);
        other.plugin_ = nullptr;
    }
    return *this;
}

void PluginInstance::release()
{
    if (plugin_)
        call("plugin.destroy", plugin_->destroy);
    plugin_ = nullptr;
}

const arbor_params_v1 *PluginInstance::params() const
{
    const auto *p = static_cast<const arbor_params_v1 *>(
        call("plugin.get_interface", plugin_->get_interface, ARBOR_INTERFACE_PARAMS));
    if (p && (!p->count || !p->describe || !p->get || !p->set))
        return nullptr;
    return p;
}

std::vector<const arbor_param_desc *> PluginInstance::param_descriptions() const
{
    std::vector<const arbor_param_desc *> out;
    if (const arbor_params_v1 *p = params())
        for (uint32_t i = 0, n = call("params.count", p->count); i < n; ++i)
            if (const arbor_param_desc *d = call("params.describe", p->describe, i))
                out.push_back(d);
    return out;
}

const arbor_param_desc *PluginInstance::find_param(const std::string &param_id) const
{
    for (const arbor_param_desc *d : param_descriptions())
        if (param_id == d->id)
            return d;
    return nullptr;
}

void PluginInstance::set_param(const std::string &param_id, const arbor_param_value &value)
{
    const arbor_params_v1 *p = params();
    if (!p)
        throw PluginError(ARBOR_ERROR_NOT_FOUND, id() + " has no parameters");
    check(call("params.set", p->set, param_id.c_str(), &value), "setting parameter '" + param_id + "'");
}

arbor_param_value PluginInstance::get_param(const std::string &param_id) const
{
    const arbor_params_v1 *p = params();
    if (!p)
        throw PluginError(ARBOR_ERROR_NOT_FOUND, id() + " has no parameters");
    arbor_param_value v{};
    v.struct_size = sizeof(v);
    check(call("params.get", p->get, param_id.c_str(), &v), "reading parameter '" + param_id + "'");
    return v;
}

std::string PluginInstance::last_error() const
{
    const char *e = plugin_->last_error ? call("plugin.last_error", plugin_->last_error) : nullptr;
    return e ? e : "";
}

void PluginInstance::check(arbor_status status, const std::string &doing) const
{
    if (status == ARBOR_OK)
        return;
    if (status == ARBOR_ERROR_CANCELLED)
        throw Cancelled();
    std::string reason = last_error();
    if (reason.empty())
        reason = arbor_status_name(status);
    throw PluginError(status, id() + ": " + doing + ": " + reason);
}

} // namespace arbor
