// `arbor convert`: read any supported volume (or a phantom), optionally run a
// filter plugin on it, and write NRRD.  Filter parameters become flags.
#include "commands.hpp"
#include "volume_input.hpp"

#include "core/nrrd_writer.hpp"
#include "host/filter_run.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

struct ConvertArgs {
    VolumeInput input;
    std::string output;
    std::string filter;
    bool raw = false;
    std::vector<PluginInstance> filters;
    PluginOptions filter_options;
};

} // namespace

void add_convert_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "convert", "Read a volume, optionally filter it, and write it as NRRD");
    auto a = std::make_shared<ConvertArgs>();
    a->input.add_to(*sub, context);
    sub->add_option("-o,--output", a->output, "Output NRRD file")->required();
    sub->add_option("--filter", a->filter, "Filter plugin id to apply before writing");
    sub->add_flag("--raw", a->raw, "Write raw (uncompressed) voxel data");
    for (const PluginInfo *info : context.registry.plugins_of_kind(ARBOR_KIND_FILTER)) {
        try {
            a->filters.push_back(context.registry.create(info->descriptor->id));
        } catch (const PluginError &e) {
            log_message(ARBOR_LOG_WARNING, "", e.what());
        }
    }
    std::vector<PluginInstance *> ptrs;
    for (PluginInstance &p : a->filters)
        ptrs.push_back(&p);
    a->filter_options.add(*sub, "Filter options", ptrs);

    context.add_command(sub, [a, &context]() {
        LoadedVolume in = a->input.load();
        Volume out = std::move(in.volume);
        if (!a->filter.empty()) {
            PluginInstance *filter = nullptr;
            for (PluginInstance &p : a->filters)
                if (p.id() == a->filter)
                    filter = &p;
            if (!filter)
                throw std::invalid_argument("no filter plugin with id '" + a->filter +
                                            "' (see `arbor plugins`)");
            a->filter_options.apply(*filter);
            out = run_filter(*filter, out, &context.progress, context.max_volume_bytes);
        }
        NrrdWriteOptions w;
        w.gzip = !a->raw;
        w.content = in.source + (a->filter.empty() ? "" : " | " + a->filter);
        write_nrrd(out, a->output, w);
        std::printf("wrote %s\n", a->output.c_str());
        return 0;
    });
}

} // namespace arbor::cli
