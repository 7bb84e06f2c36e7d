// plugin_instance.hpp - an owned plugin instance and typed access to its
// interfaces and parameters.  Every failing call becomes a PluginError whose
// message names the plugin, what the host was doing and the plugin's reason;
// every call into the plugin goes through call(), so a crash in it names the
// plugin and the call (plugin_call.hpp).
#pragma once

#include "host_services.hpp"
#include "plugin_call.hpp"

#include <arbor/arbor.h>

#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace arbor {

class PluginError : public std::runtime_error {
public:
    PluginError(arbor_status status, const std::string &message)
        : std::runtime_error(message), status_(status) {}
    arbor_status status() const { return status_; }

private:
    arbor_status status_;
};

class PluginInstance {
public:
    PluginInstance(arbor_plugin *plugin, std::unique_ptr<HostIdentity> host);
    ~PluginInstance();
    PluginInstance(PluginInstance &&other) noexcept;
    PluginInstance &operator=(PluginInstance &&other) noexcept;
    PluginInstance(const PluginInstance &) = delete;
    PluginInstance &operator=(const PluginInstance &) = delete;

    arbor_plugin *get() const { return plugin_; }
    const arbor_plugin_descriptor &descriptor() const { return *plugin_->descriptor; }
    std::string id() const { return plugin_->descriptor->id; }

    // function(instance, args...), one of the plugin's functions, as the call
    // `what` ("filter.apply"): a crash inside it names the plugin and `what`.
    template <class Function, class... Args>
    auto call(const char *what, Function function, Args &&...args) const
    {
        const auto lock = serial();
        const PluginCall in(host_->source().c_str(), what);
        return function(plugin_, std::forward<Args>(args)...);
    }

    // The table of an interface; throws PluginError when it is missing.
    template <class Table>
    const Table &interface(const char *interface_id) const
    {
        const void *t = call("plugin.get_interface", plugin_->get_interface, interface_id);
        if (!t)
            throw PluginError(ARBOR_ERROR_UNSUPPORTED,
                              id() + " does not offer interface " + interface_id);
        return *static_cast<const Table *>(t);
    }

    // Parameters (empty when the plugin has none).
    const arbor_params_v1 *params() const;
    std::vector<const arbor_param_desc *> param_descriptions() const;
    const arbor_param_desc *find_param(const std::string &param_id) const;
    void set_param(const std::string &param_id, const arbor_param_value &value);
    arbor_param_value get_param(const std::string &param_id) const;

    // Held by call() around every call into the plugin: for a plugin whose
    // descriptor sets ARBOR_PLUGIN_FLAG_SERIALIZE a lock on the one mutex all
    // its instances in this process share, else no lock at all.
    std::unique_lock<std::mutex> serial() const;

    // Messages the plugin logs go to `sink` (nullptr: the host log).
    void route_log(LogSink *sink) { host_->route_log(sink); }

    // Throws Cancelled for ARBOR_ERROR_CANCELLED, PluginError unless status
    // is ARBOR_OK; `doing` says what the host
    // asked for ("reading the header of scan.nrrd").
    void check(arbor_status status, const std::string &doing) const;
    std::string last_error() const;

private:
    void release();
    arbor_plugin *plugin_ = nullptr;
    std::mutex *serial_ = nullptr; // ARBOR_PLUGIN_FLAG_SERIALIZE: the plugin's mutex
    std::unique_ptr<HostIdentity> host_;
};

} // namespace arbor
