#include "filter_run.hpp"

namespace arbor {

Volume run_filter(PluginInstance &filter, const Volume &input, ProgressSink *progress,
                  uint64_t max_bytes, std::stop_token stop)
{
    const auto &table = filter.interface<arbor_filter_v1>(ARBOR_INTERFACE_FILTER);
    const arbor_volume in = input.view();
    arbor_voxel_type out_type = ARBOR_VOXEL_UNKNOWN;
    filter.check(filter.call("filter.output_type", table.output_type, &in, &out_type), "choosing the output voxel type");
    Volume output = Volume::allocate(out_type, input.geometry(), input.mapping(), max_bytes);
    arbor_volume out = output.view();
    Task task(progress, std::move(stop));
    filter.check(filter.call("filter.apply", table.apply, &in, &out, task.get()), "filtering the volume");
    return output;
}

} // namespace arbor
