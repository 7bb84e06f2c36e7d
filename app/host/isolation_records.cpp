#include "isolation_records.hpp"

#include <algorithm>

namespace arbor::isolation {

uint64_t BulkPlacer::reserve(uint64_t bytes)
{
    const uint64_t at = (next_ + 63) & ~uint64_t{63};
    if (at > limit_ || bytes > limit_ - at)
        throw WireError("the data of one call does not fit the plugin's window (" + std::to_string(limit_ >> 30) +
                        " GiB)");
    next_ = at + bytes;
    return at;
}

uint64_t BulkPlacer::place(const void *data, uint64_t bytes)
{
    if (!data)
        return UINT64_MAX;
    const uint64_t at = reserve(bytes);
    if (bytes)
        std::memcpy(window_ + at, data, bytes);
    return at;
}

void put_array(MessageWriter &w, BulkPlacer &bulk, const void *data, uint64_t bytes)
{
    w.put<uint64_t>(bulk.place(data, bytes));
    w.put<uint64_t>(data ? bytes : 0);
}

void put_volume_fields(MessageWriter &w, const arbor_volume &v)
{
    w.put(v.voxel_type);
    for (int a = 0; a < 3; ++a)
        w.put(v.dims[a]);
    for (int a = 0; a < 3; ++a)
        w.put(v.spacing[a]);
    for (int a = 0; a < 3; ++a)
        w.put(v.origin[a]);
    for (double d : v.direction)
        w.put(d);
    w.put(v.value_scale);
    w.put(v.value_offset);
    w.put_string(v.value_unit, 256);
}

void get_volume_fields(MessageReader &r, arbor_volume &v, std::string &unit)
{
    v.voxel_type = r.get<arbor_voxel_type>();
    for (int a = 0; a < 3; ++a)
        v.dims[a] = r.get<int64_t>();
    for (int a = 0; a < 3; ++a)
        v.spacing[a] = r.get<double>();
    for (int a = 0; a < 3; ++a)
        v.origin[a] = r.get<double>();
    for (double &d : v.direction)
        d = r.get<double>();
    v.value_scale = r.get<double>();
    v.value_offset = r.get<double>();
    bool null = false;
    unit = r.get_string(&null);
    v.value_unit = null ? nullptr : unit.c_str();
}

uint64_t contiguous_bytes(const arbor_volume &v)
{
    return static_cast<uint64_t>(v.dims[0]) * static_cast<uint64_t>(v.dims[1]) * static_cast<uint64_t>(v.dims[2]) *
           arbor_voxel_size(v.voxel_type);
}

void copy_voxels_contiguous(const arbor_volume &v, uint8_t *out)
{
    const int64_t s = arbor_voxel_size(v.voxel_type);
    const auto *in = static_cast<const uint8_t *>(v.voxels);
    if (v.strides[0] == s && v.strides[1] == s * v.dims[0] && v.strides[2] == s * v.dims[0] * v.dims[1]) {
        std::memcpy(out, in, contiguous_bytes(v));
        return;
    }
    for (int64_t k = 0; k < v.dims[2]; ++k)
        for (int64_t j = 0; j < v.dims[1]; ++j)
            for (int64_t i = 0; i < v.dims[0]; ++i, out += s)
                std::memcpy(out, in + i * v.strides[0] + j * v.strides[1] + k * v.strides[2],
                            static_cast<std::size_t>(s));
}

void get_volume(MessageReader &r, const WindowView &view, ChildVolume &out)
{
    out.volume = arbor_volume{};
    out.volume.struct_size = sizeof(arbor_volume);
    get_volume_fields(r, out.volume, out.unit);
    const uint64_t offset = r.get<uint64_t>();
    const int64_t s = arbor_voxel_size(out.volume.voxel_type);
    out.volume.strides[0] = s;
    out.volume.strides[1] = s * out.volume.dims[0];
    out.volume.strides[2] = s * out.volume.dims[0] * out.volume.dims[1];
    out.volume.voxels = view.at<void>(offset);
}

namespace {

template <class T>
void put_n(MessageWriter &w, BulkPlacer &bulk, const T *data, uint64_t count)
{
    put_array(w, bulk, data, count * sizeof(T));
}

} // namespace

void put_tree(MessageWriter &w, BulkPlacer &bulk, const arbor_branch_tree &t)
{
    const uint64_t n = t.branch_count, m = t.measure_count;
    w.put(t.branch_count);
    w.put(t.measure_count);
    put_n(w, bulk, t.parent, n);
    put_n(w, bulk, t.depth, n);
    put_n(w, bulk, t.child_offsets, n + 1);
    put_n(w, bulk, t.children, t.child_offsets ? t.child_offsets[n] : 0);
    put_n(w, bulk, t.extremum_kind, n);
    put_n(w, bulk, t.saddle_vertex, n);
    put_n(w, bulk, t.extremum_vertex, n);
    put_n(w, bulk, t.saddle_value, n);
    put_n(w, bulk, t.extremum_value, n);
    put_n(w, bulk, t.saddle_position, 3 * n);
    put_n(w, bulk, t.extremum_position, 3 * n);
    for (uint64_t c = 0; c < m; ++c)
        w.put_string(t.measure_ids[c], 256);
    put_n(w, bulk, t.measures, n * m);
    put_n(w, bulk, t.relative_measures, n * m);
    put_n(w, bulk, t.importance, n);
    const bool mapped = ARBOR_HAS_FIELD(arbor_branch_tree, t.struct_size, value_unit);
    w.put<double>(mapped ? t.value_scale : 1.0);
    w.put<double>(mapped ? t.value_offset : 0.0);
    w.put_string(mapped && t.value_unit ? t.value_unit : "", 256);
}

void get_tree(MessageReader &r, const WindowView &v, ChildTree &out)
{
    arbor_branch_tree &t = out.tree;
    t = arbor_branch_tree{};
    t.struct_size = sizeof t;
    t.branch_count = r.get<uint32_t>();
    t.measure_count = r.get<uint32_t>();
    t.parent = get_array<const int32_t>(r, v);
    t.depth = get_array<const uint32_t>(r, v);
    t.child_offsets = get_array<const uint32_t>(r, v);
    t.children = get_array<const uint32_t>(r, v);
    t.extremum_kind = get_array<const arbor_extremum_kind>(r, v);
    t.saddle_vertex = get_array<const int64_t>(r, v);
    t.extremum_vertex = get_array<const int64_t>(r, v);
    t.saddle_value = get_array<const double>(r, v);
    t.extremum_value = get_array<const double>(r, v);
    t.saddle_position = get_array<const double>(r, v);
    t.extremum_position = get_array<const double>(r, v);
    out.ids.clear();
    for (uint32_t c = 0; c < t.measure_count; ++c)
        out.ids.push_back(r.get_string());
    out.id_pointers.clear();
    for (const std::string &s : out.ids)
        out.id_pointers.push_back(s.c_str());
    t.measure_ids = out.id_pointers.data();
    t.measures = get_array<const double>(r, v);
    t.relative_measures = get_array<const double>(r, v);
    t.importance = get_array<const double>(r, v);
    t.value_scale = r.get<double>();
    t.value_offset = r.get<double>();
    out.unit = r.get_string();
    t.value_unit = out.unit.c_str();
}

void put_rows(MessageWriter &w, const arbor_measure_rows &rows)
{
    const uint64_t n = rows.row_count, m = rows.measure_count;
    w.put(rows.row_count);
    w.put(rows.measure_count);
    for (uint64_t c = 0; c < m; ++c)
        w.put_string(rows.measure_ids[c], 256);
    w.put_sized(rows.measures, rows.measures ? n * m * sizeof(double) : 0);
    w.put_sized(rows.relative_measures, rows.relative_measures ? n * m * sizeof(double) : 0);
    const bool v14 = ARBOR_HAS_FIELD(arbor_measure_rows, rows.struct_size, value_unit);
    w.put_sized(v14 ? rows.extremum_kind : nullptr, v14 && rows.extremum_kind ? n * sizeof(arbor_extremum_kind) : 0);
    w.put_sized(v14 ? rows.saddle_value : nullptr, v14 && rows.saddle_value ? n * sizeof(double) : 0);
    w.put_sized(v14 ? rows.extremum_value : nullptr, v14 && rows.extremum_value ? n * sizeof(double) : 0);
    w.put<int32_t>(v14 ? rows.root_row : -1);
    w.put<double>(v14 ? rows.value_scale : 1.0);
    w.put<double>(v14 ? rows.value_offset : 0.0);
    w.put_string(v14 && rows.value_unit ? rows.value_unit : "", 256);
}

void get_rows(MessageReader &r, ChildRows &out)
{
    arbor_measure_rows &rows = out.rows;
    rows = arbor_measure_rows{};
    rows.struct_size = sizeof rows;
    rows.row_count = r.get<uint32_t>();
    rows.measure_count = r.get<uint32_t>();
    out.ids.clear();
    for (uint32_t c = 0; c < rows.measure_count; ++c)
        out.ids.push_back(r.get_string());
    out.id_pointers.clear();
    for (const std::string &s : out.ids)
        out.id_pointers.push_back(s.c_str());
    rows.measure_ids = out.id_pointers.data();
    // std::string's buffer is aligned for any fundamental type (operator new).
    out.measures = r.get_sized();
    out.relative = r.get_sized();
    out.kind = r.get_sized();
    out.saddle = r.get_sized();
    out.extremum = r.get_sized();
    auto pointer = [](const std::string &s) { return s.empty() ? nullptr : s.data(); };
    rows.measures = reinterpret_cast<const double *>(pointer(out.measures));
    rows.relative_measures = reinterpret_cast<const double *>(pointer(out.relative));
    rows.extremum_kind = reinterpret_cast<const arbor_extremum_kind *>(pointer(out.kind));
    rows.saddle_value = reinterpret_cast<const double *>(pointer(out.saddle));
    rows.extremum_value = reinterpret_cast<const double *>(pointer(out.extremum));
    rows.root_row = r.get<int32_t>();
    rows.value_scale = r.get<double>();
    rows.value_offset = r.get<double>();
    out.unit = r.get_string();
    rows.value_unit = out.unit.c_str();
}

void put_label_hierarchy(MessageWriter &w, BulkPlacer &bulk, const arbor_label_map *labels)
{
    const bool has = labels && ARBOR_HAS_FIELD(arbor_label_map, labels->struct_size, saddle_value) &&
                     labels->parent && labels->saddle_value;
    const uint64_t n = has ? labels->label_count : 0;
    put_n(w, bulk, has ? labels->parent : nullptr, n);
    put_n(w, bulk, has ? labels->saddle_value : nullptr, n);
}

void get_label_hierarchy(MessageReader &r, const WindowView &v, arbor_label_map &labels)
{
    labels.parent = get_array<const int32_t>(r, v);
    labels.saddle_value = get_array<const double>(r, v);
}

void put_tf_input(MessageWriter &w, BulkPlacer &bulk, const arbor_tf_set &set)
{
    const uint64_t n = set.branch_count;
    w.put(set.branch_count);
    w.put(set.lut_size);
    w.put(set.opacity_unit_distance);
    put_n(w, bulk, set.domain, 2 * n);
    put_n(w, bulk, set.lut, n * set.lut_size * 4);
    put_n(w, bulk, set.point_offsets, n + 1);
    put_n(w, bulk, set.points, set.point_offsets && set.points ? set.point_offsets[n] : 0);
}

void get_tf_input(MessageReader &r, const WindowView &v, ChildTfSet &out)
{
    arbor_tf_set &s = out.set;
    s = arbor_tf_set{};
    s.struct_size = sizeof s;
    s.branch_count = r.get<uint32_t>();
    s.lut_size = r.get<uint32_t>();
    s.opacity_unit_distance = r.get<double>();
    s.domain = get_array<double>(r, v);
    s.lut = get_array<float>(r, v);
    s.point_offsets = get_array<uint32_t>(r, v);
    s.points = get_array<arbor_tf_point>(r, v);
}

void put_param_desc(MessageWriter &w, const arbor_param_desc &d)
{
    w.put(d.type);
    w.put_string(d.id, 256);
    w.put_string(d.name, 4096);
    w.put_string(d.group, 4096);
    w.put_string(d.unit, 4096);
    w.put_string(d.hint, 4096);
    w.put(d.components);
    w.put(d.flags);
    w.put(d.min_value);
    w.put(d.max_value);
    for (double x : d.default_value)
        w.put(x);
    const uint32_t choices = d.type == ARBOR_PARAM_CHOICE && d.choices ? std::min<uint32_t>(d.choice_count, 4096) : 0;
    w.put(choices);
    for (uint32_t c = 0; c < choices; ++c)
        w.put_string(d.choices[c], 4096);
    w.put<uint32_t>(choices && d.choice_names ? 1 : 0);
    for (uint32_t c = 0; choices && d.choice_names && c < choices; ++c)
        w.put_string(d.choice_names[c], 4096);
    w.put_string(d.default_text, 1 << 16);
}

void OwnedParamDesc::point()
{
    desc.id = id.c_str();
    desc.name = name.c_str();
    desc.group = group.c_str();
    desc.unit = unit.c_str();
    desc.hint = hint.c_str();
    desc.default_text = default_text.c_str();
    choice_pointers.clear();
    for (const std::string &c : choices)
        choice_pointers.push_back(c.c_str());
    choice_name_pointers.clear();
    for (const std::string &c : choice_names)
        choice_name_pointers.push_back(c.c_str());
    desc.choices = choice_pointers.empty() ? nullptr : choice_pointers.data();
    desc.choice_names = has_choice_names ? choice_name_pointers.data() : nullptr;
}

void get_param_desc(MessageReader &r, OwnedParamDesc &out)
{
    arbor_param_desc &d = out.desc;
    d = arbor_param_desc{};
    d.struct_size = sizeof d;
    d.type = r.get<arbor_param_type>();
    out.id = r.get_string();
    out.name = r.get_string();
    out.group = r.get_string();
    out.unit = r.get_string();
    out.hint = r.get_string();
    d.components = r.get<uint32_t>();
    d.flags = r.get<arbor_param_flags>();
    d.min_value = r.get<double>();
    d.max_value = r.get<double>();
    for (double &x : d.default_value)
        x = r.get<double>();
    d.choice_count = r.get<uint32_t>();
    if (d.choice_count > 4096)
        throw WireError("a parameter with more than 4096 choices");
    out.choices.clear();
    for (uint32_t c = 0; c < d.choice_count; ++c)
        out.choices.push_back(r.get_string());
    out.has_choice_names = r.get<uint32_t>() != 0;
    out.choice_names.clear();
    for (uint32_t c = 0; out.has_choice_names && c < d.choice_count; ++c)
        out.choice_names.push_back(r.get_string());
    out.default_text = r.get_string();
    out.point();
}

void put_param_value(MessageWriter &w, const arbor_param_value &v)
{
    w.put(v.type);
    w.put(v.components);
    for (double x : v.number)
        w.put(x);
    w.put_string(v.text, 1 << 20);
}

void get_param_value(MessageReader &r, arbor_param_value &v, std::string &text)
{
    v.type = r.get<arbor_param_type>();
    v.components = r.get<uint32_t>();
    for (double &x : v.number)
        x = r.get<double>();
    bool null = false;
    text = r.get_string(&null);
    v.text = null ? nullptr : text.c_str();
}

} // namespace arbor::isolation
