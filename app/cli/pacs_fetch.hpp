// pacs_fetch.hpp - how the CLI and the workstation resolve inputs named by
// URI (PipelineOptions::fetch_input): pacs://NODE/SERIES_UID is retrieved
// into the PACS cache once (dicom/pacs_input.hpp), with progress per image.
#pragma once

#include "host/host_services.hpp"

#include <filesystem>
#include <stop_token>
#include <string>

namespace arbor::cli {

std::filesystem::path fetch_pacs_input(const std::string &uri, ProgressSink &progress, std::stop_token stop);

} // namespace arbor::cli
