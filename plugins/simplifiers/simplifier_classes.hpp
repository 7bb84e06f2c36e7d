// simplifier_classes.hpp - the simplifier plugins of arbor-simplifiers.
#pragma once

#include <arbor/sdk/simplifier.hpp>

namespace arbor::simplifiers {

extern const arbor_plugin_descriptor kPersistenceDescriptor;
extern const arbor_plugin_descriptor kVolumeDescriptor;
extern const arbor_plugin_descriptor kHypervolumeDescriptor;
extern const arbor_plugin_descriptor kItriDescriptor;
extern const arbor_plugin_descriptor kNMeasureDescriptor;

sdk::Instance *create_persistence(const arbor_host *host);
sdk::Instance *create_volume(const arbor_host *host);
sdk::Instance *create_hypervolume(const arbor_host *host);
sdk::Instance *create_itri(const arbor_host *host);
sdk::Instance *create_n_measure(const arbor_host *host);

} // namespace arbor::simplifiers
