// pacs_input.hpp - `pacs://NODE/SERIES_UID` as the input of any command:
// NODE is a configured name, AET@host:port or a DICOMweb URL; the series is
// retrieved once into a cache folder (C-GET for DICOM nodes), then read like
// any DICOM folder.  A cached series counts only when its retrieve completed.
#pragma once

#include "dicom/series_retrieval.hpp"

#include <filesystem>
#include <string>

namespace arbor::dicom {

struct PacsUri {
    std::string node, series_uid;
};

bool is_pacs_uri(const std::string &text);
// Throws std::invalid_argument saying what the form is.
PacsUri parse_pacs_uri(const std::string &text);

// ARBOR_PACS_CACHE_DIR, else $XDG_CACHE_HOME/arbor/pacs, else ~/.cache/arbor/pacs.
std::filesystem::path default_pacs_cache_folder();

// The local folder holding the series; retrieves it unless the cache has it
// complete.  Concurrent fetches of one series wait for each other.
std::filesystem::path fetch_pacs_series(const std::string &uri, const PacsOptions &options,
                                        const RetrievalCallback &progress,
                                        const std::filesystem::path &cache_folder = default_pacs_cache_folder(),
                                        const std::filesystem::path &nodes_file = default_nodes_file());

} // namespace arbor::dicom
