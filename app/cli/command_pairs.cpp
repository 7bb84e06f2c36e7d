// `arbor pairs <volume> -o pairs.txt`: the saddle-extremum pairs of the
// persistence branch decomposition (the persistence diagram), as TTK's
// reference text (txt), as CSV, or as a VTK unstructured grid in the layout
// of TTK's PersistenceDiagram filter (vtu); `--plot` draws the diagram.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "diagram_plot.hpp"
#include "input_flags.hpp"
#include "stage_timings.hpp"

#include "core/atomic_file.hpp"
#include "io/persistence_diagram_files.hpp"
#include "io/persistence_diagram_vtu.hpp"
#include "topology/persistence_diagram.hpp"
#include "topology/persistence_pairs.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct PairsArgs {
    InputFlags input;
    FilterFlags filter;
    std::string output;
    std::string format; // txt, csv, vtu; empty: from the output's extension
    std::vector<std::string> plots;
    DiagramPlotStyle plot_style;
    bool timings = false;
};

std::string format_of(const PairsArgs &a)
{
    if (!a.format.empty())
        return a.format;
    const std::string ext = std::filesystem::path(a.output).extension().string();
    return ext == ".csv" ? "csv" : ext == ".vtu" ? "vtu" : "txt";
}

std::string plot_extension_problem(const std::string &path)
{
    const std::string ext = std::filesystem::path(path).extension().string();
    return ext == ".png" || ext == ".svg" ? std::string() : "a plot is written as .png or .svg, not '" + path + "'";
}

} // namespace

void add_pairs_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "pairs", "Write the persistence diagram: the contour tree's saddle-extremum pairs (TTK's columns, CSV or VTU),\n"
                 "and draw it (--plot)");
    auto a = std::make_shared<PairsArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("-o,--output", a->output,
                    "Output file ('-' for standard output; txt and csv only). Needed unless --plot is given");
    sub->add_option("--format", a->format,
                    "txt: TTK's reference columns; csv: one row per pair with its homology dimension and the "
                    "essential pair marked; vtu: TTK's PersistenceDiagram layout for ParaView. Default: from the "
                    "output's extension (.csv, .vtu, else txt)")
        ->check(CLI::IsMember({"txt", "csv", "vtu"}));
    sub->add_option("--plot", a->plots, "Draw the diagram into FILE.png or FILE.svg (repeatable)")
        ->check(CLI::Validator(plot_extension_problem, "FILE.png|FILE.svg"));
    sub->add_option("--dpi", a->plot_style.dpi, "Resolution of PNG plots")
        ->check(CLI::Range(18.0, 2400.0))
        ->capture_default_str();
    sub->add_option("--plot-size", a->plot_style.size_inches, "Side of the (square) plot in inches")
        ->check(CLI::Range(1.5, 40.0))
        ->capture_default_str();
    sub->add_flag("--timings", a->timings, "Print per-stage seconds and peak memory on stderr");
    sub->callback([a, sub]() {
        if (a->output.empty() && a->plots.empty())
            throw CLI::ValidationError("-o,--output", "give an output file (-o) or a plot (--plot)");
        if (a->output == "-" && format_of(*a) == "vtu")
            throw CLI::ValidationError("--format", "a VTU file cannot go to standard output");
        (void)sub;
    });
    context.add_command(sub, [a, &context]() {
        CommandPipeline p(context, !a->input.no_cache());
        pipeline::Document d = pipeline::default_document();
        a->input.apply(d.input, p->catalog());
        d.auto_denoise = false; // analysis sees the data as it is, unless a filter is asked for
        a->filter.apply(d.filters, d.auto_denoise, p->catalog());
        d.simplifier = {"org.arbor.simplifier.persistence", "", {}};
        p->set_document(d);
        const auto filtered = p.run<Stage::Filter>();
        const auto tree = p.run<Stage::ContourTree>();
        const auto decomposition = p.run<Stage::Decomposition>();
        const Volume &volume = *filtered->volume;
        const topology::FieldView field{volume.type(), volume.data(), static_cast<uint32_t>(volume.voxel_count()),
                                        &volume.geometry()};
        const auto pairs = topology::persistence_pairs(tree->tree, decomposition->branches, field);
        if (!a->output.empty()) {
            const std::string format = format_of(*a);
            if (format == "vtu") {
                io::write_persistence_diagram_vtu(a->output, pairs, volume.geometry());
            } else {
                std::ostringstream text;
                if (format == "csv")
                    io::write_pairs_csv(text, pairs, volume.geometry(), volume.type());
                else
                    topology::write_persistence_pairs(text, pairs, volume.geometry(), volume.type(),
                                                      filtered->source);
                if (a->output == "-") {
                    std::fputs(text.str().c_str(), stdout);
                } else {
                    AtomicFile out(a->output);
                    out.write(text.str());
                    out.commit();
                }
            }
        }
        if (!a->plots.empty()) {
            const ValueMapping &m = volume.mapping();
            const std::string unit = m.scale == 1.0 && m.offset == 0.0 && !m.unit.empty() ? m.unit : "stored value";
            const std::string name = std::filesystem::path(filtered->source).filename().string();
            for (const std::string &plot : a->plots)
                write_diagram_plot(plot, pairs, topology::grid_dimension(volume.geometry()), name, unit,
                                   a->plot_style);
        }
        if (a->timings)
            print_timings(*tree, decomposition.get(), volume);
        return 0;
    });
}

} // namespace arbor::cli
