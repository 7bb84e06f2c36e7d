// `arbor info <volume>`: what a volume is (dims, type, geometry, value range
// in stored and physical units, histogram summary), as text or JSON.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "input_flags.hpp"

#include "core/volume_header.hpp"
#include "core/volume_statistics.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

namespace arbor::cli {

namespace {

std::string fixed(double x, int digits = 4)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits + 2, x);
    return buf;
}

// One line of block characters, one per histogram bin, log-scaled so that
// small populations (a tumour next to the background peak) stay visible.
std::string sparkline(const std::vector<int64_t> &h, std::size_t width)
{
    static const char *bars[] = {" ", "▁", "▂", "▃", "▄", "▅", "▆", "▇", "█"};
    std::vector<double> merged(width, 0.0);
    for (std::size_t b = 0; b < h.size(); ++b)
        merged[b * width / h.size()] += static_cast<double>(h[b]);
    double top = 0;
    for (double v : merged)
        top = std::max(top, std::log1p(v));
    std::string s;
    for (double v : merged)
        s += bars[top > 0 ? static_cast<int>(std::lround(8.0 * std::log1p(v) / top)) : 0];
    return s;
}

nlohmann::json to_json(const pipeline::ImportResult &in, const VolumeStatistics &st)
{
    const Volume &v = *in.volume;
    const Geometry &g = v.geometry();
    const ValueMapping &m = v.mapping();
    nlohmann::json j;
    j["source"] = in.source;
    if (!in.importer.empty())
        j["importer"] = {{"id", in.importer.id}, {"version", in.importer.version}};
    j["dims"] = g.dims;
    j["voxel_count"] = v.voxel_count();
    j["voxel_type"] = arbor_voxel_type_name(v.type());
    j["bytes"] = v.byte_size();
    j["spacing_mm"] = g.spacing;
    j["origin_lps_mm"] = g.origin;
    j["direction"] = g.direction;
    j["extent_mm"] = {g.spacing[0] * (g.dims[0] - 1), g.spacing[1] * (g.dims[1] - 1),
                      g.spacing[2] * (g.dims[2] - 1)};
    j["value_mapping"] = {{"scale", m.scale}, {"offset", m.offset}, {"unit", m.unit}};
    if (const auto &hu = in.hounsfield_inferred)
        j["value_mapping"]["unit_inferred"] = {{"air_peak", hu->air_peak},
                                               {"air_fraction", hu->air_fraction},
                                               {"tissue_peak", hu->tissue_peak},
                                               {"tissue_fraction", hu->tissue_fraction}};
    j["stored"] = {{"min", st.min}, {"max", st.max}, {"mean", st.mean}, {"stddev", st.stddev}};
    j["physical"] = {{"min", std::min(m.physical(st.min), m.physical(st.max))},
                     {"max", std::max(m.physical(st.min), m.physical(st.max))},
                     {"mean", m.physical(st.mean)},
                     {"unit", m.unit}};
    j["non_finite"] = {{"nan", st.nan_count}, {"infinite", st.infinite_count}};
    j["histogram"] = {{"bins", st.histogram.size()},
                      {"min", st.min},
                      {"bin_width", st.bin_width},
                      {"counts", st.histogram},
                      {"p01", st.quantile(0.01)},
                      {"p50", st.quantile(0.50)},
                      {"p99", st.quantile(0.99)},
                      {"mode", st.mode()}};
    return j;
}

void print_text(const pipeline::ImportResult &in, const VolumeStatistics &st)
{
    const Volume &v = *in.volume;
    const Geometry &g = v.geometry();
    const ValueMapping &m = v.mapping();
    std::printf("Source      %s\n", in.source.c_str());
    if (!in.importer.empty())
        std::printf("Importer    %s %s\n", in.importer.id.c_str(), in.importer.version.c_str());
    std::printf("Dimensions  %lld x %lld x %lld (%lld voxels)\n", static_cast<long long>(g.dims[0]),
                static_cast<long long>(g.dims[1]), static_cast<long long>(g.dims[2]),
                static_cast<long long>(v.voxel_count()));
    std::printf("Voxel type  %s, %s in memory\n", arbor_voxel_type_name(v.type()),
                format_bytes(v.byte_size()).c_str());
    std::printf("Spacing     %s x %s x %s mm\n", fixed(g.spacing[0]).c_str(),
                fixed(g.spacing[1]).c_str(), fixed(g.spacing[2]).c_str());
    std::printf("Origin      (%s, %s, %s) mm, LPS\n", fixed(g.origin[0]).c_str(),
                fixed(g.origin[1]).c_str(), fixed(g.origin[2]).c_str());
    const auto &d = g.direction;
    std::printf("Direction   [%s %s %s; %s %s %s; %s %s %s]\n", fixed(d[0], 3).c_str(),
                fixed(d[1], 3).c_str(), fixed(d[2], 3).c_str(), fixed(d[3], 3).c_str(),
                fixed(d[4], 3).c_str(), fixed(d[5], 3).c_str(), fixed(d[6], 3).c_str(),
                fixed(d[7], 3).c_str(), fixed(d[8], 3).c_str());
    if (st.finite_count == 0) {
        std::printf("Values      no finite values\n");
    } else {
        std::printf("Stored      %s .. %s, mean %s, sd %s\n", fixed(st.min).c_str(),
                    fixed(st.max).c_str(), fixed(st.mean).c_str(), fixed(st.stddev).c_str());
        const double lo = std::min(m.physical(st.min), m.physical(st.max));
        const double hi = std::max(m.physical(st.min), m.physical(st.max));
        std::printf("Physical    %s .. %s %s(stored x %s + %s)\n", fixed(lo).c_str(),
                    fixed(hi).c_str(), m.unit.empty() ? "" : (m.unit + " ").c_str(),
                    fixed(m.scale).c_str(), fixed(m.offset).c_str());
        if (const auto &hu = in.hounsfield_inferred)
            std::printf("            HU read from the values, the file names no unit: %s\n",
                        hu->describe().c_str());
        std::printf("Histogram   %s\n", sparkline(st.histogram, 48).c_str());
        std::printf("            p1 %s, median %s, p99 %s, mode bin %s (stored)\n",
                    fixed(st.quantile(0.01)).c_str(), fixed(st.quantile(0.5)).c_str(),
                    fixed(st.quantile(0.99)).c_str(), fixed(st.mode()).c_str());
    }
    if (st.nan_count + st.infinite_count > 0)
        std::printf("Non-finite  %lld NaN, %lld infinite (first at voxel %lld)\n",
                    static_cast<long long>(st.nan_count), static_cast<long long>(st.infinite_count),
                    static_cast<long long>(st.first_non_finite));
}

} // namespace

void add_info_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "info", "Describe a volume: dims, type, geometry, value range, histogram");
    auto input = std::make_shared<InputFlags>();
    auto json = std::make_shared<bool>(false);
    input->add_to(*sub, context);
    sub->add_flag("--json", *json, "Print JSON instead of text");
    context.add_command(sub, [input, json, &context]() {
        CommandPipeline p(context, false);
        pipeline::Document d = pipeline::default_document();
        input->apply(d.input, p->catalog());
        p->set_document(d);
        const pipeline::ImportResult &in = *p.run<pipeline::Stage::Import>();
        const VolumeStatistics st = compute_statistics(*in.volume, 64);
        if (*json)
            std::cout << to_json(in, st).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
        else
            print_text(in, st);
        return 0;
    });
}

} // namespace arbor::cli
