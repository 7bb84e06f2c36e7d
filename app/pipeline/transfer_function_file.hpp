// transfer_function_file.hpp - our versioned file format for per-branch
// transfer functions, "arbor-transfer-functions/1": for every kept branch
// its value domain, control points (the editable form) and the baked RGBA
// lookup table (what renderers use), plus everything needed to reproduce
// it: the generator and depictor with their parameters, the simplifier and
// its cut.  Each branch's points carry a digest: a branch whose points no
// longer match it was edited, and its table is rebaked from the points
// (control_points.hpp), so an edited point is never silently ignored.
#pragma once

#include "stage_results.hpp"

#include "host/tf_generation.hpp"

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace arbor::io {
class JsonWriter;
}

namespace arbor::pipeline {

// Writes the transfer functions of a result; `source` names the volume.
// `annotate`, when given, writes members of the caller's first (a report's
// provenance).
void write_transfer_functions(const std::filesystem::path &path, const TransferFunctionsResult &result,
                              const std::string &source,
                              const std::function<void(io::JsonWriter &)> &annotate = {});

// What `arbor render` needs back from a file: how the tree was simplified
// (to rebuild the labels), each branch's extremum (to check the rebuilt
// tree is the same), and the functions.
struct StoredTransferFunctions {
    std::string source, simplifier_id, cut;
    std::vector<int64_t> extremum_vertex;
    std::shared_ptr<TransferFunctions> functions;
    // Branches whose control points were edited after the file was written:
    // their tables were rebaked from the points.
    std::vector<uint32_t> rebaked;
};

// Throws std::invalid_argument naming the file and what is wrong with it.
StoredTransferFunctions read_transfer_functions(const std::filesystem::path &path);

} // namespace arbor::pipeline
