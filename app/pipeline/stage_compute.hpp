// stage_compute.hpp - what each stage does, given the document a job was
// requested with and the results of its upstream stages.  Called by the
// pipeline's workers only, one job of a stage at a time; every long step
// reports to the job and polls its stop token.
#pragma once

#include "job.hpp"
#include "pipeline.hpp"
#include "plugin_slot.hpp"

#include <any>
#include <array>
#include <memory>

namespace arbor::pipeline {

struct StageContext {
    const Document &document;
    const PluginCatalog &catalog;
    const PipelineOptions &options;
    Job &job;
    PluginSlot &plugins;
    std::any &memo; // the stage's own state, kept from one of its jobs to the next
    std::array<std::shared_ptr<const void>, kStageCount> inputs; // upstream results, by stage

    template <Stage S> std::shared_ptr<const StageResult<S>> input() const
    {
        return std::static_pointer_cast<const StageResult<S>>(inputs[index_of(S)]);
    }
    std::stop_token stop() const { return job.stop_token(); }
};

std::shared_ptr<const void> compute_stage(Stage stage, StageContext &context);

} // namespace arbor::pipeline
