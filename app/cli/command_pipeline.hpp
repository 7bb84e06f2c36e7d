// command_pipeline.hpp - the pipeline one command runs on: its progress on
// the terminal, the on-disk contour-tree cache (unless --no-cache or no cache
// folder can be found), and Ctrl-C cancelling its jobs.
#pragma once

#include "cli_context.hpp"

#include "core/cancelled.hpp"
#include "pipeline/pipeline.hpp"

#include <functional>
#include <stop_token>

namespace arbor::cli {

class CommandPipeline {
public:
    // `single_pass`: PipelineOptions::single_pass, for a command that makes
    // one pass through the stages and ends (results no later stage reads
    // are let go as soon as they are through).
    CommandPipeline(Context &context, bool use_cache, bool single_pass = false);
    pipeline::Pipeline &operator*() { return pipeline_; }
    pipeline::Pipeline *operator->() { return &pipeline_; }

    // Pipeline::run, refused once Ctrl-C was pressed (also between jobs).
    template <pipeline::Stage S> std::shared_ptr<const pipeline::StageResult<S>> run()
    {
        throw_if_stopped(stop_);
        const std::shared_ptr<pipeline::Job> job = pipeline_.request(S);
        if (stop_.stop_requested()) // pressed while the jobs were being made
            pipeline_.cancel_all();
        return std::static_pointer_cast<const pipeline::StageResult<S>>(job->wait());
    }

private:
    std::stop_token stop_;
    pipeline::Pipeline pipeline_;
    std::stop_callback<std::function<void()>> on_interrupt_;
};

} // namespace arbor::cli
