#include "folder_scan.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>

namespace arbor::dicom {

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> files_under(const fs::path &root)
{
    std::vector<fs::path> files;
    std::error_code ec;
    if (fs::is_regular_file(root, ec)) {
        files.push_back(root);
        return files;
    }
    fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec);
    if (ec)
        throw std::runtime_error(root.string() + ": cannot list the folder (" + ec.message() + ")");
    for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (ec)
            break;
        // Hidden names are not scans: .DS_Store, editors' files, and the
        // manifest and half-received instances of a PACS retrieve.
        if (it->path().filename().string().rfind('.', 0) == 0) {
            if (it->is_directory(ec))
                it.disable_recursion_pending();
            continue;
        }
        if (it->is_regular_file(ec))
            files.push_back(it->path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

double series_number(const std::string &s)
{
    char *end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    return end == s.c_str() ? 1e300 : v;
}

std::string row_text(const Series &s, std::size_t row)
{
    const ImageRecord &r = s.first();
    return "  " + std::to_string(row) + ": " + (s.uid.empty() ? "(no Series Instance UID)" : s.uid) + " " +
           r.modality + " \"" + r.series_description + "\", " + std::to_string(s.frame_count()) +
           " frame(s)";
}

} // namespace

std::size_t Series::frame_count() const
{
    std::size_t n = 0;
    for (const ImageRecord &r : images)
        n += r.is_image() ? r.frames.size() : 0;
    return n;
}

// The series an image belongs to: its Series Instance UID, or without one,
// what images of one series share (a non-image object stays alone).
std::string series_key(const ImageRecord &r, const fs::path &file)
{
    if (!r.series_uid.empty())
        return r.series_uid;
    if (!r.is_image())
        return "file:" + file.string();
    std::string key = "no-uid|" + r.study_uid + "|" + r.series_number + "|" + r.frame_of_reference_uid + "|" +
                      std::to_string(r.rows) + "x" + std::to_string(r.columns) + "|" + std::to_string(r.bits_allocated) +
                      (r.is_signed ? "s" : "u") + std::to_string(r.samples_per_pixel) + "|";
    if (!r.frames.empty() && r.frames.front().geometry.orientation)
        for (const double c : *r.frames.front().geometry.orientation) {
            char buf[16];
            std::snprintf(buf, sizeof buf, "%.3f,", c); // a tilt of < 0.06 degrees is the same plane
            key += buf;
        }
    return key;
}

FolderScan scan_dicom(const fs::path &path, const ScanProgress &progress)
{
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw std::runtime_error(path.string() + ": no such file or folder");
    FolderScan scan;
    scan.root = path;
    const std::vector<fs::path> files = files_under(path);
    std::map<std::string, Series> by_uid;
    for (std::size_t i = 0; i < files.size(); ++i) {
        if (progress && (i % 16 == 0))
            progress(static_cast<double>(i) / static_cast<double>(files.size()));
        const fs::path &file = files[i];
        // A file named on its own is always handed to DCMTK, so that the
        // user hears why it is not DICOM.
        const bool named = files.size() == 1 && file == path;
        if (file.filename() == "DICOMDIR" || (!named && !looks_like_dicom(file))) {
            scan.not_dicom.push_back(file);
            continue;
        }
        try {
            ImageRecord r = read_image_record(file);
            const std::string key = series_key(r, file);
            Series &s = by_uid[key];
            s.uid = r.series_uid;
            if (key.rfind("no-uid|", 0) == 0)
                ++s.grouped;
            s.images.push_back(std::move(r));
        } catch (const std::runtime_error &e) {
            scan.unreadable.push_back({file, e.what()});
        }
    }
    for (auto &[key, s] : by_uid)
        scan.series.push_back(std::move(s));
    std::stable_sort(scan.series.begin(), scan.series.end(), [](const Series &a, const Series &b) {
        const ImageRecord &x = a.first(), &y = b.first();
        if (x.patient_id != y.patient_id)
            return x.patient_id < y.patient_id;
        if (x.study_date != y.study_date)
            return x.study_date < y.study_date;
        if (x.study_uid != y.study_uid)
            return x.study_uid < y.study_uid;
        if (series_number(x.series_number) != series_number(y.series_number))
            return series_number(x.series_number) < series_number(y.series_number);
        return a.uid < b.uid;
    });
    if (progress)
        progress(1.0);
    return scan;
}

std::size_t series_images_beside(const fs::path &file, const std::string &series_uid)
{
    std::set<std::string> instances;
    std::error_code ec;
    for (const fs::directory_entry &e : fs::directory_iterator(file.parent_path(), ec)) {
        if (!e.is_regular_file(ec) || !looks_like_dicom(e.path()))
            continue;
        try {
            const ImageRecord r = read_image_record(e.path());
            if (r.series_uid != series_uid || !r.is_image())
                continue;
            // Copies of one image (other encodings, re-sent instances) share
            // a position; without one, the instance UID tells them apart.
            const auto &p = r.frames.front().geometry.position;
            char key[96];
            if (p)
                std::snprintf(key, sizeof key, "%.2f %.2f %.2f", (*p)[0], (*p)[1], (*p)[2]);
            instances.insert(p ? std::string(key) : r.sop_instance_uid.empty() ? e.path().string() : r.sop_instance_uid);
        } catch (const std::runtime_error &) {
            // Unreadable neighbours do not matter here.
        }
    }
    return instances.size();
}

const Series &select_series(const FolderScan &scan, const std::string &selector)
{
    std::string choices;
    for (std::size_t i = 0; i < scan.series.size(); ++i)
        if (scan.series[i].frame_count() > 0)
            choices += "\n" + row_text(scan.series[i], i + 1);
    const std::string where = scan.root.string();
    if (!selector.empty()) {
        for (const Series &s : scan.series)
            if (s.uid == selector)
                return s;
        const bool digits = selector.find_first_not_of("0123456789") == std::string::npos;
        if (digits) {
            const unsigned long row = std::strtoul(selector.c_str(), nullptr, 10);
            if (row >= 1 && row <= scan.series.size())
                return scan.series[row - 1];
        }
        throw std::runtime_error(where + ": no series '" + selector + "'; the series with images are:" +
                                 (choices.empty() ? " none" : choices));
    }
    std::vector<const Series *> with_images;
    for (const Series &s : scan.series)
        if (s.frame_count() > 0)
            with_images.push_back(&s);
    if (with_images.size() == 1)
        return *with_images.front();
    if (with_images.empty()) {
        if (scan.series.empty() && scan.unreadable.size() == 1)
            throw std::runtime_error(scan.unreadable.front().reason);
        std::string why;
        if (!scan.series.empty()) {
            const ImageRecord &r = scan.series.front().first();
            why += "; " + std::to_string(scan.series.size()) + " DICOM series without pixel data, first " +
                   (!r.modality.empty()         ? r.modality
                    : !r.sop_class_uid.empty() ? "SOP class " + r.sop_class_uid
                                               : std::string("an object without Modality or SOP Class")) + " in " +
                   r.path.filename().string();
        }
        if (!scan.unreadable.empty())
            why += "; " + std::to_string(scan.unreadable.size()) + " file(s) could not be read, first " +
                   scan.unreadable.front().reason;
        if (scan.series.empty() && scan.unreadable.empty())
            why += " (" + std::to_string(scan.not_dicom.size()) + " file(s), none of them DICOM)";
        throw std::runtime_error(where + ": no DICOM images found" + why);
    }
    throw std::runtime_error(where + " holds " + std::to_string(with_images.size()) +
                             " series with images; choose one with --series UID or its number "
                             "(see `arbor dicom ls`):" + choices);
}

} // namespace arbor::dicom
