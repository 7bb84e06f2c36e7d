// `arbor denoise-study <volume> --out DIR [--truth labels.nrrd]`: how the
// contour tree shrinks as a denoising filter gets stronger.  Sweeps one
// filter parameter, builds the contour tree at every strength, and writes
// study.csv and study.png/.svg (branch and extremum counts against strength,
// log scale) with the plateau it suggests marked: the first strength after
// which stronger filtering stops paying off, where noise is gone but
// structures are not yet melting.  When the branch count still falls steeply
// at the range's end there is no plateau in it, and the study says so.  With
// a ground truth it also simplifies at every strength and plots the Dice of
// each truth structure (one-to-one matching) against strength.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "input_flags.hpp"
#include "look_flags.hpp"
#include "study_run.hpp"
#include "usage_error.hpp"

#include "core/atomic_file.hpp"
#include "pipeline/auto_denoise.hpp"
#include "io/figure.hpp"
#include "io/plot_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

namespace arbor::cli {

namespace {

struct StudyArgs {
    InputFlags input;
    PluginFlags filter_flags;
    SimplifierFlags simplifier;
    std::string filter = "org.arbor.filter.gaussian", param = "sigma", out, truth, truth_colors,
                simplifier_name = "itri";
    std::optional<std::size_t> keep;
    double from = 0.0, to = 4.0, dpi = 150;
    int steps = 9;
};

struct StudyPoint {
    double strength = 0;
    std::size_t branches = 0, minima = 0, maxima = 0, kept = 0;
    std::vector<double> dice; // per truth structure, with --truth
    double seconds = 0;
};

void plot(const std::filesystem::path &path, const std::vector<StudyPoint> &p, std::optional<std::size_t> plateau,
          const std::string &title, const std::string &axis, const std::vector<TruthStructure> &truth, double dpi)
{
    const io::Colour ink{0.12, 0.12, 0.12}, mark{0.80, 0.15, 0.12};
    const io::Colour colours[] = {io::colour_from_8bit(213, 94, 0), io::colour_from_8bit(0, 158, 115),
                                  io::colour_from_8bit(0, 114, 178)};
    double lo = INFINITY, hi = 1;
    for (const StudyPoint &q : p) {
        lo = std::min(lo, static_cast<double>(std::max<std::size_t>(std::min(q.minima, q.maxima), 1)));
        hi = std::max(hi, static_cast<double>(q.branches));
    }
    lo = std::pow(10.0, std::floor(std::log10(lo)));
    hi = std::max(std::pow(10.0, std::ceil(std::log10(hi))), lo * 10);
    const double s0 = p.front().strength, s1 = p.back().strength > s0 ? p.back().strength : s0 + 1;
    const bool dice = !truth.empty();
    const double pw = 300, ph = 190, left = 56, top = 44, between = 64;
    const double width = left + pw + (dice ? between + pw : 0) + 24, height = top + ph + 70;
    io::write_figure_with_svg(path, width, height, dpi, [&](io::Canvas &cv) {
        cv.text(8, 15, cv.fitted(title, 9.5, width - 16, true), 9.5, ink, io::TextAnchor::Start, true);
        cv.text(8, 28,
                cv.fitted(plateau ? "plateau: the first strength after which a step removes under a fifth of the "
                                    "steepest step's branches"
                                  : "no plateau in this range: the tree still shrinks fast at its end",
                          8, width - 16),
                8, plateau ? ink : mark);
        const io::PlotFrame counts(left, top, pw, ph, {s0, s1, false, axis}, {lo, hi, true, "count"});
        counts.draw_axes(cv, 8);
        struct Series {
            const char *name;
            std::size_t StudyPoint::*count;
        };
        const Series series[] = {{"branches", &StudyPoint::branches},
                                 {"minima", &StudyPoint::minima},
                                 {"maxima", &StudyPoint::maxima}};
        for (std::size_t n = 0; n < 3; ++n) {
            std::vector<std::pair<double, double>> line;
            for (const StudyPoint &q : p)
                line.emplace_back(counts.px(q.strength),
                                  counts.py(std::max(1.0, static_cast<double>(q.*series[n].count))));
            cv.polyline(line, colours[n], 1.3);
            for (const auto &[x, y] : line)
                cv.marker(x, y, io::Marker::Circle, 4, colours[n]);
            cv.line(left + 8 + n * 90.0, top + ph + 52, left + 24 + n * 90.0, top + ph + 52, colours[n], 1.3);
            cv.text(left + 28 + n * 90.0, top + ph + 55, series[n].name, 8, ink);
        }
        if (plateau) {
            const double x = counts.px(p[*plateau].strength);
            cv.line(x, top, x, top + ph, mark, 1.2, true);
            cv.text(x + 3, top + 10, "plateau", 8, mark);
        }
        if (!dice)
            return;
        const double x0 = left + pw + between;
        const io::PlotFrame scores(x0, top, pw, ph, {s0, s1, false, axis}, {0, 1, false, "Dice (one-to-one)"});
        scores.draw_axes(cv, 8);
        for (std::size_t t = 0; t < truth.size(); ++t) {
            const io::Colour c = io::colour_from_8bit(truth[t].colour[0], truth[t].colour[1], truth[t].colour[2]);
            std::vector<std::pair<double, double>> line;
            for (const StudyPoint &q : p)
                line.emplace_back(scores.px(q.strength), scores.py(q.dice[t]));
            cv.polyline(line, c, 1.3);
            for (const auto &[x, y] : line)
                cv.marker(x, y, io::Marker::Square, 4, c);
            if (t < 4) {
                cv.rectangle(x0 + t * 75.0, top + ph + 46, 8, 8, c);
                cv.text(x0 + 11 + t * 75.0, top + ph + 54, cv.fitted(truth[t].name, 8, 60), 8, ink);
            }
        }
    });
}

} // namespace

void add_denoise_study_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "denoise-study", "Sweep a denoising filter's strength and plot the contour tree's size against it");
    auto a = std::make_shared<StudyArgs>();
    a->input.add_to(*sub, context);
    sub->add_option("--filter", a->filter,
                    "Filter plugin: a short name or id of those loaded (" +
                        plugin_names(context.registry, ARBOR_KIND_FILTER) + ")")
        ->default_val("org.arbor.filter.gaussian");
    sub->add_option("--param", a->param, "The filter parameter to sweep")->default_val("sigma");
    sub->add_option("--from", a->from, "First strength (0 for the gaussian: the unfiltered volume)")->default_val(0.0);
    sub->add_option("--to", a->to, "Last strength")->default_val(4.0);
    sub->add_option("--steps", a->steps, "Strengths from --from to --to")->check(CLI::Range(2, 100))->default_val(9);
    sub->add_option("--out", a->out, "Folder for study.csv and study.png (with an SVG twin)")->required();
    sub->add_option("--truth", a->truth,
                    "Ground-truth label map with the volume's dims: simplify at every strength and plot each "
                    "structure's Dice (one-to-one matching) against it");
    sub->add_option("--truth-colors", a->truth_colors,
                    "3D Slicer colour table (.ctbl) naming the truth's labels (default: the one beside --truth)");
    sub->add_option("--simplifier", a->simplifier_name, "With --truth: the simplifier (id or last part)")
        ->default_val("itri");
    sub->add_option("--keep", a->keep,
                    "With --truth: keep N branches (root included) at every strength (default: the knee of the "
                    "importance curve)")
        ->check(CLI::Range(std::size_t{1}, std::size_t{1000000}));
    sub->add_option("--dpi", a->dpi, "Resolution of study.png")->check(CLI::Range(18.0, 2400.0))->default_val(150);
    a->filter_flags.add(*sub, context.registry, ARBOR_KIND_FILTER, "Filter options");
    context.flag_names.add(a->filter_flags);
    a->simplifier.add_to(*sub, context, false);
    context.add_command(sub, [a, &context]() {
        CommandPipeline p(context, !a->input.no_cache());
        const pipeline::PluginCatalog &catalog = p->catalog();
        pipeline::PluginSetting filter{catalog.find(ARBOR_KIND_FILTER, a->filter), "", {}};
        a->filter_flags.apply(filter);
        const arbor_param_desc *d = nullptr;
        for (const arbor_param_desc *x : catalog.descriptions(filter.id))
            if (a->param == x->id)
                d = x;
        if (!d)
            throw UsageError(filter.id + " has no parameter '" + a->param + "'");
        pipeline::Document doc = pipeline::default_document();
        doc.auto_denoise = false; // the study's own strengths, strength 0 as it is
        a->input.apply(doc.input, catalog);
        if (!a->truth.empty()) {
            a->simplifier.apply(doc.simplifier, a->simplifier_name, catalog);
            if (a->keep)
                doc.cut.keep = *a->keep;
        } else if (a->keep || !a->truth_colors.empty()) {
            throw UsageError("--keep and --truth-colors go with --truth");
        }
        p->set_document(doc);
        const auto imported = p.run<pipeline::Stage::Import>();
        std::optional<GroundTruth> truth;
        if (!a->truth.empty())
            truth = load_ground_truth(context, a->truth, a->truth_colors, imported->volume->geometry().dims);
        std::filesystem::create_directories(a->out);
        std::vector<StudyPoint> points;
        for (int i = 0; i < a->steps; ++i) {
            StudyPoint point;
            point.strength = a->from + (a->to - a->from) * i / (a->steps - 1.0);
            // Strength 0 of the gaussian is the unfiltered volume.
            std::vector<pipeline::PluginSetting> chain;
            if (!(point.strength == 0.0 && a->param == "sigma")) {
                char text[64];
                std::snprintf(text, sizeof text, "%.17g", point.strength);
                pipeline::PluginSetting step = filter;
                step.params[a->param] = text;
                chain.push_back(step);
            }
            p->set_filters(chain);
            const auto tree = p.run<pipeline::Stage::ContourTree>();
            point.seconds = p.run<pipeline::Stage::Filter>()->seconds + tree->seconds;
            for (std::size_t x = 0; x < tree->tree.node_count(); ++x) {
                point.minima += tree->tree.node_kind[x] == topology::NodeKind::Minimum;
                point.maxima += tree->tree.node_kind[x] == topology::NodeKind::Maximum;
            }
            // Every extremum but the root's two pairs with a saddle: one branch each, plus the root.
            point.branches = point.minima + point.maxima > 0 ? point.minima + point.maxima - 1 : 0;
            std::string scores;
            if (truth) {
                const auto cut = p.run<pipeline::Stage::Cut>();
                point.kept = cut->kept();
                const study::TruthMatches m = score_cut(*truth->labels, *cut, RegionScoring::Exclusive);
                scores = "  kept " + std::to_string(point.kept) + ", Dice";
                for (const study::RegionMatch &r : m.one_to_one) {
                    point.dice.push_back(r.dice);
                    char text[16];
                    std::snprintf(text, sizeof text, " %.3f", r.dice);
                    scores += text;
                }
            }
            std::printf("  %s = %-8g %10zu branches %10zu minima %10zu maxima  %.2f s%s%s\n", a->param.c_str(),
                        point.strength, point.branches, point.minima, point.maxima, point.seconds,
                        tree->from_cache ? " (tree from the cache)" : "", scores.c_str());
            std::fflush(stdout);
            points.push_back(point);
        }
        const std::optional<std::size_t> plateau = [&] {
            std::vector<uint64_t> counts;
            for (const StudyPoint &q : points)
                counts.push_back(q.branches);
            return pipeline::find_plateau(counts);
        }();
        const std::filesystem::path dir(a->out);
        AtomicFile csv(dir / "study.csv");
        csv.write(a->param + ",branches,minima,maxima,seconds,plateau");
        if (truth) {
            csv.write(",kept");
            for (const TruthStructure &t : truth->structures) {
                std::string name = t.name;
                std::replace(name.begin(), name.end(), ',', ' ');
                csv.write(",dice_" + std::to_string(t.label) + " " + name);
            }
        }
        csv.write("\n");
        for (std::size_t i = 0; i < points.size(); ++i) {
            char strength[32];
            std::snprintf(strength, sizeof strength, "%.10g", points[i].strength);
            std::string row = std::string(strength) + "," + std::to_string(points[i].branches) + "," +
                              std::to_string(points[i].minima) + "," + std::to_string(points[i].maxima) + "," +
                              std::to_string(points[i].seconds) + "," + (plateau && i == *plateau ? "1" : "0");
            if (truth) {
                row += "," + std::to_string(points[i].kept);
                for (const double x : points[i].dice) {
                    char text[32];
                    std::snprintf(text, sizeof text, ",%.6f", x);
                    row += text;
                }
            }
            csv.write(row + "\n");
        }
        csv.commit();
        plot(dir / "study.png", points, plateau, "Contour tree size of " + imported->source + " under " + filter.id,
             a->param + (d->unit && *d->unit ? std::string(" (") + d->unit + ")" : std::string()),
             truth ? truth->structures : std::vector<TruthStructure>{}, a->dpi);
        if (plateau) {
            std::printf("%s: suggested %s = %g (%zu branches, from %zu unfiltered) -> %s\n", imported->source.c_str(),
                        a->param.c_str(), points[*plateau].strength, points[*plateau].branches,
                        points.front().branches, (dir / "study.png").string().c_str());
        } else {
            const StudyPoint &last = points.back(), &before = points[points.size() - 2];
            std::printf("%s: no plateau between %s = %g and %g: the last step still removes %.0f %% of the branches "
                        "(%zu -> %zu); try a larger --to -> %s\n",
                        imported->source.c_str(), a->param.c_str(), points.front().strength, last.strength,
                        100.0 * (1.0 - static_cast<double>(last.branches) /
                                           static_cast<double>(std::max<std::size_t>(before.branches, 1))),
                        before.branches, last.branches, (dir / "study.png").string().c_str());
        }
        return 0;
    });
}

} // namespace arbor::cli
