// pacs_client.hpp - what Arbor asks of an archive, whatever it speaks:
// verify the connection, search studies and series, retrieve one series.
// DIMSE (C-ECHO, C-FIND, C-GET, C-MOVE on DCMTK's DcmSCU) and DICOMweb
// (QIDO-RS, WADO-RS on libcurl) implement it; connect() picks by the node.
//
// Every call is bounded by the timeout and polls the stop token; failures
// are PacsError with what went wrong in words a user can act on.
#pragma once

#include "dicom/pacs_node.hpp"

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

namespace arbor::dicom {

class PacsError : public std::runtime_error {
public:
    enum class Kind {
        Unreachable,  // unknown host, connection refused
        Rejected,     // association rejected (AE title), HTTP 401/403
        Timeout,
        Failed,       // the archive answered with a failure status
        Cancelled,
    };
    PacsError(Kind kind, const std::string &message) : std::runtime_error(message), kind_(kind) {}
    Kind kind() const { return kind_; }

private:
    Kind kind_;
};

// Empty fields match anything.  study_date: YYYYMMDD or a range
// YYYYMMDD-YYYYMMDD (either end open); patient: a name or ID, * and ? wildcards.
struct PacsQuery {
    std::string patient, study_date, modality, accession;
    std::string study_uid; // series searches within one study
};

struct StudyRow {
    std::string patient_name, patient_id, study_uid, study_date, study_description, accession;
    std::string modalities; // "CT\PT"
    int series_count = -1, image_count = -1; // -1: not reported
};

struct SeriesRow {
    std::string patient_name, patient_id, study_uid, study_date, study_description;
    std::string series_uid, series_number, modality, description;
    int image_count = -1;
};

enum class RetrieveMethod { Get, Move };

// Where retrieved instances go (series_retrieval.hpp: a folder).  A client
// writes each instance to a staging file, then hands it in.
class InstanceSink {
public:
    virtual ~InstanceSink() = default;
    // A fresh file name for one incoming instance (hidden from folder scans).
    virtual std::filesystem::path staging_file() = 0;
    // Takes a written staging file in (it must be DICOM; it is named by its
    // SOP Instance UID).  False, with the reason, when it cannot be kept.
    virtual bool commit(const std::filesystem::path &staged, std::string &problem) = 0;
    // The number of instances the archive said it will send (-1: unknown).
    virtual void expect(int count) = 0;
};

struct PacsOptions {
    int timeout_s = 30;
    std::stop_token stop;
};

class PacsClient {
public:
    virtual ~PacsClient() = default;
    // Round-trip time in milliseconds.
    virtual double echo() = 0;
    virtual std::vector<StudyRow> find_studies(const PacsQuery &query) = 0;
    // With query.study_uid empty: the series of every study that matches.
    virtual std::vector<SeriesRow> find_series(const PacsQuery &query) = 0;
    // Every instance of the series into `sink`.  Returns normally when the
    // archive reported the retrieve complete; throws PacsError otherwise
    // (what arrived is in the sink).  DICOMweb ignores `method`.
    virtual void retrieve(const std::string &series_uid, RetrieveMethod method, InstanceSink &sink) = 0;
};

// The studies a series search looks in: the one query.study_uid names, or
// every study `search()` finds.  Series are searched study by study, as
// strictly hierarchical archives need.
template <class Search> std::vector<StudyRow> studies_to_search(const PacsQuery &query, Search search)
{
    if (!query.study_uid.empty()) {
        StudyRow only;
        only.study_uid = query.study_uid;
        return {only};
    }
    return search();
}

std::unique_ptr<PacsClient> connect(const PacsNode &node, const PacsOptions &options);
std::unique_ptr<PacsClient> connect_dimse(const PacsNode &node, const PacsOptions &options);
std::unique_ptr<PacsClient> connect_dicomweb(const PacsNode &node, const PacsOptions &options);

} // namespace arbor::dicom
