#include "command_pipeline.hpp"

#include "pacs_fetch.hpp"

#include "pipeline/tree_cache.hpp"

namespace arbor::cli {

namespace {

pipeline::PipelineOptions options_for(Context &context, bool use_cache, bool single_pass)
{
    pipeline::PipelineOptions o;
    o.single_pass = single_pass;
    o.max_volume_bytes = context.max_volume_bytes;
    o.progress = &context.progress;
    o.fetch_input = fetch_pacs_input;
    if (use_cache) {
        try {
            o.tree_cache_folder = pipeline::TreeCache::default_folder();
            o.tree_cache_max_bytes = pipeline::TreeCache::default_max_bytes();
        } catch (const std::exception &e) {
            log_message(ARBOR_LOG_DEBUG, "", std::string("no contour-tree cache: ") + e.what());
            o.tree_cache_folder.clear();
        }
    }
    return o;
}

} // namespace

CommandPipeline::CommandPipeline(Context &context, bool use_cache, bool single_pass)
    : stop_(context.stop.get_token()),
      pipeline_(context.registry, options_for(context, use_cache, single_pass)),
      on_interrupt_(context.stop.get_token(), std::function<void()>([this] { pipeline_.cancel_all(); }))
{
}

} // namespace arbor::cli
