// record_size.hpp - ARBOR_MIN_SIZE by type, for templates: the least
// struct_size the SDK demands of a record (the end of its last field in the
// ABI minor that introduced it), never sizeof, which grows with each minor.
#pragma once

#include <arbor/arbor.h>

#include <cstddef>

namespace arbor::sdk {

template <class Record> constexpr std::size_t min_record_size();

template <> constexpr std::size_t min_record_size<arbor_branch_tree>() { return ARBOR_MIN_SIZE(arbor_branch_tree); }
template <> constexpr std::size_t min_record_size<arbor_label_map>() { return ARBOR_MIN_SIZE(arbor_label_map); }
template <> constexpr std::size_t min_record_size<arbor_depiction_request>() { return ARBOR_MIN_SIZE(arbor_depiction_request); }
template <> constexpr std::size_t min_record_size<arbor_depiction>() { return ARBOR_MIN_SIZE(arbor_depiction); }
template <> constexpr std::size_t min_record_size<arbor_host>() { return ARBOR_MIN_SIZE(arbor_host); }
template <> constexpr std::size_t min_record_size<arbor_task>() { return ARBOR_MIN_SIZE(arbor_task); }
template <> constexpr std::size_t min_record_size<arbor_image>() { return ARBOR_MIN_SIZE(arbor_image); }
template <> constexpr std::size_t min_record_size<arbor_param_desc>() { return ARBOR_MIN_SIZE(arbor_param_desc); }
template <> constexpr std::size_t min_record_size<arbor_param_value>() { return ARBOR_MIN_SIZE(arbor_param_value); }
template <> constexpr std::size_t min_record_size<arbor_plugin_descriptor>() { return ARBOR_MIN_SIZE(arbor_plugin_descriptor); }
template <> constexpr std::size_t min_record_size<arbor_plugin>() { return ARBOR_MIN_SIZE(arbor_plugin); }
template <> constexpr std::size_t min_record_size<arbor_plugin_entry>() { return ARBOR_MIN_SIZE(arbor_plugin_entry); }
template <> constexpr std::size_t min_record_size<arbor_camera>() { return ARBOR_MIN_SIZE(arbor_camera); }
template <> constexpr std::size_t min_record_size<arbor_render_request>() { return ARBOR_MIN_SIZE(arbor_render_request); }
template <> constexpr std::size_t min_record_size<arbor_render_request_v2>() { return ARBOR_MIN_SIZE(arbor_render_request_v2); }
template <> constexpr std::size_t min_record_size<arbor_renderer_v2>() { return ARBOR_MIN_SIZE(arbor_renderer_v2); }
template <> constexpr std::size_t min_record_size<arbor_render_device>() { return ARBOR_MIN_SIZE(arbor_render_device); }
template <> constexpr std::size_t min_record_size<arbor_render_device_v1>() { return ARBOR_MIN_SIZE(arbor_render_device_v1); }
template <> constexpr std::size_t min_record_size<arbor_gl_target>() { return ARBOR_MIN_SIZE(arbor_gl_target); }
template <> constexpr std::size_t min_record_size<arbor_renderer_gl_v1>() { return ARBOR_MIN_SIZE(arbor_renderer_gl_v1); }
template <> constexpr std::size_t min_record_size<arbor_measure_rows>() { return ARBOR_MIN_SIZE(arbor_measure_rows); }
template <> constexpr std::size_t min_record_size<arbor_tf_request>() { return ARBOR_MIN_SIZE(arbor_tf_request); }
template <> constexpr std::size_t min_record_size<arbor_tf_set>() { return ARBOR_MIN_SIZE(arbor_tf_set); }
template <> constexpr std::size_t min_record_size<arbor_volume>() { return ARBOR_MIN_SIZE(arbor_volume); }

} // namespace arbor::sdk
