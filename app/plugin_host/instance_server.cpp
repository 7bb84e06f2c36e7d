#include "instance_server.hpp"

#include "host/isolation_records.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace arbor::plugin_host {

using namespace isolation;

namespace {

const char *const kInterfaceIds[9] = {ARBOR_INTERFACE_PARAMS,       ARBOR_INTERFACE_IMPORTER,
                                      ARBOR_INTERFACE_FILTER,       ARBOR_INTERFACE_SIMPLIFIER,
                                      ARBOR_INTERFACE_DEPICTOR,     ARBOR_INTERFACE_TF_GENERATOR,
                                      ARBOR_INTERFACE_RENDERER,     ARBOR_INTERFACE_RENDERER_2,
                                      ARBOR_INTERFACE_RENDER_DEVICE};

constexpr uint32_t kOffered = 1u << 31;

// The mask of a table: offered, and bit i where its i-th function is there.
template <class... Pointers>
uint32_t bits(Pointers... present)
{
    uint32_t m = kOffered, i = 0;
    ((m |= (present != nullptr ? 1u : 0u) << i++), ...);
    return m;
}

template <class T>
const T &table(const void *const *tables, int index)
{
    const T *t = static_cast<const T *>(tables[index]);
    if (!t)
        throw std::runtime_error("the instance does not offer this interface");
    return *t;
}

void contiguous(arbor_volume &v)
{
    const int64_t s = arbor_voxel_size(v.voxel_type);
    v.strides[0] = s;
    v.strides[1] = s * v.dims[0];
    v.strides[2] = s * v.dims[0] * v.dims[1];
}

arbor_depiction get_depiction(MessageReader &r, const WindowView &view)
{
    arbor_depiction d{};
    d.struct_size = sizeof d;
    d.branch_count = r.get<uint32_t>();
    d.role = view.at<arbor_branch_role>(r.get<uint64_t>());
    d.opacity_at_saddle = view.at<float>(r.get<uint64_t>());
    d.opacity_at_extremum = view.at<float>(r.get<uint64_t>());
    d.hue = view.at<float>(r.get<uint64_t>());
    d.saturation = view.at<float>(r.get<uint64_t>());
    return d;
}

arbor_image get_image(MessageReader &r, const WindowView &view)
{
    arbor_image image{};
    image.struct_size = sizeof image;
    image.width = r.get<uint32_t>();
    image.height = r.get<uint32_t>();
    image.row_stride = 4 * static_cast<int64_t>(image.width);
    image.rgba = view.at<float>(r.get<uint64_t>());
    image.depth = view.at<float>(r.get<uint64_t>());
    image.label_visibility = view.at<double>(r.get<uint64_t>());
    image.label_visibility_count = r.get<uint32_t>();
    image.depth_stride = image.width;
    return image;
}

// The scene of a render request: volume, labels, functions, camera.
struct Scene {
    ChildVolume volume;
    arbor_label_map labels{};
    bool has_labels = false;
    ChildTfSet functions;
    arbor_camera camera{};
    float background[4] = {};
    uint64_t volume_revision = 0, labels_revision = 0;

    void read(MessageReader &r, const WindowView &view)
    {
        get_volume(r, view, volume);
        has_labels = r.get<uint32_t>() != 0;
        if (has_labels) {
            labels.struct_size = sizeof labels;
            labels.label_count = r.get<uint32_t>();
            for (int a = 0; a < 3; ++a)
                labels.dims[a] = r.get<int64_t>();
            labels.labels = view.at<const uint32_t>(r.get<uint64_t>());
        }
        get_label_hierarchy(r, view, labels);
        get_tf_input(r, view, functions);
        camera = r.get<arbor_camera>();
        for (float &b : background)
            b = r.get<float>();
        volume_revision = r.get<uint64_t>();
        labels_revision = r.get<uint64_t>();
    }

    // The fields renderer/1 and /2 requests share.
    template <class Request>
    void fill(Request &request) const
    {
        request.struct_size = sizeof request;
        request.volume = &volume.volume;
        request.labels = has_labels ? &labels : nullptr;
        request.transfer_functions = &functions.set;
        request.camera = &camera;
        std::memcpy(request.background, background, sizeof request.background);
        request.volume_revision = volume_revision;
        request.labels_revision = labels_revision;
    }
};

// A depictor's request: the selection and the tree.
struct DepictionInput {
    ChildTree tree;
    arbor_depiction_request request{};
    void read(MessageReader &r, const WindowView &view)
    {
        request.struct_size = sizeof request;
        request.selected_branch = r.get<int32_t>();
        get_tree(r, view, tree);
        request.tree = &tree.tree;
    }
};

} // namespace

std::string check_instance_record(const arbor_plugin *plugin)
{
    if (!plugin)
        return "create_plugin returned OK without an instance";
    if (plugin->struct_size < ARBOR_MIN_SIZE(arbor_plugin) || !plugin->destroy || !plugin->get_interface ||
        !plugin->last_error || !plugin->descriptor)
        return "the instance record is malformed";
    return "";
}

InstanceServer::InstanceServer(arbor_plugin *plugin, ChannelHeader *header, uint8_t *window)
    : plugin_(plugin), header_(header), window_(window), task_(header, window)
{
    for (int i = 0; i < 9; ++i)
        tables_[i] = plugin_->get_interface(plugin_, kInterfaceIds[i]);
    // The host posts its first request as soon as the create reply is out,
    // perhaps before the thread runs: the thread starts from this number.
    const uint32_t seen = header_->request.load(std::memory_order_acquire);
    thread_ = std::thread([this, seen] { serve(seen); });
}

InstanceServer::~InstanceServer()
{
    // A new number, so that a thread about to sleep on the old one does not
    // (the channel is closing: the host clears its header when it reuses it).
    stop_ = true;
    header_->request.fetch_add(1);
    futex_wake(header_->request);
    thread_.join();
    plugin_->destroy(plugin_);
}

void InstanceServer::describe(MessageWriter &w) const
{
    const auto *params = static_cast<const arbor_params_v1 *>(tables_[0]);
    const auto *importer = static_cast<const arbor_importer_v1 *>(tables_[1]);
    const auto *filter = static_cast<const arbor_filter_v1 *>(tables_[2]);
    const auto *simplifier = static_cast<const arbor_simplifier_v1 *>(tables_[3]);
    const auto *depictor = static_cast<const arbor_depictor_v1 *>(tables_[4]);
    const auto *generator = static_cast<const arbor_tf_generator_v1 *>(tables_[5]);
    const auto *renderer1 = static_cast<const arbor_renderer_v1 *>(tables_[6]);
    const auto *renderer2 = static_cast<const arbor_renderer_v2 *>(tables_[7]);
    const auto *device = static_cast<const arbor_render_device_v1 *>(tables_[8]);
    const bool r2 = renderer2 && ARBOR_HAS_FIELD(arbor_renderer_v2, renderer2->struct_size, render);
    const bool d1 = device && ARBOR_HAS_FIELD(arbor_render_device_v1, device->struct_size, describe);
    w.put<uint32_t>(params ? bits(params->count, params->describe, params->get, params->set) : 0);
    w.put<uint32_t>(importer ? bits(importer->suffixes, importer->probe, importer->read_header, importer->read_voxels)
                             : 0);
    w.put<uint32_t>(filter ? bits(filter->output_type, filter->apply) : 0);
    w.put<uint32_t>(simplifier ? bits(simplifier->prepare, simplifier->importance) : 0);
    w.put<uint32_t>(depictor ? bits(depictor->depict, depictor->related, depictor->legend) : 0);
    w.put<uint32_t>(generator ? bits(generator->generate) : 0);
    w.put<uint32_t>(renderer1 ? bits(renderer1->render) : 0);
    w.put<uint32_t>(renderer2 ? bits(r2 ? renderer2->render : nullptr) : 0);
    w.put<uint32_t>(device ? bits(d1 ? device->describe : nullptr) : 0);
    w.put_string(importer && importer->suffixes ? importer->suffixes : "", 4096);
    w.put<uint32_t>(renderer2 ? renderer2->struct_size : 0);
    w.put<uint32_t>(device ? device->struct_size : 0);
    const uint32_t count = params && params->count && params->describe ? params->count(plugin_) : 0;
    if (count > 10000)
        throw std::runtime_error("params.count says " + std::to_string(count) + " (at most 10000)");
    w.put(count);
    for (uint32_t i = 0; i < count; ++i) {
        const arbor_param_desc *d = params->describe(plugin_, i);
        if (!d)
            throw std::runtime_error("params.describe(" + std::to_string(i) + ") returned NULL");
        put_param_desc(w, *d);
    }
}

std::string InstanceServer::error() const
{
    const char *e = plugin_->last_error(plugin_);
    return e ? std::string(e, strnlen(e, 4096)) : "";
}

void InstanceServer::serve(uint32_t seen)
{
    ChannelHeader &h = *header_;
    for (;;) {
        // A simplifier's next call comes within microseconds: spin first.
        if (!spin_until_changed(h.request, seen, 50'000))
            while (h.request.load(std::memory_order_acquire) == seen && !stop_)
                futex_wait(h.request, seen, -1);
        if (stop_)
            return;
        seen = h.request.load(std::memory_order_acquire);
        MessageReader r(window_ + kRequestAt, std::min(h.request_size, kRequestBytes));
        MessageWriter w(window_ + kReplyAt, kReplyBytes);
        const auto op = static_cast<Op>(h.op);
        int32_t status;
        std::string failure;
        MessageWriter outputs(window_ + kReplyAt + 4096, kReplyBytes - 4096);
        try {
            status = handle(op, r, outputs);
        } catch (const std::exception &e) {
            status = ARBOR_ERROR_INTERNAL;
            failure = std::string("arbor-plugin-host: ") + e.what();
            outputs = MessageWriter(window_ + kReplyAt + 4096, kReplyBytes - 4096);
        }
        // Status, the reason of a failure, then the outputs.
        const std::string reason = !failure.empty() ? failure : status == ARBOR_OK ? "" : error();
        w.put<int32_t>(status);
        w.put_string(reason.substr(0, 3000));
        const uint64_t head = w.size();
        std::memmove(window_ + kReplyAt + head, window_ + kReplyAt + 4096, outputs.size());
        h.reply_size = head + outputs.size();
        h.reply.store(seen, std::memory_order_release);
        futex_wake(h.reply);
    }
}

int32_t InstanceServer::handle(Op op, MessageReader &r, MessageWriter &w)
{
    const WindowView view{window_};
    arbor_task *task = task_.get();
    switch (op) {
    case Op::ParamGet: {
        const std::string id = r.get_string();
        arbor_param_value v{};
        v.struct_size = sizeof v;
        const int32_t s = table<arbor_params_v1>(tables_, 0).get(plugin_, id.c_str(), &v);
        if (s == ARBOR_OK)
            put_param_value(w, v);
        return s;
    }
    case Op::ParamSet: {
        const std::string id = r.get_string();
        arbor_param_value v{};
        v.struct_size = sizeof v;
        std::string text;
        get_param_value(r, v, text);
        return table<arbor_params_v1>(tables_, 0).set(plugin_, id.c_str(), &v);
    }
    case Op::Probe: {
        const std::string path = r.get_string(), head = r.get_sized();
        const bool has_head = r.get<uint32_t>() != 0;
        int32_t confidence = 0;
        const int32_t s = table<arbor_importer_v1>(tables_, 1).probe(
            plugin_, path.c_str(), has_head ? reinterpret_cast<const uint8_t *>(head.data()) : nullptr, head.size(),
            &confidence);
        w.put(confidence);
        return s;
    }
    case Op::ReadHeader: {
        const std::string path = r.get_string();
        arbor_volume v{};
        v.struct_size = sizeof v;
        const int32_t s = table<arbor_importer_v1>(tables_, 1).read_header(plugin_, path.c_str(), task, &v);
        if (s == ARBOR_OK)
            put_volume_fields(w, v);
        return s;
    }
    case Op::ReadVoxels: {
        const std::string path = r.get_string();
        arbor_volume v{};
        v.struct_size = sizeof v;
        std::string unit;
        get_volume_fields(r, v, unit);
        contiguous(v);
        v.voxels = view.at<void>(r.get<uint64_t>());
        return table<arbor_importer_v1>(tables_, 1).read_voxels(plugin_, path.c_str(), task, &v);
    }
    case Op::OutputType: {
        ChildVolume input;
        get_volume(r, view, input);
        arbor_voxel_type type = ARBOR_VOXEL_UNKNOWN;
        const int32_t s = table<arbor_filter_v1>(tables_, 2).output_type(plugin_, &input.volume, &type);
        w.put(type);
        return s;
    }
    case Op::Apply: {
        ChildVolume input;
        get_volume(r, view, input);
        arbor_volume output{};
        output.struct_size = sizeof output;
        std::string unit;
        get_volume_fields(r, output, unit);
        contiguous(output);
        output.voxels = view.at<void>(r.get<uint64_t>());
        return table<arbor_filter_v1>(tables_, 2).apply(plugin_, &input.volume, &output, task);
    }
    case Op::Prepare: {
        ChildRows rows;
        get_rows(r, rows);
        return table<arbor_simplifier_v1>(tables_, 3).prepare(plugin_, &rows.rows);
    }
    case Op::Importance: {
        ChildRows rows;
        get_rows(r, rows);
        std::vector<double> out(rows.rows.row_count, NAN);
        const int32_t s = table<arbor_simplifier_v1>(tables_, 3).importance(plugin_, &rows.rows, out.data());
        w.put_sized(out.data(), out.size() * sizeof(double));
        return s;
    }
    case Op::Depict: {
        DepictionInput in;
        in.read(r, view);
        arbor_depiction out = get_depiction(r, view);
        return table<arbor_depictor_v1>(tables_, 4).depict(plugin_, &in.request, &out, task);
    }
    case Op::Related: {
        ChildTree tree;
        get_tree(r, view, tree);
        const uint32_t a = r.get<uint32_t>(), b = r.get<uint32_t>();
        arbor_bool32 related = 0;
        const int32_t s = table<arbor_depictor_v1>(tables_, 4).related(plugin_, &tree.tree, a, b, &related);
        w.put(related);
        return s;
    }
    case Op::Legend: {
        DepictionInput in;
        in.read(r, view);
        arbor_image image = get_image(r, view);
        image.depth = nullptr;
        image.label_visibility = nullptr;
        image.label_visibility_count = 0;
        return table<arbor_depictor_v1>(tables_, 4).legend(plugin_, &in.request, &image, task);
    }
    case Op::Generate: {
        arbor_tf_request request{};
        request.struct_size = sizeof request;
        ChildVolume volume;
        if (r.get<uint32_t>()) {
            get_volume(r, view, volume);
            request.volume = &volume.volume;
        }
        ChildTree tree;
        get_tree(r, view, tree);
        request.tree = &tree.tree;
        arbor_depiction depiction{};
        if (r.get<uint32_t>()) {
            depiction = get_depiction(r, view);
            request.depiction = &depiction;
        }
        request.value_range[0] = r.get<double>();
        request.value_range[1] = r.get<double>();
        request.min_spacing = r.get<double>();
        request.background_level = r.get<double>();
        request.background_peak = r.get<double>();
        arbor_tf_set out{};
        out.struct_size = sizeof out;
        out.branch_count = r.get<uint32_t>();
        out.lut_size = r.get<uint32_t>();
        out.opacity_unit_distance = r.get<double>();
        out.domain = view.at<double>(r.get<uint64_t>());
        out.lut = view.at<float>(r.get<uint64_t>());
        out.point_offsets = view.at<uint32_t>(r.get<uint64_t>());
        out.notes = view.at<char>(r.get<uint64_t>());
        out.note_size = r.get<uint32_t>();
        if (!out.note_size)
            out.notes = nullptr;
        const int32_t s = table<arbor_tf_generator_v1>(tables_, 5).generate(plugin_, &request, &out, task);
        w.put(out.opacity_unit_distance);
        w.put(out.depiction_by_host);
        // The control points, wherever the plugin put them, into the window.
        const uint64_t count = s == ARBOR_OK && out.points ? out.point_offsets[out.branch_count] : 0;
        void *copy = count && count < (uint64_t{1} << 28) ? task_.allocate(count * sizeof(arbor_tf_point)) : nullptr;
        if (copy)
            std::memcpy(copy, out.points, count * sizeof(arbor_tf_point));
        w.put<uint64_t>(copy ? static_cast<uint64_t>(static_cast<uint8_t *>(copy) - window_) : 0);
        w.put<uint64_t>(copy ? count : 0);
        return s;
    }
    case Op::Render1:
    case Op::Render2: {
        Scene scene;
        scene.read(r, view);
        if (op == Op::Render1) {
            arbor_render_request request{};
            scene.fill(request);
            arbor_image image = get_image(r, view);
            return table<arbor_renderer_v1>(tables_, 6).render(plugin_, &request, &image, task);
        }
        arbor_render_request_v2 request{};
        scene.fill(request);
        request.pass = r.get<arbor_render_pass>();
        request.transfer_functions_revision = r.get<uint64_t>();
        request.frame_width = r.get<uint32_t>();
        request.frame_height = r.get<uint32_t>();
        request.region_x = r.get<uint32_t>();
        request.region_y = r.get<uint32_t>();
        request.region_width = r.get<uint32_t>();
        request.region_height = r.get<uint32_t>();
        request.sample_index = r.get<uint32_t>();
        arbor_image image = get_image(r, view);
        return table<arbor_renderer_v2>(tables_, 7).render(plugin_, &request, &image, task);
    }
    case Op::DescribeDevice: {
        arbor_render_device device{};
        device.struct_size = sizeof device;
        const int32_t s = table<arbor_render_device_v1>(tables_, 8).describe(plugin_, &device);
        w.put(device.kind);
        w.put_string(s == ARBOR_OK ? device.name : "", 1000);
        return s;
    }
    default:
        throw std::runtime_error("an unknown request on an instance channel");
    }
}

} // namespace arbor::plugin_host
