// contour_tree_json.hpp - the file `arbor tree --json` writes,
// "arbor-contour-tree/2": a volume's contour tree and its branch
// decomposition with measures, as tables of columns (one array per field,
// indexed by node, arc or branch id) rather than one object per entry, so
// that the trees of noisy scans (hundreds of thousands of nodes) stay small
// and fast to write and to read.
//
// What can be derived is left out: positions (the grid geometry is written
// once), relative measures (a measure over the root's), children (from the
// parents).  README.md ("Contour tree files") says how to derive each.
#pragma once

#include "core/volume.hpp"
#include "topology/simplification.hpp"
#include "topology/topology_pipeline.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace arbor::io {

class JsonWriter;

struct ContourTreeFile {
    std::string source; // what the volume was read from
    const Volume *volume = nullptr;
    const topology::ContourTree *tree = nullptr;
    const topology::BranchDecomposition *branches = nullptr;
    const std::vector<topology::StageTiming> *timings = nullptr; // of the tree and the decomposition
    const topology::SimplificationCut *cut = nullptr;            // optional: "simplified"
    // Optional: writes members of the caller's (the report's provenance).
    std::function<void(JsonWriter &)> annotate;
};

// Replaces `path` only once the whole file is written.
void write_contour_tree_json(const std::filesystem::path &path, const ContourTreeFile &file);

} // namespace arbor::io
