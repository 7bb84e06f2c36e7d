#include "isolated_plugin.hpp"

#include "isolated_library.hpp"
#include "isolation_records.hpp"

#include <xxhash.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <utility>

namespace arbor {

using namespace isolation;

namespace {

// Which interfaces (and which of their functions) the instance in the
// child offers: bit i of a table's mask is its i-th function.
enum Interface : uint32_t {
    kParams,
    kImporter,
    kFilter,
    kSimplifier,
    kDepictor,
    kGenerator,
    kRenderer1,
    kRenderer2,
    kDevice,
    kInterfaces
};

// Data kept in the window from one call to the next: a renderer's volume
// and labels (one copy per revision), a filter's staged input.
struct CacheSlot {
    bool valid = false;
    uint64_t key[4] = {};
    uint64_t offset = 0, bytes = 0;
};

struct Proxy {
    arbor_plugin record{};
    IsolatedLibrary *library = nullptr;
    const arbor_host *host = nullptr;
    const arbor_plugin_descriptor *descriptor = nullptr;
    std::shared_ptr<PluginProcess> process;
    uint32_t channel = 0;
    std::string error;

    uint32_t masks[kInterfaces] = {};
    arbor_params_v1 params{};
    arbor_importer_v1 importer{};
    arbor_filter_v1 filter{};
    arbor_simplifier_v1 simplifier{};
    arbor_depictor_v1 depictor{};
    arbor_tf_generator_v1 generator{};
    arbor_renderer_v1 renderer1{};
    arbor_renderer_v2 renderer2{};
    arbor_render_device_v1 device{};
    std::string suffixes, device_name, header_unit;
    std::map<std::string, std::string> param_texts; // get()'s text, by id: valid until that id's next get
    std::vector<std::unique_ptr<OwnedParamDesc>> descriptions;
    // The values the host set, in order, to set again after a restart.
    std::vector<std::pair<std::string, std::pair<arbor_param_value, std::string>>> values;

    CacheSlot volume, labels;
    uint64_t keep = 0; // bulk bytes the caches hold
};

Proxy &proxy_of(const arbor_plugin *plugin) { return *static_cast<Proxy *>(plugin->plugin_data); }

// --- the instance's life in the child --------------------------------------

// Creates the instance in `process` on a channel of its own and reads what
// it offers.  "" on success, else the reason.
std::string attach(Proxy &p, const std::shared_ptr<PluginProcess> &process)
{
    const uint32_t channel = process->open_channel();
    if (channel == 0)
        return "has " + std::to_string(kMaxChannels - 1) + " live instances already (the most an isolated library has)";
    std::string failure;
    {
        const std::lock_guard control(process->control_mutex);
        MessageWriter w(process->window(0) + kRequestAt, kRequestBytes);
        w.put<uint32_t>(channel);
        w.put_string(p.descriptor->id);
        failure = process->call(0, Op::Create, w.size(), nullptr, p.host);
        if (failure.empty()) {
            try {
                const ChannelHeader &h = process->header(0);
                MessageReader r(process->window(0) + kReplyAt, std::min(h.reply_size, kReplyBytes));
                const int32_t status = r.get<int32_t>();
                const std::string reason = r.get_string();
                if (status != ARBOR_OK) {
                    failure = reason.empty() ? std::string("could not create an instance (") +
                                                   arbor_status_name(status) + ")"
                                             : reason;
                } else {
                    for (uint32_t &m : p.masks)
                        m = r.get<uint32_t>();
                    p.suffixes = r.get_string();
                    p.renderer2.struct_size =
                        std::min<uint32_t>(r.get<uint32_t>(), static_cast<uint32_t>(sizeof(arbor_renderer_v2)));
                    p.device.struct_size = std::min<uint32_t>(r.get<uint32_t>(),
                                                              static_cast<uint32_t>(sizeof(arbor_render_device_v1)));
                    const uint32_t count = r.get<uint32_t>();
                    if (count > 10000)
                        throw WireError("more than 10000 parameters");
                    std::vector<std::unique_ptr<OwnedParamDesc>> descriptions;
                    for (uint32_t i = 0; i < count; ++i) {
                        descriptions.push_back(std::make_unique<OwnedParamDesc>());
                        get_param_desc(r, *descriptions.back());
                    }
                    // Descriptions live as long as the proxy: a restart keeps
                    // the first ones (the same plugin describes the same).
                    if (p.descriptions.empty())
                        p.descriptions = std::move(descriptions);
                }
            } catch (const WireError &e) {
                failure = std::string("answered its creation garbled: ") + e.what();
            }
        }
    }
    if (!failure.empty()) {
        process->close_channel(channel);
        return failure;
    }
    p.process = process;
    p.channel = channel;
    p.volume = CacheSlot{};
    p.labels = CacheSlot{};
    p.keep = 0;
    return "";
}

void detach(Proxy &p)
{
    if (!p.process)
        return;
    if (p.process->alive()) {
        const std::lock_guard control(p.process->control_mutex);
        MessageWriter w(p.process->window(0) + kRequestAt, kRequestBytes);
        w.put<uint32_t>(p.channel);
        p.process->call(0, Op::Destroy, w.size(), nullptr, p.host);
    }
    p.process->close_channel(p.channel);
    p.process.reset();
}

arbor_status fail(Proxy &p, Op op, const std::string &why)
{
    p.error = why + " in " + op_call_name(op) +
              "; it runs isolated in a process of its own, so Arbor carries on and restarts it at its next call";
    return ARBOR_ERROR_INTERNAL;
}

void fill_tables(Proxy &p);

// The instance is in a live process: after a death, a new process, the
// instance created again, its parameters set again.
bool ensure_running(Proxy &p, Op op)
{
    if (p.process && p.process->alive())
        return true;
    std::shared_ptr<PluginProcess> process;
    try {
        process = p.library->process();
    } catch (const std::exception &e) {
        fail(p, op, e.what());
        return false;
    }
    if (p.process) {
        p.process->close_channel(p.channel);
        p.process.reset();
    }
    if (const std::string why = attach(p, process); !why.empty()) {
        fail(p, op, "restarted, but " + why);
        return false;
    }
    fill_tables(p); // the suffixes string is new
    for (const auto &[id, value] : p.values) {
        MessageWriter w(process->window(p.channel) + kRequestAt, kRequestBytes);
        w.put_string(id);
        arbor_param_value v = value.first;
        v.text = v.type == ARBOR_PARAM_STRING || v.type == ARBOR_PARAM_PATH ? value.second.c_str() : nullptr;
        put_param_value(w, v);
        if (const std::string why = process->call(p.channel, Op::ParamSet, w.size(), nullptr, p.host); !why.empty()) {
            fail(p, op, why + " (setting its parameters after a restart)");
            return false;
        }
    }
    return true;
}

// --- one call ----------------------------------------------------------------

struct CallContext {
    Proxy &p;
    uint8_t *window;
    uint64_t window_bytes;
    std::optional<BulkPlacer> placer;

    BulkPlacer &bulk()
    {
        if (!placer)
            placer.emplace(window, window_bytes, kBulkAt + p.keep);
        return *placer;
    }

    // A key for contents without a revision: their XXH3-128.
    static void hash_key(const void *data, uint64_t bytes, uint64_t key[2])
    {
        const XXH128_hash_t h = XXH3_128bits(data, bytes);
        key[0] = h.low64;
        key[1] = h.high64;
    }

    // Puts volume `v` (its voxels in the slot), copying only when its key
    // changed.  `revision` 0: the contents decide.  Before bulk().
    void put_cached_volume(MessageWriter &w, const arbor_volume &v, uint64_t revision)
    {
        const uint64_t bytes = contiguous_bytes(v);
        const int64_t s = arbor_voxel_size(v.voxel_type);
        const bool contiguous =
            v.strides[0] == s && v.strides[1] == s * v.dims[0] && v.strides[2] == s * v.dims[0] * v.dims[1];
        uint64_t key[4] = {revision, 0, bytes, v.voxel_type};
        if (revision == 0 && contiguous)
            hash_key(v.voxels, bytes, key);
        const bool same = p.volume.valid && contiguous && std::equal(key, key + 4, p.volume.key) &&
                          p.volume.bytes == bytes;
        if (!same) {
            BulkPlacer cache(window, window_bytes, kBulkAt);
            p.volume.offset = cache.reserve(bytes);
            copy_voxels_contiguous(v, window + p.volume.offset);
            p.volume.bytes = bytes;
            std::copy(key, key + 4, p.volume.key);
            p.volume.valid = true;
            p.labels.valid = false;
            p.keep = cache.next() - kBulkAt;
        }
        put_volume_fields(w, v);
        w.put<uint64_t>(p.volume.offset);
    }

    // A label map, after the cached volume, copied when its key changed.
    void put_cached_labels(MessageWriter &w, const arbor_label_map *labels, uint64_t revision)
    {
        w.put<uint32_t>(labels ? 1 : 0);
        if (!labels)
            return;
        const uint64_t count = static_cast<uint64_t>(labels->dims[0]) * labels->dims[1] * labels->dims[2];
        const uint64_t bytes = count * sizeof(uint32_t);
        uint64_t key[4] = {revision, 0, bytes, labels->label_count};
        if (revision == 0)
            hash_key(labels->labels, bytes, key);
        if (!(p.labels.valid && std::equal(key, key + 4, p.labels.key))) {
            BulkPlacer cache(window, window_bytes, p.volume.valid ? p.volume.offset + p.volume.bytes : kBulkAt);
            p.labels.offset = cache.place(labels->labels, bytes);
            p.labels.bytes = bytes;
            std::copy(key, key + 4, p.labels.key);
            p.labels.valid = true;
            p.keep = cache.next() - kBulkAt;
        }
        w.put(labels->label_count);
        for (int a = 0; a < 3; ++a)
            w.put(labels->dims[a]);
        w.put<uint64_t>(p.labels.offset);
    }
};

// Runs one call: `fill(w, context)` writes the request, `read(r, checked,
// status)` reads the reply (for OK, and for CANCELLED when read_cancelled).
template <class Fill, class Read>
arbor_status run(Proxy &p, Op op, arbor_task *task, Fill &&fill, Read &&read, bool read_cancelled = false)
{
    if (!ensure_running(p, op))
        return ARBOR_ERROR_INTERNAL;
    PluginProcess &process = *p.process;
    try {
        CallContext context{p, process.window(p.channel), process.window_bytes(), std::nullopt};
        MessageWriter w(context.window + kRequestAt, kRequestBytes);
        fill(w, context);
        ChannelHeader &h = process.header(p.channel);
        const uint64_t placed = context.bulk().next();
        h.allocate_limit = placed;
        h.allocate_top.store(process.window_bytes());
        const std::string failure = process.call(p.channel, op, w.size(), task, p.host);
        if (!failure.empty())
            return fail(p, op, failure);
        MessageReader r(context.window + kReplyAt, std::min(h.reply_size, kReplyBytes));
        const arbor_status status = r.get<int32_t>();
        p.error = r.get_string();
        if (status == ARBOR_OK || (read_cancelled && status == ARBOR_ERROR_CANCELLED))
            read(r, CheckedWindow{context.window, process.window_bytes()}, status);
        const uint64_t top = std::min(h.allocate_top.load(), process.window_bytes());
        process.release_bulk(p.channel, p.keep,
                             std::max(placed, process.window_bytes() - top + placed) - kBulkAt);
        return status;
    } catch (const std::exception &e) {
        p.error = std::string("isolated call ") + op_call_name(op) + ": " + e.what();
        return ARBOR_ERROR_INTERNAL;
    }
}

auto no_reply = [](MessageReader &, const CheckedWindow &, arbor_status) {};

// Copies `count` Ts between the host's array and the window.
template <class T>
uint64_t place_copy(BulkPlacer &bulk, const T *data, uint64_t count)
{
    return bulk.place(data, count * sizeof(T));
}

// An image region: compact in the window, strided in the host.
struct PlacedImage {
    uint64_t rgba = UINT64_MAX, depth = UINT64_MAX, visibility = UINT64_MAX;
};

PlacedImage place_image(MessageWriter &w, BulkPlacer &bulk, const arbor_image &out)
{
    PlacedImage placed;
    const uint64_t width = out.width, height = out.height;
    placed.rgba = bulk.reserve(width * height * 4 * sizeof(float));
    auto *rgba = reinterpret_cast<float *>(bulk.at(placed.rgba));
    for (uint64_t y = 0; y < height; ++y)
        std::memcpy(rgba + y * width * 4, out.rgba + static_cast<int64_t>(y) * out.row_stride, width * 4 * sizeof(float));
    const bool v11 = ARBOR_HAS_FIELD(arbor_image, out.struct_size, label_visibility_count);
    const bool v12 = ARBOR_HAS_FIELD(arbor_image, out.struct_size, depth_stride);
    const int64_t depth_stride = v12 && out.depth_stride ? out.depth_stride : static_cast<int64_t>(width);
    if (out.depth) {
        placed.depth = bulk.reserve(width * height * sizeof(float));
        auto *depth = reinterpret_cast<float *>(bulk.at(placed.depth));
        for (uint64_t y = 0; y < height; ++y)
            std::memcpy(depth + y * width, out.depth + static_cast<int64_t>(y) * depth_stride, width * sizeof(float));
    }
    const uint32_t labels = v11 && out.label_visibility ? out.label_visibility_count : 0;
    if (labels)
        placed.visibility = place_copy(bulk, out.label_visibility, labels);
    w.put(out.width);
    w.put(out.height);
    w.put<uint64_t>(placed.rgba);
    w.put<uint64_t>(placed.depth);
    w.put<uint64_t>(placed.visibility);
    w.put<uint32_t>(labels);
    return placed;
}

void copy_image_back(const CheckedWindow &window, const PlacedImage &placed, arbor_image &out, bool visibility)
{
    const uint64_t width = out.width, height = out.height;
    const float *rgba = window.at<float>(placed.rgba, width * height * 4);
    for (uint64_t y = 0; y < height; ++y)
        std::memcpy(out.rgba + static_cast<int64_t>(y) * out.row_stride, rgba + y * width * 4, width * 4 * sizeof(float));
    const bool v12 = ARBOR_HAS_FIELD(arbor_image, out.struct_size, depth_stride);
    const int64_t depth_stride = v12 && out.depth_stride ? out.depth_stride : static_cast<int64_t>(width);
    if (out.depth && placed.depth != UINT64_MAX) {
        const float *depth = window.at<float>(placed.depth, width * height);
        for (uint64_t y = 0; y < height; ++y)
            std::memcpy(out.depth + static_cast<int64_t>(y) * depth_stride, depth + y * width, width * sizeof(float));
    }
    if (visibility && placed.visibility != UINT64_MAX)
        std::memcpy(out.label_visibility, window.at<double>(placed.visibility, out.label_visibility_count),
                    out.label_visibility_count * sizeof(double));
}

// --- arbor_plugin -------------------------------------------------------------

void c_destroy(arbor_plugin *plugin)
{
    Proxy *p = &proxy_of(plugin);
    detach(*p);
    delete p;
}

const void *c_get_interface(const arbor_plugin *plugin, const char *id)
{
    Proxy &p = proxy_of(plugin);
    if (!id)
        return nullptr;
    const std::pair<const char *, std::pair<Interface, const void *>> tables[] = {
        {ARBOR_INTERFACE_PARAMS, {kParams, &p.params}},
        {ARBOR_INTERFACE_IMPORTER, {kImporter, &p.importer}},
        {ARBOR_INTERFACE_FILTER, {kFilter, &p.filter}},
        {ARBOR_INTERFACE_SIMPLIFIER, {kSimplifier, &p.simplifier}},
        {ARBOR_INTERFACE_DEPICTOR, {kDepictor, &p.depictor}},
        {ARBOR_INTERFACE_TF_GENERATOR, {kGenerator, &p.generator}},
        {ARBOR_INTERFACE_RENDERER, {kRenderer1, &p.renderer1}},
        {ARBOR_INTERFACE_RENDERER_2, {kRenderer2, &p.renderer2}},
        {ARBOR_INTERFACE_RENDER_DEVICE, {kDevice, &p.device}}};
    for (const auto &[name, table] : tables)
        if (std::strcmp(id, name) == 0)
            return p.masks[table.first] ? table.second : nullptr;
    return nullptr;
}

const char *c_last_error(const arbor_plugin *plugin) { return proxy_of(plugin).error.c_str(); }

// --- params ---------------------------------------------------------------------

uint32_t c_param_count(const arbor_plugin *plugin)
{
    return static_cast<uint32_t>(proxy_of(plugin).descriptions.size());
}

const arbor_param_desc *c_param_describe(const arbor_plugin *plugin, uint32_t index)
{
    const Proxy &p = proxy_of(plugin);
    return index < p.descriptions.size() ? &p.descriptions[index]->desc : nullptr;
}

arbor_status c_param_get(const arbor_plugin *plugin, const char *id, arbor_param_value *out)
{
    Proxy &p = proxy_of(plugin);
    if (!id || !out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return run(
        p, Op::ParamGet, nullptr, [&](MessageWriter &w, CallContext &) { w.put_string(id); },
        [&](MessageReader &r, const CheckedWindow &, arbor_status) {
            arbor_param_value v{};
            std::string &text = p.param_texts[id];
            get_param_value(r, v, text);
            out->type = v.type;
            out->components = v.components;
            std::copy(std::begin(v.number), std::end(v.number), out->number);
            out->text = v.text ? text.c_str() : nullptr;
        });
}

arbor_status c_param_set(arbor_plugin *plugin, const char *id, const arbor_param_value *value)
{
    Proxy &p = proxy_of(plugin);
    if (!id || !value)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    const arbor_status s = run(
        p, Op::ParamSet, nullptr,
        [&](MessageWriter &w, CallContext &) {
            w.put_string(id);
            put_param_value(w, *value);
        },
        no_reply);
    if (s == ARBOR_OK) {
        arbor_param_value kept = *value;
        const std::string text = value->text ? value->text : "";
        kept.text = nullptr;
        auto it = std::find_if(p.values.begin(), p.values.end(), [&](const auto &e) { return e.first == id; });
        if (it != p.values.end())
            it->second = {kept, text};
        else
            p.values.push_back({id, {kept, text}});
    }
    return s;
}

// --- importer -------------------------------------------------------------------

arbor_status c_probe(arbor_plugin *plugin, const char *path, const uint8_t *head, uint64_t head_size,
                     int32_t *confidence)
{
    Proxy &p = proxy_of(plugin);
    if (!path || !confidence)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return run(
        p, Op::Probe, nullptr,
        [&](MessageWriter &w, CallContext &) {
            w.put_string(path);
            w.put_sized(head, head ? std::min<uint64_t>(head_size, 4096) : 0);
            w.put<uint32_t>(head ? 1 : 0);
        },
        [&](MessageReader &r, const CheckedWindow &, arbor_status) { *confidence = r.get<int32_t>(); });
}

arbor_status c_read_header(arbor_plugin *plugin, const char *path, arbor_task *task, arbor_volume *out)
{
    Proxy &p = proxy_of(plugin);
    if (!path || !out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return run(
        p, Op::ReadHeader, task, [&](MessageWriter &w, CallContext &) { w.put_string(path); },
        [&](MessageReader &r, const CheckedWindow &, arbor_status) {
            arbor_volume v{};
            get_volume_fields(r, v, p.header_unit);
            const uint32_t size = out->struct_size;
            const int64_t strides[3] = {out->strides[0], out->strides[1], out->strides[2]};
            void *voxels = out->voxels;
            std::memcpy(out, &v, std::min<std::size_t>(size, sizeof v));
            out->struct_size = size;
            std::copy(strides, strides + 3, out->strides);
            out->voxels = voxels;
            out->value_unit = v.value_unit ? p.header_unit.c_str() : nullptr;
        });
}

arbor_status c_read_voxels(arbor_plugin *plugin, const char *path, arbor_task *task, arbor_volume *volume)
{
    Proxy &p = proxy_of(plugin);
    if (!path || !volume || !volume->voxels)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    uint64_t at = 0;
    const uint64_t bytes = contiguous_bytes(*volume);
    return run(
        p, Op::ReadVoxels, task,
        [&](MessageWriter &w, CallContext &c) {
            w.put_string(path);
            put_volume_fields(w, *volume);
            at = c.bulk().reserve(bytes);
            w.put<uint64_t>(at);
        },
        [&](MessageReader &, const CheckedWindow &window, arbor_status) {
            const uint8_t *voxels = window.at<uint8_t>(at, bytes);
            arbor_volume target = *volume;
            const int64_t s = arbor_voxel_size(volume->voxel_type);
            if (volume->strides[0] == s && volume->strides[1] == s * volume->dims[0] &&
                volume->strides[2] == s * volume->dims[0] * volume->dims[1]) {
                std::memcpy(volume->voxels, voxels, bytes);
                return;
            }
            auto *out = static_cast<uint8_t *>(target.voxels);
            for (int64_t k = 0; k < volume->dims[2]; ++k)
                for (int64_t j = 0; j < volume->dims[1]; ++j)
                    for (int64_t i = 0; i < volume->dims[0]; ++i, voxels += s)
                        std::memcpy(out + i * volume->strides[0] + j * volume->strides[1] + k * volume->strides[2],
                                    voxels, static_cast<std::size_t>(s));
        });
}

// --- filter ---------------------------------------------------------------------

arbor_status c_output_type(arbor_plugin *plugin, const arbor_volume *input, arbor_voxel_type *out_type)
{
    Proxy &p = proxy_of(plugin);
    if (!input || !out_type || !input->voxels)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return run(
        p, Op::OutputType, nullptr, [&](MessageWriter &w, CallContext &c) { c.put_cached_volume(w, *input, 0); },
        [&](MessageReader &r, const CheckedWindow &, arbor_status) { *out_type = r.get<arbor_voxel_type>(); });
}

arbor_status c_apply(arbor_plugin *plugin, const arbor_volume *input, arbor_volume *output, arbor_task *task)
{
    Proxy &p = proxy_of(plugin);
    if (!input || !output || !input->voxels || !output->voxels)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    uint64_t at = 0;
    const uint64_t bytes = contiguous_bytes(*output);
    return run(
        p, Op::Apply, task,
        [&](MessageWriter &w, CallContext &c) {
            c.put_cached_volume(w, *input, 0); // staged by output_type, which comes right before
            put_volume_fields(w, *output);
            at = c.bulk().reserve(bytes);
            w.put<uint64_t>(at);
        },
        [&](MessageReader &, const CheckedWindow &window, arbor_status) {
            std::memcpy(output->voxels, window.at<uint8_t>(at, bytes), bytes);
        });
}

// --- simplifier -------------------------------------------------------------------

arbor_status c_prepare(arbor_plugin *plugin, const arbor_measure_rows *schema)
{
    Proxy &p = proxy_of(plugin);
    if (!schema)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return run(p, Op::Prepare, nullptr, [&](MessageWriter &w, CallContext &) { put_rows(w, *schema); }, no_reply);
}

arbor_status c_importance(arbor_plugin *plugin, const arbor_measure_rows *rows, double *out)
{
    Proxy &p = proxy_of(plugin);
    if (!rows || !out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return run(
        p, Op::Importance, nullptr, [&](MessageWriter &w, CallContext &) { put_rows(w, *rows); },
        [&](MessageReader &r, const CheckedWindow &, arbor_status) {
            const std::string values = r.get_sized();
            std::memcpy(out, values.data(), std::min<std::size_t>(values.size(), rows->row_count * sizeof(double)));
        });
}

// --- depictor ---------------------------------------------------------------------

struct PlacedDepiction {
    uint64_t role, saddle, extremum, hue, saturation;
};

PlacedDepiction place_depiction(MessageWriter &w, BulkPlacer &bulk, const arbor_depiction &d)
{
    const uint64_t n = d.branch_count;
    PlacedDepiction placed{place_copy(bulk, d.role, n), place_copy(bulk, d.opacity_at_saddle, n),
                           place_copy(bulk, d.opacity_at_extremum, n), place_copy(bulk, d.hue, n),
                           place_copy(bulk, d.saturation, n)};
    w.put(d.branch_count);
    for (uint64_t at : {placed.role, placed.saddle, placed.extremum, placed.hue, placed.saturation})
        w.put(at);
    return placed;
}

void copy_depiction_back(const CheckedWindow &window, const PlacedDepiction &placed, arbor_depiction &d)
{
    const uint64_t n = d.branch_count;
    std::memcpy(d.role, window.at<arbor_branch_role>(placed.role, n), n * sizeof *d.role);
    std::memcpy(d.opacity_at_saddle, window.at<float>(placed.saddle, n), n * sizeof(float));
    std::memcpy(d.opacity_at_extremum, window.at<float>(placed.extremum, n), n * sizeof(float));
    std::memcpy(d.hue, window.at<float>(placed.hue, n), n * sizeof(float));
    std::memcpy(d.saturation, window.at<float>(placed.saturation, n), n * sizeof(float));
}

bool depiction_complete(const arbor_depiction *d)
{
    return d && d->struct_size >= ARBOR_MIN_SIZE(arbor_depiction) && d->role && d->opacity_at_saddle &&
           d->opacity_at_extremum && d->hue && d->saturation;
}

arbor_status c_depict(arbor_plugin *plugin, const arbor_depiction_request *request, arbor_depiction *out,
                      arbor_task *task)
{
    Proxy &p = proxy_of(plugin);
    if (!request || !request->tree || !depiction_complete(out))
        return ARBOR_ERROR_INVALID_ARGUMENT;
    PlacedDepiction placed{};
    return run(
        p, Op::Depict, task,
        [&](MessageWriter &w, CallContext &c) {
            w.put(request->selected_branch);
            put_tree(w, c.bulk(), *request->tree);
            placed = place_depiction(w, c.bulk(), *out);
        },
        [&](MessageReader &, const CheckedWindow &window, arbor_status) { copy_depiction_back(window, placed, *out); });
}

arbor_status c_related(arbor_plugin *plugin, const arbor_branch_tree *tree, uint32_t a, uint32_t b,
                       arbor_bool32 *related)
{
    Proxy &p = proxy_of(plugin);
    if (!tree || !related)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return run(
        p, Op::Related, nullptr,
        [&](MessageWriter &w, CallContext &c) {
            put_tree(w, c.bulk(), *tree);
            w.put(a);
            w.put(b);
        },
        [&](MessageReader &r, const CheckedWindow &, arbor_status) { *related = r.get<arbor_bool32>(); });
}

arbor_status c_legend(arbor_plugin *plugin, const arbor_depiction_request *request, arbor_image *out,
                      arbor_task *task)
{
    Proxy &p = proxy_of(plugin);
    if (!request || !request->tree || !out || !out->rgba || out->width == 0 || out->height == 0)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    PlacedImage placed;
    return run(
        p, Op::Legend, task,
        [&](MessageWriter &w, CallContext &c) {
            w.put(request->selected_branch);
            put_tree(w, c.bulk(), *request->tree);
            placed = place_image(w, c.bulk(), *out);
        },
        [&](MessageReader &, const CheckedWindow &window, arbor_status) {
            copy_image_back(window, placed, *out, false);
        });
}

// --- transfer-function generator ----------------------------------------------------

arbor_status c_generate(arbor_plugin *plugin, const arbor_tf_request *request, arbor_tf_set *out, arbor_task *task)
{
    Proxy &p = proxy_of(plugin);
    if (!request || !request->tree || !out || out->struct_size < ARBOR_MIN_SIZE(arbor_tf_set) || !out->domain ||
        !out->lut || !out->point_offsets || !task)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    const uint64_t n = out->branch_count;
    const bool notes = ARBOR_HAS_FIELD(arbor_tf_set, out->struct_size, note_size) && out->notes && out->note_size;
    const bool by_host = ARBOR_HAS_FIELD(arbor_tf_set, out->struct_size, depiction_by_host);
    uint64_t domain = 0, lut = 0, offsets = 0, note_at = UINT64_MAX;
    return run(
        p, Op::Generate, task,
        [&](MessageWriter &w, CallContext &c) {
            w.put<uint32_t>(request->volume ? 1 : 0);
            if (request->volume)
                c.put_cached_volume(w, *request->volume, 0);
            put_tree(w, c.bulk(), *request->tree);
            w.put<uint32_t>(depiction_complete(request->depiction) ? 1 : 0);
            if (depiction_complete(request->depiction))
                place_depiction(w, c.bulk(), *request->depiction);
            w.put(request->value_range[0]);
            w.put(request->value_range[1]);
            w.put(request->min_spacing);
            const bool background = ARBOR_HAS_FIELD(arbor_tf_request, request->struct_size, background_level);
            w.put<double>(background ? request->background_level : NAN);
            w.put<double>(background ? request->background_peak : NAN);
            w.put(out->branch_count);
            w.put(out->lut_size);
            w.put(out->opacity_unit_distance);
            domain = place_copy(c.bulk(), out->domain, 2 * n);
            lut = place_copy(c.bulk(), out->lut, n * out->lut_size * 4);
            offsets = place_copy(c.bulk(), out->point_offsets, n + 1);
            if (notes)
                note_at = place_copy(c.bulk(), out->notes, n * out->note_size);
            w.put(domain);
            w.put(lut);
            w.put(offsets);
            w.put(note_at);
            w.put<uint32_t>(notes ? out->note_size : 0);
        },
        [&](MessageReader &r, const CheckedWindow &window, arbor_status) {
            out->opacity_unit_distance = r.get<double>();
            const arbor_bool32 depiction_by_host = r.get<arbor_bool32>();
            const uint64_t points_at = r.get<uint64_t>(), point_count = r.get<uint64_t>();
            std::memcpy(out->domain, window.at<double>(domain, 2 * n), 2 * n * sizeof(double));
            std::memcpy(out->lut, window.at<float>(lut, n * out->lut_size * 4), n * out->lut_size * 4 * sizeof(float));
            std::memcpy(out->point_offsets, window.at<uint32_t>(offsets, n + 1), (n + 1) * sizeof(uint32_t));
            if (notes)
                std::memcpy(out->notes, window.at<char>(note_at, n * out->note_size), n * out->note_size);
            if (by_host)
                out->depiction_by_host = depiction_by_host;
            out->points = nullptr;
            if (point_count) {
                const arbor_tf_point *points = window.at<arbor_tf_point>(points_at, point_count);
                auto *copy = static_cast<arbor_tf_point *>(task->allocate(task, point_count * sizeof(arbor_tf_point)));
                if (!copy)
                    throw std::runtime_error("the host refused memory for the control points");
                std::memcpy(copy, points, point_count * sizeof(arbor_tf_point));
                out->points = copy;
            }
        });
}

// --- renderers ----------------------------------------------------------------------

void put_camera(MessageWriter &w, const arbor_camera &camera)
{
    arbor_camera c{};
    std::memcpy(&c, &camera, std::min<std::size_t>(camera.struct_size, sizeof c));
    c.struct_size = sizeof c;
    w.put(c);
}

template <class Request>
void put_scene(MessageWriter &w, CallContext &c, const Request &request)
{
    c.put_cached_volume(w, *request.volume, request.volume_revision);
    c.put_cached_labels(w, request.labels, request.labels_revision);
    put_label_hierarchy(w, c.bulk(), request.labels);
    put_tf_input(w, c.bulk(), *request.transfer_functions);
    put_camera(w, *request.camera);
    for (float b : request.background)
        w.put(b);
    w.put(request.volume_revision);
    w.put(request.labels_revision);
}

bool image_complete(const arbor_image *out)
{
    return out && out->struct_size >= ARBOR_MIN_SIZE(arbor_image) && out->rgba && out->width && out->height &&
           out->row_stride >= 4 * static_cast<int64_t>(out->width);
}

arbor_status c_render1(arbor_plugin *plugin, const arbor_render_request *request, arbor_image *out, arbor_task *task)
{
    Proxy &p = proxy_of(plugin);
    if (!request || !request->volume || !request->volume->voxels || !request->transfer_functions ||
        !request->camera || !image_complete(out))
        return ARBOR_ERROR_INVALID_ARGUMENT;
    PlacedImage placed;
    return run(
        p, Op::Render1, task,
        [&](MessageWriter &w, CallContext &c) {
            put_scene(w, c, *request);
            placed = place_image(w, c.bulk(), *out);
        },
        [&](MessageReader &, const CheckedWindow &window, arbor_status status) {
            copy_image_back(window, placed, *out, status == ARBOR_OK);
        },
        true);
}

arbor_status c_render2(arbor_plugin *plugin, const arbor_render_request_v2 *request, arbor_image *out,
                       arbor_task *task)
{
    Proxy &p = proxy_of(plugin);
    if (!request || request->struct_size < ARBOR_MIN_SIZE(arbor_render_request_v2) || !request->volume ||
        !request->volume->voxels || !request->transfer_functions || !request->camera || !image_complete(out))
        return ARBOR_ERROR_INVALID_ARGUMENT;
    PlacedImage placed;
    return run(
        p, Op::Render2, task,
        [&](MessageWriter &w, CallContext &c) {
            put_scene(w, c, *request);
            w.put(request->pass);
            w.put(request->transfer_functions_revision);
            for (uint32_t x : {request->frame_width, request->frame_height, request->region_x, request->region_y,
                               request->region_width, request->region_height, request->sample_index})
                w.put(x);
            placed = place_image(w, c.bulk(), *out);
        },
        [&](MessageReader &, const CheckedWindow &window, arbor_status status) {
            copy_image_back(window, placed, *out, status == ARBOR_OK);
        },
        true);
}

arbor_status c_describe_device(const arbor_plugin *plugin, arbor_render_device *out)
{
    Proxy &p = proxy_of(plugin);
    if (!out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return run(
        p, Op::DescribeDevice, nullptr, [](MessageWriter &, CallContext &) {},
        [&](MessageReader &r, const CheckedWindow &, arbor_status) {
            out->kind = r.get<arbor_device_kind>();
            p.device_name = r.get_string();
            out->name = p.device_name.c_str();
        });
}

// Function i of a table is there when bit i of its mask is.
template <class F>
F *offered(uint32_t mask, int bit, F *function)
{
    return (mask >> bit) & 1 ? function : nullptr;
}

void fill_tables(Proxy &p)
{
    const uint32_t *m = p.masks;
    p.params = {offered(m[kParams], 0, c_param_count), offered(m[kParams], 1, c_param_describe),
                offered(m[kParams], 2, c_param_get), offered(m[kParams], 3, c_param_set)};
    p.importer = {p.suffixes.c_str(), offered(m[kImporter], 1, c_probe), offered(m[kImporter], 2, c_read_header),
                  offered(m[kImporter], 3, c_read_voxels)};
    p.filter = {offered(m[kFilter], 0, c_output_type), offered(m[kFilter], 1, c_apply)};
    p.simplifier = {offered(m[kSimplifier], 0, c_prepare), offered(m[kSimplifier], 1, c_importance)};
    p.depictor = {offered(m[kDepictor], 0, c_depict), offered(m[kDepictor], 1, c_related),
                  offered(m[kDepictor], 2, c_legend)};
    p.generator = {offered(m[kGenerator], 0, c_generate)};
    p.renderer1 = {offered(m[kRenderer1], 0, c_render1)};
    p.renderer2.render = offered(m[kRenderer2], 0, c_render2);
    p.device.describe = offered(m[kDevice], 0, c_describe_device);
}

} // namespace

arbor_status create_proxy_plugin(IsolatedLibrary &library, const arbor_host *host,
                                 const arbor_plugin_descriptor *descriptor, arbor_plugin **out)
{
    auto p = std::make_unique<Proxy>();
    p->library = &library;
    p->host = host;
    p->descriptor = descriptor;
    std::string why;
    try {
        why = attach(*p, library.process());
    } catch (const std::exception &e) {
        why = e.what();
    }
    if (!why.empty()) {
        if (host && host->log)
            host->log(host, ARBOR_LOG_ERROR, (std::string(descriptor->id) + " (isolated): " + why).c_str());
        return ARBOR_ERROR_INTERNAL;
    }
    fill_tables(*p);
    p->record.struct_size = sizeof(arbor_plugin);
    p->record.descriptor = descriptor;
    p->record.plugin_data = p.get();
    p->record.destroy = c_destroy;
    p->record.get_interface = c_get_interface;
    p->record.last_error = c_last_error;
    *out = &p.release()->record;
    return ARBOR_OK;
}

} // namespace arbor
