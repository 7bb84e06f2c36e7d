// library.cpp - the entry point of arbor-simplifiers: the single-measure
// simplifiers (persistence, volume, hypervolume), ITri and the n-measure
// generalisation, all ranking branches by their relative measures.
#include "simplifier_classes.hpp"

namespace {

const arbor::sdk::PluginClass kSimplifiers[] = {
    {&arbor::simplifiers::kPersistenceDescriptor, &arbor::simplifiers::create_persistence},
    {&arbor::simplifiers::kVolumeDescriptor, &arbor::simplifiers::create_volume},
    {&arbor::simplifiers::kHypervolumeDescriptor, &arbor::simplifiers::create_hypervolume},
    {&arbor::simplifiers::kItriDescriptor, &arbor::simplifiers::create_itri},
    {&arbor::simplifiers::kNMeasureDescriptor, &arbor::simplifiers::create_n_measure},
};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kSimplifiers)
