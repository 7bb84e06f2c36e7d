#include "filter_run.hpp"

namespace arbor {

Volume run_filter(PluginInstance &filter, const Volume &input, ProgressSink *progress,
                  uint64_t max_bytes, std::stop_token stop)
{
    const auto &table = filter.interface<arbor_filter_v1>(ARBOR_INTERFACE_FILTER);
    const arbor_volume in = input.view();
    arbor_voxel_type out_type = ARBOR_VOXEL_UNKNOWN;
    arbor_status s;
    {
        const auto lock = filter.serial();
        s = table.output_type(filter.get(), &in, &out_type);
    }
    filter.check(s, "choosing the output voxel type");
    Volume output = Volume::allocate(out_type, input.geometry(), input.mapping(), max_bytes);
    arbor_volume out = output.view();
    Task task(progress, std::move(stop));
    {
        const auto lock = filter.serial();
        s = table.apply(filter.get(), &in, &out, task.get());
    }
    filter.check(s, "filtering the volume");
    return output;
}

} // namespace arbor
