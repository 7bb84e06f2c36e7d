// tf_generator_classes.hpp - the transfer-function generators of
// arbor-tf-generators, and what they share: filling a branch's lookup table.
#pragma once

#include <arbor/sdk/tf_generator.hpp>

#include <functional>

namespace arbor::tf {

extern const arbor_plugin_descriptor kResidueFlowDescriptor;
extern const arbor_plugin_descriptor kHistogramDescriptor;

sdk::Instance *create_residue_flow(const arbor_host *host);
sdk::Instance *create_histogram(const arbor_host *host);

// The value interval [low, high] of branch b (saddle and extremum in
// ascending order; the root spans the volume's range).
std::pair<double, double> branch_domain(const sdk::BranchTreeView &tree, const arbor_tf_request &request, uint32_t b);

// Fills out.domain and out.lut of branch b from rgba(value) (straight sRGB,
// opacity), clamping every component to [0, 1].
void bake_lut(arbor_tf_set &out, uint32_t b, std::pair<double, double> domain,
              const std::function<std::array<float, 4>(double value)> &rgba);

} // namespace arbor::tf
