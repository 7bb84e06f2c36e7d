// dicom_browser.hpp - the DICOM browser: a folder scanned in the background
// (progress, Cancel), its patients, studies and series in a table with what
// reading each as a volume would give and would correct (or why it cannot),
// and Open per series.  A folder dropped on the window or opened from the
// File menu comes here; one holding a single readable series opens at once,
// as Slicer's DICOM module loads a lone series.  Its PACS tab searches and
// opens series from an archive (pacs_browser.hpp).
#pragma once

#include "pacs_browser.hpp"

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
    // Shows the browser on its PACS tab.
    void show_pacs();
    PacsBrowser &pacs() { return pacs_; }
    const PacsBrowser &pacs() const { return pacs_; }

private:
    struct Scan {
        dicom::FolderScan folder;
        std::vector<dicom::SeriesSummary> series;
    };
    void cancel();
    void draw_folder(Workstation &workstation);

    bool shown_ = false;
    int select_pacs_ = -1; // the tab to select next frame: 0 folder, 1 PACS
    PacsBrowser pacs_;
    char path_[1024] = "";
    bool open_single_ = false;
    std::future<std::shared_ptr<Scan>> pending_;
    std::shared_ptr<std::atomic<double>> progress_;
    std::shared_ptr<std::atomic<bool>> cancelled_;
    std::shared_ptr<Scan> result_;
    std::string error_;
};

} // namespace arbor::workstation
