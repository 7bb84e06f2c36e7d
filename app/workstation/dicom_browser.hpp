// dicom_browser.hpp - the DICOM browser: a folder scanned in the background
// (progress, Cancel), its patients, studies and series in a table with what
// reading each as a volume would give and would correct (or why it cannot),
// and Open per series.  A folder dropped on the window or opened from the
// File menu comes here; one holding a single readable series opens at once,
// as Slicer's DICOM module loads a lone series.
#pragma once

#include "dicom/series_summary.hpp"

#include <atomic>
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <vector>

namespace arbor::workstation {

class Workstation;

class DicomBrowser {
public:
    ~DicomBrowser();
    // Starts scanning `folder` and shows the browser; `open_single`: open
    // the series at once when it is the only readable one.
    void scan(const std::filesystem::path &folder, bool open_single);
    bool &shown() { return shown_; }
    bool scanning() const { return pending_.valid(); }
    void draw(Workstation &workstation);

private:
    struct Scan {
        dicom::FolderScan folder;
        std::vector<dicom::SeriesSummary> series;
    };
    void cancel();

    bool shown_ = false;
    char path_[1024] = "";
    bool open_single_ = false;
    std::future<std::shared_ptr<Scan>> pending_;
    std::shared_ptr<std::atomic<double>> progress_;
    std::shared_ptr<std::atomic<bool>> cancelled_;
    std::shared_ptr<Scan> result_;
    std::string error_;
};

} // namespace arbor::workstation
