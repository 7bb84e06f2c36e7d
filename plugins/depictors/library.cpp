// library.cpp - the entry point of arbor-depictors: inclusion (depth-driven
// opacity) and neighbouring (the relation wheel).
#include "depictor_classes.hpp"

namespace {

const arbor::sdk::PluginClass kDepictors[] = {
    {&arbor::depictors::kInclusionDescriptor, &arbor::depictors::create_inclusion},
    {&arbor::depictors::kNeighbourDescriptor, &arbor::depictors::create_neighbour},
};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kDepictors)
