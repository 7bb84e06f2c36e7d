// `arbor denoise-study <volume> --out DIR`: how the contour tree shrinks as a
// denoising filter gets stronger.  Sweeps one filter parameter, builds the
// contour tree at every strength, and writes study.csv and study.png (branch
// and extremum counts against strength, log scale) with the plateau it
// suggests marked: the first strength after which stronger filtering stops
// paying off, where noise is gone but structures are not yet melting.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "input_flags.hpp"

#include "core/atomic_file.hpp"
#include "io/png_output.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

struct StudyArgs {
    InputFlags input;
    PluginFlags filter_flags;
    std::string filter = "gaussian", param = "sigma", out;
    double from = 0.0, to = 4.0;
    int steps = 9;
};

struct StudyPoint {
    double strength = 0;
    std::size_t branches = 0, minima = 0, maxima = 0;
    double seconds = 0;
};

// The first point whose step to the next removes less than a fifth (in
// log terms) of what the steepest step removed.
std::size_t plateau_of(const std::vector<StudyPoint> &p)
{
    std::vector<double> drop;
    for (std::size_t i = 0; i + 1 < p.size(); ++i)
        drop.push_back(std::log(std::max<double>(p[i].branches, 1)) - std::log(std::max<double>(p[i + 1].branches, 1)));
    const double steepest = drop.empty() ? 0.0 : *std::max_element(drop.begin(), drop.end());
    for (std::size_t i = 0; i < drop.size(); ++i)
        if (i > 0 && drop[i] < 0.2 * steepest)
            return i;
    return p.size() - 1;
}

void plot(const std::filesystem::path &path, const std::vector<StudyPoint> &p, std::size_t plateau,
          const std::string &title, const std::string &axis)
{
    const int w = 720, h = 440, left = 80, right = 20, top = 40, bottom = 60;
    cv::Mat m(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
    double lo = INFINITY, hi = 0;
    for (const StudyPoint &q : p) {
        lo = std::min(lo, std::log10(std::max<double>(std::min(q.minima, q.maxima), 1)));
        hi = std::max(hi, std::log10(std::max<double>(q.branches, 1)));
    }
    lo = std::floor(lo);
    hi = std::max(std::ceil(hi), lo + 1);
    const double s0 = p.front().strength, s1 = p.back().strength > s0 ? p.back().strength : s0 + 1;
    const auto at = [&](double s, double count) {
        return cv::Point(left + static_cast<int>((s - s0) / (s1 - s0) * (w - left - right)),
                         h - bottom - static_cast<int>((std::log10(std::max(count, 1.0)) - lo) / (hi - lo) *
                                                       (h - top - bottom)));
    };
    const cv::Scalar ink(40, 40, 40), grid(225, 225, 225);
    for (double d = lo; d <= hi; d += 1) {
        const int y = at(s0, std::pow(10, d)).y;
        cv::line(m, {left, y}, {w - right, y}, grid);
        cv::putText(m, "1e" + std::to_string(static_cast<int>(d)), {10, y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45, ink, 1,
                    cv::LINE_AA);
    }
    cv::rectangle(m, {left, top}, {w - right, h - bottom}, ink);
    struct Series {
        const char *name;
        std::size_t StudyPoint::*count;
        cv::Scalar colour;
    };
    const Series series[] = {{"branches", &StudyPoint::branches, cv::Scalar(200, 90, 30)},
                             {"minima", &StudyPoint::minima, cv::Scalar(40, 140, 40)},
                             {"maxima", &StudyPoint::maxima, cv::Scalar(30, 120, 220)}};
    for (std::size_t i = 0; i < p.size(); ++i) {
        for (const Series &s : series) {
            const cv::Point q = at(p[i].strength, static_cast<double>(p[i].*s.count));
            cv::circle(m, q, 4, s.colour, cv::FILLED, cv::LINE_AA);
            if (i > 0)
                cv::line(m, at(p[i - 1].strength, static_cast<double>(p[i - 1].*s.count)), q, s.colour, 2,
                         cv::LINE_AA);
        }
        const cv::Point b = at(p[i].strength, static_cast<double>(p[i].branches));
        char label[32];
        std::snprintf(label, sizeof label, "%g", p[i].strength);
        cv::putText(m, label, {b.x - 10, h - bottom + 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45, ink, 1, cv::LINE_AA);
    }
    const int x = at(p[plateau].strength, 1).x;
    cv::line(m, {x, top}, {x, h - bottom}, cv::Scalar(40, 40, 210), 2, cv::LINE_AA);
    cv::putText(m, "plateau", {x > w - right - 80 ? x - 72 : x + 5, top + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(40, 40, 210), 1, cv::LINE_AA);
    cv::putText(m, title, {10, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.55, ink, 1, cv::LINE_AA);
    cv::putText(m, axis, {left, h - 15}, cv::FONT_HERSHEY_SIMPLEX, 0.5, ink, 1, cv::LINE_AA);
    for (std::size_t n = 0; n < 3; ++n)
        cv::putText(m, series[n].name, {w - 140, top + 20 + 20 * static_cast<int>(n)}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                    series[n].colour, 1, cv::LINE_AA);
    io::write_png(path, m);
}

} // namespace

void add_denoise_study_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "denoise-study", "Sweep a denoising filter's strength and plot the contour tree's size against it");
    auto a = std::make_shared<StudyArgs>();
    a->input.add_to(*sub, context);
    sub->add_option("--filter", a->filter, "Filter plugin (id or last part)")->default_val("gaussian");
    sub->add_option("--param", a->param, "The filter parameter to sweep")->default_val("sigma");
    sub->add_option("--from", a->from, "First strength (0 for the gaussian: the unfiltered volume)")->default_val(0.0);
    sub->add_option("--to", a->to, "Last strength")->default_val(4.0);
    sub->add_option("--steps", a->steps, "Strengths from --from to --to")->check(CLI::Range(2, 100))->default_val(9);
    sub->add_option("--out", a->out, "Folder for study.csv and study.png")->required();
    a->filter_flags.add(*sub, context.registry, ARBOR_KIND_FILTER, "Filter options");
    context.flag_names.add(a->filter_flags);
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
            throw std::invalid_argument(filter.id + " has no parameter '" + a->param + "'");
        pipeline::Document doc = pipeline::default_document();
        doc.auto_denoise = false; // the study's own strengths, strength 0 as it is
        a->input.apply(doc.input, catalog);
        p->set_document(doc);
        const auto imported = p.run<pipeline::Stage::Import>();
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
            std::printf("  %s = %-8g %10zu branches %10zu minima %10zu maxima  %.2f s%s\n", a->param.c_str(),
                        point.strength, point.branches, point.minima, point.maxima, point.seconds,
                        tree->from_cache ? " (tree from the cache)" : "");
            std::fflush(stdout);
            points.push_back(point);
        }
        const std::size_t plateau = plateau_of(points);
        const std::filesystem::path dir(a->out);
        AtomicFile csv(dir / "study.csv");
        csv.write(a->param + ",branches,minima,maxima,seconds,plateau\n");
        for (std::size_t i = 0; i < points.size(); ++i)
            csv.write(std::to_string(points[i].strength) + "," + std::to_string(points[i].branches) + "," +
                      std::to_string(points[i].minima) + "," + std::to_string(points[i].maxima) + "," +
                      std::to_string(points[i].seconds) + "," +
                      (i == plateau ? "1" : "0") + "\n");
        csv.commit();
        plot(dir / "study.png", points, plateau, "Contour tree size of " + imported->source + " under " + filter.id,
             a->param + " (" + (d->unit && *d->unit ? d->unit : "") + ")");
        std::printf("%s: suggested %s = %g (%zu branches, from %zu unfiltered) -> %s\n", imported->source.c_str(),
                    a->param.c_str(), points[plateau].strength, points[plateau].branches, points.front().branches,
                    (dir / "study.png").string().c_str());
        return 0;
    });
}

} // namespace arbor::cli
