// arbor/sdk/importer.hpp - base class for importer plugins written in C++.
//
// Derive, pass the suffixes to the constructor, and implement probe,
// read_header and read_voxels.  Argument checks common to every importer
// (NULL pointers, record sizes, a voxel buffer that matches the header) are
// done here, so conformance checks pass without code in each plugin.
#pragma once

#include <arbor/importer.h>

#include "instance.hpp"
#include "task.hpp"

#include <cstdint>
#include <string>

namespace arbor::sdk {

class Importer : public Instance {
public:
    Importer(const arbor_plugin_descriptor &descriptor, const arbor_host *host,
             const char *suffixes, std::vector<ParamSpec> params = {})
        : Instance(descriptor, host, std::move(params))
    {
        table_.suffixes = suffixes;
        table_.probe = &c_probe;
        table_.read_header = &c_read_header;
        table_.read_voxels = &c_read_voxels;
    }

    // Confidence 0..100; `head` may be empty.
    virtual int32_t probe(const std::string &path, const uint8_t *head, uint64_t head_size) = 0;
    // Fill everything but strides and voxels.
    virtual void read_header(const std::string &path, const Task &task, arbor_volume &out) = 0;
    // Fill volume.voxels (contiguous, allocated by the host from the header).
    virtual void read_voxels(const std::string &path, const Task &task, arbor_volume &volume) = 0;

protected:
    const void *find_interface(std::string_view id) const override
    {
        if (id == ARBOR_INTERFACE_IMPORTER)
            return &table_;
        return Instance::find_interface(id);
    }

private:
    static Importer &self_of(Instance &i) { return static_cast<Importer &>(i); }

    static void require_path(const char *path)
    {
        if (!path || !*path)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "path is NULL or empty");
    }

    static arbor_status c_probe(arbor_plugin *plugin, const char *path, const uint8_t *head,
                                uint64_t head_size, int32_t *confidence)
    {
        return guarded(plugin, [&](Instance &self) {
            require_path(path);
            if (!confidence)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "confidence is NULL");
            if (!head && head_size > 0)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "head is NULL but head_size is not 0");
            *confidence = 0;
            const int32_t c = self_of(self).probe(path, head, head_size);
            *confidence = c < 0 ? 0 : (c > 100 ? 100 : c);
        });
    }

    static arbor_status c_read_header(arbor_plugin *plugin, const char *path, arbor_task *task,
                                      arbor_volume *out)
    {
        return guarded(plugin, [&](Instance &self) {
            require_path(path);
            require_record(out, "volume");
            const uint32_t size = out->struct_size;
            *out = arbor_volume{};
            out->struct_size = size;
            out->value_scale = 1.0;
            out->value_unit = "";
            self_of(self).read_header(path, Task(task), *out);
        });
    }

    static arbor_status c_read_voxels(arbor_plugin *plugin, const char *path, arbor_task *task,
                                      arbor_volume *volume)
    {
        return guarded(plugin, [&](Instance &self) {
            require_path(path);
            require_record(volume, "volume");
            if (!volume->voxels)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "volume has no voxel buffer");
            const int64_t s = arbor_voxel_size(volume->voxel_type);
            if (s == 0)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "volume has an unknown voxel type");
            for (int a = 0; a < 3; ++a)
                if (volume->dims[a] <= 0)
                    fail(ARBOR_ERROR_INVALID_ARGUMENT, "volume dims must be positive");
            if (volume->strides[0] != s || volume->strides[1] != s * volume->dims[0] ||
                volume->strides[2] != s * volume->dims[0] * volume->dims[1])
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "volume strides are not contiguous");
            self_of(self).read_voxels(path, Task(task), *volume);
        });
    }

    arbor_importer_v1 table_{};
};

} // namespace arbor::sdk
