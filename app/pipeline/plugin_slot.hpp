// plugin_slot.hpp - the plugin instances of one stage, kept from one of its
// jobs to the next (a renderer keeps what it prepared for the last frame, a
// generator its colour tables).  Jobs of a stage run one at a time, so an
// instance is never used by two threads at once.  A lease applies the job's
// setting to the instance and routes the plugin's log to the job while the
// job holds it.
#pragma once

#include "plugin_catalog.hpp"

#include <map>
#include <string>

namespace arbor::pipeline {

class PluginSlot {
public:
    class Lease {
    public:
        Lease(PluginInstance &instance, LogSink *log) : instance_(instance) { instance_.route_log(log); }
        ~Lease() { instance_.route_log(nullptr); }
        Lease(const Lease &) = delete;
        Lease &operator=(const Lease &) = delete;
        PluginInstance &operator*() const { return instance_; }
        PluginInstance *operator->() const { return &instance_; }

    private:
        PluginInstance &instance_;
    };

    explicit PluginSlot(const PluginCatalog &catalog) : catalog_(catalog) {}

    // The instance of setting.id (created the first time) with every value of
    // the setting applied; throws std::invalid_argument or PluginError.
    Lease lease(const PluginSetting &setting, LogSink *log)
    {
        auto it = instances_.find(setting.id);
        if (it == instances_.end())
            it = instances_.emplace(setting.id, catalog_.create(setting.id)).first;
        apply_setting(it->second, setting);
        return Lease(it->second, log);
    }

private:
    const PluginCatalog &catalog_;
    std::map<std::string, PluginInstance> instances_;
};

} // namespace arbor::pipeline
