// arbor/sdk/instance.hpp - a C++ base class for plugin instances.
//
// Part of the optional C++ layer of the SDK.  An Instance owns the
// arbor_plugin record the host sees, its parameters and its last-error text.
// Kind adapters (importer.hpp, filter.hpp, ...) derive from it and expose the
// interface table of their kind; every call from the host runs through
// Instance::guarded, which turns exceptions into status codes so none crosses
// the C ABI.
#pragma once

#include <arbor/plugin.h>
#include <arbor/params.h>

#include "error.hpp"
#include "params.hpp"
#include "record_size.hpp"

#include <cstring>
#include <iterator>
#include <new>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace arbor::sdk {

class Instance {
public:
    Instance(const arbor_plugin_descriptor &descriptor, const arbor_host *host,
             std::vector<ParamSpec> params = {})
        : host_(host), params_(std::move(params))
    {
        plugin_.struct_size = sizeof(arbor_plugin);
        plugin_.descriptor = &descriptor;
        plugin_.plugin_data = this;
        plugin_.destroy = &Instance::c_destroy;
        plugin_.get_interface = &Instance::c_get_interface;
        plugin_.last_error = &Instance::c_last_error;
    }
    virtual ~Instance() = default;
    Instance(const Instance &) = delete;
    Instance &operator=(const Instance &) = delete;

    arbor_plugin *handle() noexcept { return &plugin_; }
    const arbor_plugin_descriptor &descriptor() const { return *plugin_.descriptor; }
    ParamSet &params() { return params_; }
    const ParamSet &params() const { return params_; }

    void log(arbor_log_level level, const std::string &message) const
    {
        if (host_ && host_->log)
            host_->log(host_, level, message.c_str());
    }

    // The instance behind a handle, or nullptr for a handle that is not ours.
    static Instance *of(const arbor_plugin *plugin) noexcept
    {
        if (!plugin || plugin->destroy != &Instance::c_destroy)
            return nullptr;
        return static_cast<Instance *>(plugin->plugin_data);
    }

    // Run `body` (returning nothing) for a host call: clears the last error,
    // maps exceptions to status codes and messages.
    template <class Body>
    static arbor_status guarded(const arbor_plugin *plugin, Body &&body) noexcept
    {
        Instance *self = of(plugin);
        if (!self)
            return ARBOR_ERROR_INVALID_ARGUMENT;
        self->error_.clear();
        try {
            body(*self);
            return ARBOR_OK;
        } catch (const Error &e) {
            return self->record(e.status(), e.what());
        } catch (const std::bad_alloc &) {
            return self->record(ARBOR_ERROR_OUT_OF_MEMORY, "out of memory");
        } catch (const std::exception &e) {
            return self->record(ARBOR_ERROR_INTERNAL, e.what());
        } catch (...) {
            return self->record(ARBOR_ERROR_INTERNAL, "unknown exception");
        }
    }

    // Throws ARBOR_ERROR_INVALID_ARGUMENT unless `record` is non-null and its
    // struct_size covers at least `min_size` bytes (by default the record's
    // ARBOR_MIN_SIZE: a record from any 1.x host is accepted; read fields
    // added later only under ARBOR_HAS_FIELD).
    template <class Record>
    static void require_record(const Record *record, const char *what,
                               std::size_t min_size = min_record_size<Record>())
    {
        if (!record)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, std::string(what) + " is NULL");
        if (record->struct_size < min_size)
            fail(ARBOR_ERROR_INVALID_ARGUMENT,
                 std::string(what) + ": struct_size " + std::to_string(record->struct_size) +
                     " is smaller than " + std::to_string(min_size));
    }

protected:
    // Interface tables this instance offers; the base offers parameters.
    virtual const void *find_interface(std::string_view id) const
    {
        if (id == ARBOR_INTERFACE_PARAMS)
            return &params_table;
        return nullptr;
    }

private:
    arbor_status record(arbor_status status, const char *message)
    {
        error_ = message ? message : "";
        return status;
    }

    static void c_destroy(arbor_plugin *plugin)
    {
        delete of(plugin);
    }
    static const void *c_get_interface(const arbor_plugin *plugin, const char *id)
    {
        const Instance *self = of(plugin);
        return self && id ? self->find_interface(id) : nullptr;
    }
    static const char *c_last_error(const arbor_plugin *plugin)
    {
        const Instance *self = of(plugin);
        return self ? self->error_.c_str() : "not an instance of this plugin";
    }

    static uint32_t c_param_count(const arbor_plugin *plugin)
    {
        const Instance *self = of(plugin);
        return self ? self->params_.count() : 0;
    }
    static const arbor_param_desc *c_param_describe(const arbor_plugin *plugin, uint32_t index)
    {
        const Instance *self = of(plugin);
        return self ? self->params_.describe(index) : nullptr;
    }
    static arbor_status c_param_get(const arbor_plugin *plugin, const char *id,
                                    arbor_param_value *out)
    {
        return guarded(plugin, [&](Instance &self) {
            if (!id)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "parameter id is NULL");
            require_record(out, "parameter value");
            self.params_.get(id, *out);
        });
    }
    static arbor_status c_param_set(arbor_plugin *plugin, const char *id,
                                    const arbor_param_value *value)
    {
        return guarded(plugin, [&](Instance &self) {
            if (!id)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "parameter id is NULL");
            require_record(value, "parameter value");
            self.params_.set(id, *value);
        });
    }

    static constexpr arbor_params_v1 params_table = {&c_param_count, &c_param_describe,
                                                     &c_param_get, &c_param_set};

    arbor_plugin plugin_{};
    const arbor_host *host_;
    ParamSet params_;
    std::string error_;
};

// One plugin of a library: its descriptor and how to make an instance.
struct PluginClass {
    const arbor_plugin_descriptor *descriptor;
    Instance *(*create)(const arbor_host *host);
};

template <class T>
Instance *make_instance(const arbor_host *host)
{
    return new T(host);
}

} // namespace arbor::sdk

// Defines the library's entry symbol from a static array of PluginClass:
//     static const arbor::sdk::PluginClass kPlugins[] = {...};
//     ARBOR_SDK_DEFINE_LIBRARY(kPlugins)
#define ARBOR_SDK_DEFINE_LIBRARY(classes)                                                       \
    namespace {                                                                                 \
    arbor_status arbor_sdk_init(const arbor_host *, const char *) { return ARBOR_OK; }         \
    void arbor_sdk_deinit() {}                                                                  \
    uint32_t arbor_sdk_count() { return static_cast<uint32_t>(std::size(classes)); }           \
    const arbor_plugin_descriptor *arbor_sdk_descriptor(uint32_t index)                         \
    {                                                                                           \
        return index < std::size(classes) ? classes[index].descriptor : nullptr;               \
    }                                                                                           \
    arbor_status arbor_sdk_create(const arbor_host *host, const char *id, arbor_plugin **out)   \
    {                                                                                           \
        if (!out)                                                                               \
            return ARBOR_ERROR_INVALID_ARGUMENT;                                                \
        *out = nullptr;                                                                         \
        if (!id)                                                                                \
            return ARBOR_ERROR_INVALID_ARGUMENT;                                                \
        for (const auto &c : classes) {                                                         \
            if (std::strcmp(c.descriptor->id, id) != 0)                                         \
                continue;                                                                       \
            try {                                                                               \
                *out = c.create(host)->handle();                                                \
                return ARBOR_OK;                                                                \
            } catch (const std::bad_alloc &) {                                                  \
                return ARBOR_ERROR_OUT_OF_MEMORY;                                               \
            } catch (const std::exception &e) {                                                 \
                if (host && host->log)                                                          \
                    host->log(host, ARBOR_LOG_ERROR, e.what());                                 \
                return ARBOR_ERROR_INTERNAL;                                                    \
            }                                                                                   \
        }                                                                                       \
        return ARBOR_ERROR_NOT_FOUND;                                                           \
    }                                                                                           \
    }                                                                                           \
    ARBOR_PLUGIN_ENTRY = {sizeof(arbor_plugin_entry), ARBOR_ABI_VERSION_INIT,                   \
                          &arbor_sdk_init,            &arbor_sdk_deinit,                        \
                          &arbor_sdk_count,           &arbor_sdk_descriptor,                    \
                          &arbor_sdk_create};
