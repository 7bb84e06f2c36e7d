// transfer_function_stage.hpp - the step from a simplified branch tree to
// per-branch transfer functions, shared by `arbor tf` and `arbor run`: a
// depictor (inclusion by default, neighbour around --select) then a
// generator (residue flow by default), with their flags.
#pragma once

#include "plugin_choice.hpp"

#include "host/branch_tree_record.hpp"
#include "host/tf_generation.hpp"

#include <opencv2/core.hpp>

#include <memory>
#include <optional>
#include <string>

namespace arbor::cli {

struct TransferFunctionResult {
    PluginInstance *generator = nullptr;
    PluginInstance *depictor = nullptr; // null with --relation none
    arbor_depiction_request request{};  // the selection the depictor saw
    std::unique_ptr<DepictionRecord> depiction;
    std::unique_ptr<TransferFunctions> functions;
    double value_range[2] = {0, 0};
    double seconds = 0.0;
};

class TransferFunctionStage {
public:
    void add_to(CLI::App &command, Context &context);
    // Checks the flags against each other before any work is done.
    void validate(bool want_legend) const;
    // `value_range`: the volume's stored minimum and maximum.
    TransferFunctionResult run(const BranchTreeRecord &tree, const Volume &volume, const double value_range[2],
                               Context &context);
    // The depictor's legend (the relation wheel) as a BGR image; throws
    // std::invalid_argument when the depictor draws none.
    cv::Mat legend(PluginInstance &depictor, const arbor_depiction_request &request, int size) const;
    const std::string &relation() const { return relation_; }
    std::optional<int32_t> selected() const { return select_; }
    PluginChoice &depictors() { return depictors_; }

private:
    PluginChoice depictors_{ARBOR_KIND_DEPICTOR, "depictor"};
    PluginChoice generators_{ARBOR_KIND_TF_GENERATOR, "transfer-function generator"};
    std::string generator_ = "residue-flow", relation_ = "inclusion";
    std::optional<double> flow_rate_;
    std::optional<std::string> shape_, hues_;
    std::optional<int32_t> select_;
    uint32_t lut_size_ = 256;
};

} // namespace arbor::cli
