#include "series_retrieval.hpp"

#include "dicom/dcmtk_setup.hpp"

#include "core/atomic_file.hpp"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <unistd.h>

namespace arbor::dicom {

namespace fs = std::filesystem;

namespace {

const char *const kManifest = ".arbor-retrieve.json";
const char *const kIncoming = ".incoming";

nlohmann::json read_manifest(const fs::path &folder)
{
    std::ifstream in(folder / kManifest);
    if (!in)
        return nullptr;
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception &) {
        return nullptr;
    }
}

void write_manifest(const fs::path &folder, const PacsNode &node, const std::string &series_uid,
                    const std::string &state, int received, int expected, const std::string &problem)
{
    nlohmann::ordered_json j = {{"format", "arbor-retrieve/1"},
                                {"node", node.describe()}, // never a secret
                                {"series_uid", series_uid},
                                {"state", state},
                                {"received", received},
                                {"expected", expected < 0 ? nlohmann::ordered_json(nullptr)
                                                          : nlohmann::ordered_json(expected)}};
    if (!problem.empty())
        j["problem"] = problem;
    AtomicFile out(folder / kManifest);
    out.write(j.dump(2) + "\n");
    out.commit();
}

// The folder may be new, empty, or an earlier retrieve of this series.
void claim_folder(const fs::path &folder, const std::string &series_uid)
{
    std::error_code ec;
    if (fs::exists(folder, ec)) {
        if (!fs::is_directory(folder, ec))
            throw std::runtime_error(folder.string() + " exists and is not a folder");
        const nlohmann::json m = read_manifest(folder);
        const bool same = m.is_object() && m.value("series_uid", "") == series_uid;
        if (!same && !fs::is_empty(folder, ec))
            throw std::runtime_error(folder.string() +
                                     " already holds other files: give a new or empty folder for the series");
    }
    fs::create_directories(folder / kIncoming, ec);
    if (ec)
        throw std::runtime_error("cannot create " + (folder / kIncoming).string() + ": " + ec.message());
}

} // namespace

RetrievalFolder::RetrievalFolder(fs::path folder, RetrievalCallback progress)
    : folder_(std::move(folder)), progress_(std::move(progress))
{
}

fs::path RetrievalFolder::staging_file()
{
    std::lock_guard lock(mutex_);
    return folder_ / kIncoming / ("instance-" + std::to_string(::getpid()) + "-" + std::to_string(next_++));
}

bool RetrievalFolder::commit(const fs::path &staged, std::string &problem)
{
    ensure_dcmtk_ready();
    std::error_code ec;
    DcmFileFormat file;
    OFString sop;
    if (file.loadFileUntilTag(staged.c_str(), EXS_Unknown, EGL_noChange, DCM_MaxReadLength, ERM_autoDetect,
                              DCM_PixelData)
            .bad() ||
        file.getDataset()->findAndGetOFString(DCM_SOPInstanceUID, sop).bad() || sop.empty()) {
        problem = "an instance that arrived is not readable DICOM or has no SOP Instance UID";
    } else if (sop.find_first_not_of("0123456789.") != OFString_npos || sop.length() > 64) {
        problem = "an instance has an invalid SOP Instance UID";
    } else {
        const fs::path target = folder_ / (std::string(sop.c_str()) + ".dcm");
        fs::rename(staged, target, ec);
        if (ec)
            problem = "cannot keep " + target.string() + ": " + ec.message();
    }
    RetrievalProgress now;
    {
        std::lock_guard lock(mutex_);
        if (!problem.empty()) {
            fs::remove(staged, ec);
            if (first_problem_.empty())
                first_problem_ = problem;
            return false;
        }
        received_.insert(sop.c_str());
        now = {static_cast<int>(received_.size()), expected_};
    }
    if (progress_)
        progress_(now);
    return true;
}

void RetrievalFolder::expect(int count)
{
    RetrievalProgress now;
    {
        std::lock_guard lock(mutex_);
        if (count == expected_)
            return;
        expected_ = count;
        now = {static_cast<int>(received_.size()), expected_};
    }
    if (progress_)
        progress_(now);
}

int RetrievalFolder::received() const
{
    std::lock_guard lock(mutex_);
    return static_cast<int>(received_.size());
}

int RetrievalFolder::expected() const
{
    std::lock_guard lock(mutex_);
    return expected_;
}

std::string RetrievalFolder::first_problem() const
{
    std::lock_guard lock(mutex_);
    return first_problem_;
}

Retrieval retrieve_series(PacsClient &client, const PacsNode &node, const std::string &series_uid,
                          RetrieveMethod method, const fs::path &folder, const RetrievalCallback &progress)
{
    claim_folder(folder, series_uid);
    write_manifest(folder, node, series_uid, "in progress", 0, -1, "");
    RetrievalFolder sink(folder, progress);
    std::string problem;
    PacsError::Kind kind = PacsError::Kind::Failed;
    try {
        client.retrieve(series_uid, method, sink);
    } catch (const PacsError &e) {
        problem = e.what();
        kind = e.kind();
    }
    std::error_code ec;
    fs::remove_all(folder / kIncoming, ec); // what did not arrive whole
    const int received = sink.received(), expected = sink.expected();
    if (problem.empty() && !sink.first_problem().empty())
        problem = sink.first_problem();
    if (problem.empty() && received == 0)
        problem = "the archive sent no images for series " + series_uid + " (is the Series Instance UID right?)";
    if (problem.empty() && expected >= 0 && received < expected)
        problem = "the archive sent " + std::to_string(received) + " of the " + std::to_string(expected) +
                  " images it announced";
    if (!problem.empty()) {
        write_manifest(folder, node, series_uid, "incomplete", received, expected, problem);
        std::string kept = received == 0 ? std::string(" Nothing arrived.")
                                         : " The " + std::to_string(received) + " image(s) that arrived are in " +
                                               folder.string() + ", marked incomplete.";
        throw PacsError(kind, problem + "." + kept);
    }
    write_manifest(folder, node, series_uid, "complete", received, expected < 0 ? received : expected, "");
    return {folder, received, expected < 0 ? received : expected};
}

bool retrieval_complete(const fs::path &folder, const std::string &series_uid)
{
    const nlohmann::json m = read_manifest(folder);
    return m.is_object() && m.value("series_uid", "") == series_uid && m.value("state", "") == "complete";
}

} // namespace arbor::dicom
