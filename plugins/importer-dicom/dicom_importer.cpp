// dicom_importer.cpp - org.arbor.importer.dicom: one series of a DICOM folder
// (or one DICOM file) as a volume.  read_header scans and plans (headers
// only); read_voxels decodes.  Every correction the library makes is logged
// as a warning, so the user sees what was done to their data.
#include <arbor/sdk/importer.hpp>

#include "dicom/folder_scan.hpp"
#include "dicom/image_record.hpp"
#include "dicom/series_volume.hpp"

#include <strings.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

namespace {

namespace fs = std::filesystem;
using namespace arbor;

const arbor_plugin_descriptor kDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.importer.dicom",
    ARBOR_KIND_IMPORTER,
    "DICOM series",
    "1.0.0",
    "Arbor",
    "Reads a DICOM series from a folder (scanned recursively) or a single DICOM file: slices "
    "ordered along the slice normal, LPS geometry, rescale to HU, MONOCHROME1, pixel padding, "
    "enhanced multi-frame, and JPEG, JPEG-LS, RLE (DCMTK) and JPEG 2000 (OpenJPEG) compressed images.",
    "",
};

std::vector<sdk::ParamSpec> dicom_params()
{
    std::vector<sdk::ParamSpec> p;
    p.push_back(sdk::ParamSpec::text("series", "Series", "")
                    .hint("Series Instance UID, or the series' number in `arbor dicom ls`; may be "
                          "left empty when the folder holds one series with images"));
    p.push_back(sdk::ParamSpec::choice("irregular-slices", "Irregular slice gaps", {"resample", "refuse"}, 0,
                                       {"resample onto even spacing", "refuse the series"})
                    .group("Series problems")
                    .hint("What to do when gaps between slices differ"));
    p.push_back(sdk::ParamSpec::choice("missing-slices", "Missing slices", {"refuse", "interpolate"}, 0,
                                       {"refuse the series", "fill by linear interpolation"})
                    .group("Series problems")
                    .hint("What to do when gaps skip whole slices"));
    p.push_back(sdk::ParamSpec::choice("gantry-tilt", "Gantry tilt", {"correct", "refuse"}, 0,
                                       {"shift slices onto an orthogonal grid", "refuse the series"})
                    .group("Series problems")
                    .hint("What to do when slices are sheared by a tilted CT gantry"));
    return p;
}

bool folder_holds_dicom(const fs::path &folder)
{
    // Cheap: look at no more than 64 entries near the top.
    std::error_code ec;
    int seen = 0;
    for (fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end && seen < 64; it.increment(ec)) {
        if (it.depth() > 2) {
            it.pop(ec);
            if (ec || it == end)
                break;
        }
        if (it->is_regular_file(ec)) {
            ++seen;
            if (dicom::looks_like_dicom(it->path()))
                return true;
        }
    }
    return false;
}

// Library messages start with the file they concern; for a single-file input
// the host names it already.
[[noreturn]] void fail_for(const std::string &path, const std::string &message)
{
    const std::string prefix = path + ": ";
    sdk::fail(ARBOR_ERROR_FORMAT, message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message);
}

class DicomImporter final : public sdk::Importer {
public:
    explicit DicomImporter(const arbor_host *host)
        : Importer(kDescriptor, host, ".dcm;.dicom;.ima;/", dicom_params())
    {
    }

    int32_t probe(const std::string &path, const uint8_t *head, uint64_t head_size) override
    {
        std::error_code ec;
        if (fs::is_directory(path, ec))
            return folder_holds_dicom(path) ? 90 : 0;
        if (head_size >= 132 && std::equal(head + 128, head + 132, "DICM"))
            return 100;
        if (dicom::looks_like_dicom(head, static_cast<std::size_t>(head_size)))
            return 30;
        // A .dcm file nothing else reads: let DCMTK say what is wrong with it.
        for (const char *suffix : {".dcm", ".dicom", ".ima"})
            if (path.size() > std::strlen(suffix) &&
                strcasecmp(path.c_str() + path.size() - std::strlen(suffix), suffix) == 0)
                return 5;
        return 0;
    }

    void read_header(const std::string &path, const sdk::Task &task, arbor_volume &out) override
    {
        plan_.reset();
        scan_.reset();
        dicom::StackPolicy policy;
        policy.resample_irregular = params().choice("irregular-slices") == "resample";
        policy.fill_missing = params().choice("missing-slices") == "interpolate";
        policy.correct_tilt = params().choice("gantry-tilt") == "correct";
        try {
            scan_ = dicom::scan_dicom(path, [&](double f) { task.progress(f, "scanning DICOM files"); });
            std::error_code ec;
            const bool folder = fs::is_directory(path, ec);
            if (folder)
                report_skipped();
            const dicom::Series &series = dicom::select_series(*scan_, params().text("series"));
            plan_.emplace(series, policy);
            // Read back for a session, the parameter names the series itself
            // (its UID), not its row in this folder's listing.
            if (!series.uid.empty()) {
                arbor_param_value uid{};
                uid.struct_size = sizeof uid;
                uid.type = ARBOR_PARAM_STRING;
                uid.components = 1;
                uid.text = series.uid.c_str();
                params().set("series", uid);
            }
            if (!folder)
                report_siblings(path, series);
        } catch (const sdk::Error &) {
            throw;
        } catch (const std::runtime_error &e) {
            fail_for(path, e.what());
        }
        for (const std::string &note : plan_->notes())
            log(ARBOR_LOG_WARNING, note);
        const dicom::VolumeLayout &v = plan_->layout();
        out.voxel_type = v.type;
        for (int a = 0; a < 3; ++a) {
            out.dims[a] = v.dims[static_cast<std::size_t>(a)];
            out.spacing[a] = v.spacing[static_cast<std::size_t>(a)];
            out.origin[a] = v.origin[static_cast<std::size_t>(a)];
        }
        for (int i = 0; i < 9; ++i)
            out.direction[i] = v.direction[static_cast<std::size_t>(i)];
        out.value_scale = v.value_scale;
        out.value_offset = v.value_offset;
        out.value_unit = v.unit.c_str();
        planned_path_ = path;
    }

    void read_voxels(const std::string &path, const sdk::Task &task, arbor_volume &volume) override
    {
        if (!plan_ || planned_path_ != path) {
            arbor_volume header{};
            header.struct_size = sizeof header;
            read_header(path, task, header);
        }
        const dicom::VolumeLayout &v = plan_->layout();
        if (volume.voxel_type != v.type || volume.dims[0] != v.dims[0] || volume.dims[1] != v.dims[1] ||
            volume.dims[2] != v.dims[2])
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the volume does not match the header read for " + path);
        std::vector<std::string> notes;
        try {
            notes = plan_->read(volume.voxels, [&](double f) { task.progress(f, "decoding DICOM slices"); });
        } catch (const sdk::Error &) {
            throw;
        } catch (const std::runtime_error &e) {
            fail_for(path, e.what());
        }
        for (const std::string &note : notes)
            log(ARBOR_LOG_WARNING, note);
    }

private:
    void report_skipped() const
    {
        const auto &bad = scan_->unreadable;
        if (bad.empty())
            return;
        std::string text = std::to_string(bad.size()) + " DICOM file(s) could not be read and were left out:";
        for (std::size_t i = 0; i < bad.size() && i < 5; ++i)
            text += "\n  " + bad[i].reason;
        if (bad.size() > 5)
            text += "\n  ... (`arbor dicom ls` lists them all)";
        log(ARBOR_LOG_WARNING, text);
    }

    // One file of a multi-file series reads as that slice alone: say so.
    void report_siblings(const std::string &path, const dicom::Series &series) const
    {
        if (series.uid.empty() || series.frame_count() > 1)
            return;
        const std::size_t beside = dicom::series_images_beside(path, series.uid);
        if (beside > 1)
            log(ARBOR_LOG_WARNING, fs::path(path).filename().string() + " is 1 of " + std::to_string(beside) +
                                       " images of its series in this folder; only it is read (give the "
                                       "folder to read the whole series)");
    }

    std::optional<dicom::FolderScan> scan_;
    std::optional<dicom::SeriesVolume> plan_;
    std::string planned_path_;
};

sdk::Instance *create_dicom_importer(const arbor_host *host)
{
    return new DicomImporter(host);
}

const sdk::PluginClass kImporters[] = {{&kDescriptor, &create_dicom_importer}};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kImporters)
