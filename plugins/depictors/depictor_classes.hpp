// depictor_classes.hpp - the relationship depictors of arbor-depictors.
#pragma once

#include <arbor/sdk/depictor.hpp>

namespace arbor::depictors {

extern const arbor_plugin_descriptor kInclusionDescriptor;
extern const arbor_plugin_descriptor kNeighbourDescriptor;

sdk::Instance *create_inclusion(const arbor_host *host);
sdk::Instance *create_neighbour(const arbor_host *host);

} // namespace arbor::depictors
