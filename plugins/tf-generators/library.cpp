// library.cpp - the entry point of arbor-tf-generators: the residue-flow
// generator and the conventional histogram-ramp baseline.
#include "tf_generator_classes.hpp"

namespace {

const arbor::sdk::PluginClass kGenerators[] = {
    {&arbor::tf::kResidueFlowDescriptor, &arbor::tf::create_residue_flow},
    {&arbor::tf::kHistogramDescriptor, &arbor::tf::create_histogram},
};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kGenerators)
