// series_retrieval.hpp - one series retrieved from an archive into a
// folder, so that what is there can always be told complete or not:
//   FOLDER/<SOP Instance UID>.dcm     one file per instance, renamed into
//                                     place only once whole and readable
//   FOLDER/.incoming/                 instances being received
//   FOLDER/.arbor-retrieve.json       the manifest: node, series, state
//                                     ("in progress", "complete",
//                                     "incomplete"), expected and received
// Hidden names are skipped by folder scans, so an interrupted retrieve
// leaves nothing half-written that reads as part of the series.
#pragma once

#include "dicom/pacs_client.hpp"

#include <filesystem>
#include <functional>
#include <mutex>
#include <set>
#include <string>

namespace arbor::dicom {

struct RetrievalProgress {
    int received = 0;
    int expected = -1; // -1: not known yet
};
// Called from the thread that received the instance.
using RetrievalCallback = std::function<void(const RetrievalProgress &)>;

struct Retrieval {
    std::filesystem::path folder;
    int received = 0, expected = -1;
};

// Retrieves every instance of the series into `folder` (created; it must be
// new, empty, or hold an earlier retrieve of the same series).  Throws
// PacsError when the retrieve fails or ends incomplete, after marking the
// folder incomplete and saying in the message how many images arrived and
// where they are.
Retrieval retrieve_series(PacsClient &client, const PacsNode &node, const std::string &series_uid,
                          RetrieveMethod method, const std::filesystem::path &folder,
                          const RetrievalCallback &progress);

// The folder's manifest says a complete retrieve of this series.
bool retrieval_complete(const std::filesystem::path &folder, const std::string &series_uid);

// The folder that receives instances: writes each staged file's SOP
// Instance UID name, counts, reports.  Thread-safe (C-MOVE stores arrive on
// the storage SCP's thread).
class RetrievalFolder final : public InstanceSink {
public:
    RetrievalFolder(std::filesystem::path folder, RetrievalCallback progress);
    std::filesystem::path staging_file() override;
    bool commit(const std::filesystem::path &staged, std::string &problem) override;
    void expect(int count) override;
    int received() const;
    int expected() const;
    std::string first_problem() const;

private:
    const std::filesystem::path folder_;
    const RetrievalCallback progress_;
    mutable std::mutex mutex_;
    std::set<std::string> received_;
    int expected_ = -1;
    uint64_t next_ = 0;
    std::string first_problem_;
};

} // namespace arbor::dicom
