// commands.hpp - the subcommands of `arbor`.  Each adds itself to the CLI
// and registers its run function in the Context.
#pragma once

#include "cli_context.hpp"

namespace arbor::cli {

void add_info_command(CLI::App &app, Context &context);
void add_plugins_command(CLI::App &app, Context &context);
void add_plugin_check_command(CLI::App &app, Context &context);
void add_phantom_command(CLI::App &app, Context &context);
void add_convert_command(CLI::App &app, Context &context);
void add_pairs_command(CLI::App &app, Context &context);
void add_diagram_distance_command(CLI::App &app, Context &context);
void add_tree_command(CLI::App &app, Context &context);
void add_simplify_command(CLI::App &app, Context &context);
void add_compare_command(CLI::App &app, Context &context);
void add_tf_command(CLI::App &app, Context &context);
void add_render_command(CLI::App &app, Context &context);
void add_run_command(CLI::App &app, Context &context);
void add_denoise_study_command(CLI::App &app, Context &context);
void add_dicom_command(CLI::App &app, Context &context);
void add_view_command(CLI::App &app, Context &context);
void add_pacs_command(CLI::App &app, Context &context);

} // namespace arbor::cli
