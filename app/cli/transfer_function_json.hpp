// transfer_function_json.hpp - our versioned file format for per-branch
// transfer functions, "arbor-transfer-functions/1": for every kept branch
// its value domain, control points (the editable form) and the baked RGBA
// lookup table (what renderers use), plus everything needed to reproduce
// it: the generator and depictor with their parameters, the simplifier and
// its cut.
#pragma once

#include "host/plugin_instance.hpp"
#include "host/tf_generation.hpp"

#include <arbor/branch_tree.h>

#include <memory>
#include <string>
#include <vector>

namespace arbor::cli {

struct TransferFunctionFile {
    std::string source;          // the volume
    std::string simplifier_id;   // and its cut ("keep 12")
    std::string cut;
    const PluginInstance *generator = nullptr;
    const PluginInstance *depictor = nullptr; // may be null
    int32_t selected_branch = -1;
    double value_range[2] = {0, 0};
    const arbor_branch_tree *tree = nullptr;
    const arbor_depiction *depiction = nullptr; // may be null
    const TransferFunctions *functions = nullptr;
};

void write_transfer_functions(const std::string &path, const TransferFunctionFile &f);

// What `arbor render` needs back from a file: how the tree was simplified
// (to rebuild the labels), each branch's extremum (to check the rebuilt
// tree is the same), and the functions.
struct StoredTransferFunctions {
    std::string source, simplifier_id, cut;
    std::vector<int64_t> extremum_vertex;
    std::unique_ptr<TransferFunctions> functions;
};

// Throws std::invalid_argument naming the file and what is wrong with it.
StoredTransferFunctions read_transfer_functions(const std::string &path);

} // namespace arbor::cli
