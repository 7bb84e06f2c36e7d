// `arbor render <volume> --tf tf.json -o image.png`: renders with transfer
// functions written by `arbor tf` (or edited since).  The labels are rebuilt
// from the volume with the simplifier and cut the file records, and the
// pipeline checks them against the file's branches, so functions made for
// another volume or another simplification are refused instead of misapplied.
// Without --tf it renders what `arbor run` would (or a --session).  With
// --orbit N it writes a turntable: N frames once round the volume, as a
// video or a folder of PNGs, at --quality coarse, full or supersampled, and
// a report of seconds per frame and per pass beside it.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "provenance.hpp"
#include "input_flags.hpp"
#include "usage_error.hpp"
#include "view_flags.hpp"

#include "io/image_output.hpp"
#include "io/json_writer.hpp"
#include "io/turntable_output.hpp"
#include "pipeline/session.hpp"
#include "pipeline/transfer_function_file.hpp"
#include "pipeline/turntable.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <numeric>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct RenderArgs {
    InputFlags input;
    FilterFlags filter;
    ViewFlags view;
    std::string tf, output, session, quality = "full";
    uint32_t orbit = 0, supersamples = 4;
    double fps = 24;
};

// The frames through the writer, a line of progress each, and the report.
int write_turntable(CommandPipeline &p, const RenderArgs &a, const Context &context)
{
    pipeline::TurntableOptions options;
    options.frames = a.orbit;
    options.quality = pipeline::parse_quality(a.quality);
    options.supersamples = a.supersamples;
    const pipeline::ViewChoice view = p->document().view;
    io::TurntableWriter writer(a.output, view.width, view.height, a.fps);
    std::vector<pipeline::TurntableFrame> timings;
    pipeline::render_turntable(*p, options, [&](const pipeline::TurntableFrame &f) {
        writer.add(f.image);
        std::fprintf(stderr, "\rturntable: frame %u of %u (%.2f s)", f.index + 1, options.frames, f.seconds);
        pipeline::TurntableFrame t;
        t.index = f.index;
        t.azimuth = f.azimuth;
        t.pass_seconds = f.pass_seconds;
        t.seconds = f.seconds;
        timings.push_back(std::move(t));
    });
    std::fprintf(stderr, "\n");
    writer.finish();
    const double total = std::accumulate(timings.begin(), timings.end(), 0.0,
                                         [](double s, const pipeline::TurntableFrame &f) { return s + f.seconds; });
    const std::filesystem::path report = std::filesystem::path(a.output).string() + ".report.json";
    io::write_json_file(report, io::JsonLayout::indented, [&](io::JsonWriter &j) {
        j.field("format", "arbor-turntable-report/1");
        const pipeline::Document d = p->document();
        write_provenance(j, context, p->catalog(),
                         provenance_of(d, p.run<Stage::Import>().get(), p.run<Stage::Filter>()->filters));
        j.field("output", std::filesystem::path(a.output).string());
        j.field("kind", writer.kind());
        j.field("frames", options.frames);
        j.field("quality", pipeline::quality_name(options.quality));
        j.field("width", view.width);
        j.field("height", view.height);
        j.field("frames_per_second_of_the_video", a.fps);
        j.field("renderer", view.renderer.id);
        j.field("seconds", total);
        j.field("seconds_per_frame", total / options.frames);
        auto frames = j.array("per_frame");
        for (const pipeline::TurntableFrame &f : timings) {
            auto o = j.object();
            j.field("frame", f.index + 1);
            j.field("azimuth", f.azimuth);
            j.field("seconds", f.seconds);
            j.field("pass_seconds", f.pass_seconds);
        }
    });
    std::printf("%s: %u frames (%s, %s) -> %s, %.2f s a frame; report %s\n",
                p.run<Stage::Filter>()->source.c_str(), options.frames, pipeline::quality_name(options.quality),
                writer.kind(), a.output.c_str(), total / options.frames, report.string().c_str());
    return 0;
}

} // namespace

void add_render_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand("render", "Render a volume with per-branch transfer functions from `arbor tf` "
                                                 "(or those `arbor run` makes); --orbit N: a turntable video");
    auto a = std::make_shared<RenderArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("--tf", a->tf, "Transfer functions (arbor-transfer-functions/1 JSON); default: those "
                                   "`arbor run` would make (or the session's)");
    sub->add_option("--session", a->session, "Start from this session (arbor-session/1); flags given override it");
    sub->add_option("-o,--output", a->output,
                    "Image to write (.png or .exr); with --orbit a video (.mp4, .avi, .gif) or a folder of PNGs (a "
                    "path without suffix)")
        ->required();
    sub->add_option("--orbit", a->orbit, "A turntable of N frames, once round the volume from the view's azimuth")
        ->check(CLI::Range(1u, 36000u));
    sub->add_option("--quality", a->quality,
                    "Turntable frames: coarse (the interactive pass), full, or supersampled (full, then "
                    "--supersamples passes)")
        ->check(CLI::IsMember({"coarse", "full", "supersampled"}))
        ->default_str("full");
    sub->add_option("--supersamples", a->supersamples, "Passes after the full one for --quality supersampled")
        ->check(CLI::Range(1u, 256u))
        ->default_str("4");
    sub->add_option("--fps", a->fps, "Frames per second of the video")->check(CLI::Range(0.1, 240.0))->default_str("24");
    a->view.add_to(*sub, context);
    context.add_command(sub, [a, &context]() {
        CommandPipeline p(context, !a->input.no_cache());
        const pipeline::PluginCatalog &catalog = p->catalog();
        pipeline::Document d = pipeline::default_document();
        if (!a->session.empty()) {
            pipeline::SessionRead read = pipeline::read_session(a->session, catalog, !a->input.given());
            for (const std::string &w : read.warnings)
                log_message(ARBOR_LOG_WARNING, "", w);
            d = read.document;
        }
        a->input.apply(d.input, catalog);
        if (d.input.empty())
            throw UsageError("no volume: give a file or folder, --phantom head or --session");
        a->filter.apply(d.filters, d.auto_denoise, catalog);
        if (!a->tf.empty()) {
            const pipeline::StoredTransferFunctions stored = pipeline::read_transfer_functions(a->tf);
            d.simplifier = {stored.simplifier_id, "", {}};
            d.cut = pipeline::CutChoice::parse(stored.cut);
            d.appearance.transfer_functions_file = a->tf;
        }
        a->view.apply(d.view, catalog);
        p->set_document(d);
        if (a->orbit > 0)
            return write_turntable(p, *a, context);
        const auto render = p.run<Stage::Render>();
        io::write_image(a->output, render->image);
        std::printf("%s: %u branches rendered by %s -> %s (%.0f%% covered)\n", p.run<Stage::Filter>()->source.c_str(),
                    p.run<Stage::TransferFunctions>()->functions->branch_count(), render->renderer.id.c_str(),
                    a->output.c_str(), 100.0 * io::covered_fraction(render->image));
        return 0;
    });
}

} // namespace arbor::cli
