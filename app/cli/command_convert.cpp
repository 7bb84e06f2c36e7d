// `arbor convert`: read any supported volume (or a phantom), optionally run a
// filter plugin on it, and write NRRD.  Filter parameters become flags.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "input_flags.hpp"

#include "io/nrrd_writer.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

struct ConvertArgs {
    InputFlags input;
    FilterFlags filter;
    std::string output;
    bool raw = false;
};

} // namespace

void add_convert_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "convert", "Read a volume, optionally filter it, and write it as NRRD");
    auto a = std::make_shared<ConvertArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("-o,--output", a->output, "Output NRRD file")->required();
    sub->add_flag("--raw", a->raw, "Write raw (uncompressed) voxel data");
    context.add_command(sub, [a, &context]() {
        CommandPipeline p(context, false);
        pipeline::Document d = pipeline::default_document();
        a->input.apply(d.input, p->catalog());
        d.auto_denoise = false; // analysis sees the data as it is, unless a filter is asked for
        a->filter.apply(d.filters, d.auto_denoise, p->catalog());
        p->set_document(d);
        const pipeline::FilterResult &in = *p.run<pipeline::Stage::Filter>();
        io::NrrdWriteOptions w;
        w.gzip = !a->raw;
        w.content = in.source;
        io::write_nrrd(*in.volume, a->output, w);
        std::printf("wrote %s\n", a->output.c_str());
        return 0;
    });
}

} // namespace arbor::cli
