// isolation_records.hpp - the SDK's records on the wire between the host and
// an isolated plugin's process (isolation_wire.hpp).
//
// Arrays travel in the window's bulk area: the writer places them and puts
// their offset and size into the message; the reader points at them in its
// own mapping of the window.  The child trusts what the host wrote; the host
// checks every offset the child gives back (BulkView::at).
#pragma once

#include "isolation_wire.hpp"

#include <arbor/arbor.h>

#include <memory>
#include <string>
#include <vector>

namespace arbor::isolation {

// The host's placement of arrays in a window's bulk area for one call.
class BulkPlacer {
public:
    BulkPlacer(uint8_t *window, uint64_t window_bytes, uint64_t start)
        : window_(window), limit_(window_bytes), next_(start) {}
    // Room for `bytes`, 64-byte aligned; its offset.  Throws WireError when
    // the window is full.
    uint64_t reserve(uint64_t bytes);
    // Copies `bytes` from `data` into new room; UINT64_MAX for NULL.
    uint64_t place(const void *data, uint64_t bytes);
    uint8_t *at(uint64_t offset) const { return window_ + offset; }
    uint64_t next() const { return next_; }

private:
    uint8_t *window_;
    uint64_t limit_, next_;
};

// The child's view of a window: pointers from offsets (trusted).
struct WindowView {
    uint8_t *window;
    template <class T>
    T *at(uint64_t offset) const
    {
        return offset == UINT64_MAX ? nullptr : reinterpret_cast<T *>(window + offset);
    }
};

// The host's view: offsets the child gave, checked against the window.
struct CheckedWindow {
    const uint8_t *window;
    uint64_t bytes;
    // `count` elements of T at `offset`, inside the bulk area; throws WireError.
    template <class T>
    const T *at(uint64_t offset, uint64_t count) const
    {
        if (offset < kBulkAt || offset > bytes || count > (bytes - offset) / sizeof(T) ||
            offset % alignof(T) != 0)
            throw WireError("an array the plugin's process returned lies outside its window");
        return reinterpret_cast<const T *>(window + offset);
    }
};

// An array placed in bulk: offset (UINT64_MAX for NULL) and bytes.
void put_array(MessageWriter &w, BulkPlacer &bulk, const void *data, uint64_t bytes);
template <class T>
T *get_array(MessageReader &r, const WindowView &v, uint64_t *bytes = nullptr)
{
    const uint64_t offset = r.get<uint64_t>(), n = r.get<uint64_t>();
    if (bytes)
        *bytes = n;
    return v.at<T>(offset);
}

// A volume's fields without its voxels, and the unit.
void put_volume_fields(MessageWriter &w, const arbor_volume &v);
void get_volume_fields(MessageReader &r, arbor_volume &v, std::string &unit);
// Bytes the voxels of `v` span when contiguous (i fastest).
uint64_t contiguous_bytes(const arbor_volume &v);
// Copies v's voxels, whatever their strides, contiguously into `out`.
void copy_voxels_contiguous(const arbor_volume &v, uint8_t *out);

// A volume the child reads: the record and what it points to.
struct ChildVolume {
    arbor_volume volume{};
    std::string unit;
};
void get_volume(MessageReader &r, const WindowView &v, ChildVolume &out); // voxels placed by the host

// A branch tree (input of depictors and generators).
void put_tree(MessageWriter &w, BulkPlacer &bulk, const arbor_branch_tree &t);
struct ChildTree {
    arbor_branch_tree tree{};
    std::vector<std::string> ids;
    std::vector<const char *> id_pointers;
    std::string unit;
};
void get_tree(MessageReader &r, const WindowView &v, ChildTree &out);

// Measure rows (simplifiers): inline, they are small.
void put_rows(MessageWriter &w, const arbor_measure_rows &rows);
struct ChildRows {
    arbor_measure_rows rows{};
    std::vector<std::string> ids;
    std::vector<const char *> id_pointers;
    std::string measures, relative, kind, saddle, extremum, unit;
};
void get_rows(MessageReader &r, ChildRows &out);

// How a label map's labels nest (parent, saddle value; since ABI 1.6),
// after the map itself; nothing when the map has none.
void put_label_hierarchy(MessageWriter &w, BulkPlacer &bulk, const arbor_label_map *labels);
void get_label_hierarchy(MessageReader &r, const WindowView &v, arbor_label_map &labels);

// A transfer-function set as a renderer's input.
void put_tf_input(MessageWriter &w, BulkPlacer &bulk, const arbor_tf_set &set);
struct ChildTfSet {
    arbor_tf_set set{};
};
void get_tf_input(MessageReader &r, const WindowView &v, ChildTfSet &out);

// Parameter descriptions (child to host) and values (both ways).
void put_param_desc(MessageWriter &w, const arbor_param_desc &d);
// A description the host owns, with every string it points to.
struct OwnedParamDesc {
    arbor_param_desc desc{};
    std::string id, name, group, unit, hint, default_text;
    std::vector<std::string> choices, choice_names;
    std::vector<const char *> choice_pointers, choice_name_pointers;
    bool has_choice_names = false;
    void point(); // sets desc's pointers at the strings
};
void get_param_desc(MessageReader &r, OwnedParamDesc &out);
void put_param_value(MessageWriter &w, const arbor_param_value &v);
void get_param_value(MessageReader &r, arbor_param_value &v, std::string &text);

} // namespace arbor::isolation
