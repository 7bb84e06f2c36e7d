// pacs_browser.hpp - the DICOM browser's PACS tab: choose a node (from
// pacs-nodes.json, or typed: AET@host:port or a DICOMweb URL), search its
// series by patient, study date, modality and accession in the background,
// and open one.  Opening sets the input to pacs://NODE/SERIES_UID: the
// import job retrieves it into the PACS cache, with progress per image and
// Cancel in the jobs panel, and a saved session names the archive, not the
// cache.
#pragma once

#include "dicom/pacs_client.hpp"

#include <future>
#include <stop_token>
#include <string>
#include <utility>
#include <vector>

namespace arbor::workstation {

class Workstation;

class PacsBrowser {
public:
    ~PacsBrowser();
    // Starts a series search (the previous one is cancelled).
    void search(const std::string &node, const dicom::PacsQuery &query);
    bool searching() const { return pending_.valid(); }
    // Takes a finished search's rows or error; called every frame.
    void poll();
    const std::vector<dicom::SeriesRow> &rows() const { return rows_; }
    const std::string &error() const { return error_; }
    // Opens the row (0-based) of the last search.  Throws std::out_of_range.
    void open(std::size_t row, Workstation &workstation);
    // The tab's contents.
    void draw(Workstation &workstation);
    // A series was opened since the last call (the browser then closes).
    bool take_opened() { return std::exchange(opened_, false); }

private:
    void cancel();
    void load_nodes();

    std::vector<dicom::PacsNode> nodes_;
    bool nodes_loaded_ = false;
    std::string nodes_problem_;
    char node_[512] = "";
    char patient_[128] = "", date_[32] = "", modality_[16] = "", accession_[64] = "";
    std::stop_source stop_;
    std::future<std::vector<dicom::SeriesRow>> pending_;
    std::string searched_node_; // the node of rows_
    std::vector<dicom::SeriesRow> rows_;
    std::string error_;
    bool opened_ = false;
};

} // namespace arbor::workstation
