#include "pacs_fetch.hpp"

#include "dicom/pacs_input.hpp"

#include <stdexcept>

namespace arbor::cli {

std::filesystem::path fetch_pacs_input(const std::string &uri, ProgressSink &progress, std::stop_token stop)
{
    if (!dicom::is_pacs_uri(uri))
        throw std::invalid_argument(uri + ": the only inputs by URI are pacs://NODE/SERIES_UID");
    const auto report = [&progress](const dicom::RetrievalProgress &p) {
        const std::string of = p.expected >= 0 ? " of " + std::to_string(p.expected) : "";
        progress.report("retrieving from PACS: image " + std::to_string(p.received) + of,
                        p.expected > 0 ? double(p.received) / p.expected : 0.0);
    };
    try {
        return dicom::fetch_pacs_series(uri, {30, stop}, report);
    } catch (const dicom::PacsError &e) {
        if (e.kind() == dicom::PacsError::Kind::Cancelled)
            throw; // the job's stop token tells it was cancelled
        throw std::runtime_error(uri + ": " + e.what());
    }
}

} // namespace arbor::cli
