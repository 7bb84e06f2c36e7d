// `arbor dicom ls <folder>`: the studies and series under a folder, with what
// reading each series as a volume would give (size, spacing) and what it
// would correct or refuse, plus the files that could not be read.
#include "commands.hpp"
#include "table_text.hpp"

#include "dicom/folder_scan.hpp"
#include "dicom/series_summary.hpp"
#include "dicom/value_text.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

namespace arbor::cli {

namespace {

using dicom::SeriesSummary;

std::string fixed(double v, int digits)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

// At most `width` bytes, never cutting a UTF-8 character in half.
nlohmann::json summary_json(const SeriesSummary &s, std::size_t row)
{
    const dicom::ImageRecord &r = s.series->first();
    nlohmann::json j = {{"row", row},
                        {"patient_name", r.patient_name},
                        {"patient_id", r.patient_id},
                        {"study_uid", r.study_uid},
                        {"study_date", r.study_date},
                        {"study_description", r.study_description},
                        {"series_uid", s.series->uid},
                        {"series_number", r.series_number},
                        {"modality", r.modality},
                        {"description", r.series_description},
                        {"files", s.series->images.size()},
                        {"frames", s.series->frame_count()},
                        {"notes", s.notes}};
    nlohmann::json syntaxes = nlohmann::json::array();
    for (const dicom::ImageRecord &i : s.series->images)
        if (std::find(syntaxes.begin(), syntaxes.end(), i.transfer_syntax_uid) == syntaxes.end())
            syntaxes.push_back(i.transfer_syntax_uid);
    j["transfer_syntaxes"] = syntaxes;
    if (s.layout) {
        j["dims"] = s.layout->dims;
        j["spacing_mm"] = s.layout->spacing;
        j["origin_lps_mm"] = s.layout->origin;
        j["direction"] = s.layout->direction;
        j["voxel_type"] = arbor_voxel_type_name(s.layout->type);
        j["unit"] = s.layout->unit;
        j["readable"] = true;
    } else {
        j["readable"] = false;
        j["problem"] = s.refusal;
    }
    return j;
}

void print_table(const dicom::FolderScan &scan, const std::vector<SeriesSummary> &rows)
{
    std::printf("%-3s %-22s %-22s %-6s %-4s %-24s %7s %-16s %s\n", "#", "PATIENT", "STUDY", "SERIES", "MOD",
                "DESCRIPTION", "SLICES", "SIZE", "SPACING (mm)");
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const SeriesSummary &s = rows[i];
        const dicom::ImageRecord &r = s.series->first();
        const std::string patient = r.patient_name.empty() ? r.patient_id : r.patient_name;
        const std::string study = dicom::display_date(r.study_date) + (r.study_description.empty() ? "" : " " + r.study_description);
        std::string size = "-", spacing = "-";
        if (s.layout) {
            const auto &l = *s.layout;
            size = std::to_string(l.dims[0]) + "x" + std::to_string(l.dims[1]) + "x" + std::to_string(l.dims[2]);
            spacing = fixed(l.spacing[0], 3) + " x " + fixed(l.spacing[1], 3) + " x " + fixed(l.spacing[2], 3);
        }
        std::printf("%-3zu %-22s %-22s %-6s %-4s %-24s %7zu %-16s %s\n", i + 1, clip(patient, 22).c_str(),
                    clip(study, 22).c_str(), clip(r.series_number, 6).c_str(), clip(r.modality, 4).c_str(),
                    clip(r.series_description, 24).c_str(), s.series->frame_count(), size.c_str(),
                    spacing.c_str());
        if (s.series->uid.empty())
            std::printf("    no Series Instance UID: %s\n", r.path.c_str());
        else
            std::printf("    series UID %s\n", s.series->uid.c_str());
        for (const std::string &n : s.notes)
            std::printf("    note: %s\n", n.c_str());
        if (!s.refusal.empty())
            std::printf("    cannot be read as a volume: %s\n", s.refusal.c_str());
    }
    if (rows.empty())
        std::printf("(no DICOM series)\n");
    if (!scan.unreadable.empty()) {
        std::printf("\n%zu DICOM file(s) could not be read:\n", scan.unreadable.size());
        for (const dicom::SkippedFile &f : scan.unreadable)
            std::printf("  %s\n", f.reason.c_str());
    }
    if (!scan.not_dicom.empty()) {
        std::printf("\n%zu file(s) are not DICOM:", scan.not_dicom.size());
        for (std::size_t i = 0; i < scan.not_dicom.size() && i < 8; ++i)
            std::printf(" %s", scan.not_dicom[i].filename().c_str());
        std::printf("%s\n", scan.not_dicom.size() > 8 ? " ..." : "");
    }
}

} // namespace

void add_dicom_command(CLI::App &app, Context &context)
{
    CLI::App *dicom = app.add_subcommand("dicom", "DICOM folders: list studies and series");
    dicom->require_subcommand(1);
    CLI::App *ls = dicom->add_subcommand("ls", "List the patients, studies and series under a folder");
    auto folder = std::make_shared<std::string>();
    auto json = std::make_shared<bool>(false);
    ls->add_option("folder", *folder, "Folder (scanned recursively) or DICOM file")->required();
    ls->add_flag("--json", *json, "Print JSON instead of a table");
    context.add_command(ls, [&context, folder, json]() {
        const dicom::FolderScan scan = dicom::scan_dicom(*folder, [&context](double f) {
            context.progress.report("scanning DICOM files", f);
        });
        context.progress.finish();
        std::vector<SeriesSummary> rows;
        for (const dicom::Series &s : scan.series)
            rows.push_back(dicom::summarise_series(s));
        if (*json) {
            nlohmann::json j = {{"folder", scan.root.string()}, {"series", nlohmann::json::array()}};
            for (std::size_t i = 0; i < rows.size(); ++i)
                j["series"].push_back(summary_json(rows[i], i + 1));
            j["unreadable"] = nlohmann::json::array();
            for (const dicom::SkippedFile &f : scan.unreadable)
                j["unreadable"].push_back({{"path", f.path.string()}, {"reason", f.reason}});
            j["not_dicom"] = nlohmann::json::array();
            for (const auto &p : scan.not_dicom)
                j["not_dicom"].push_back(p.string());
            // File names need not be UTF-8: replace what JSON cannot hold.
            std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
        } else {
            print_table(scan, rows);
        }
        return 0;
    });
}

} // namespace arbor::cli
