// bench_tf.cpp - how long regenerating transfer functions takes, through the
// ABI, on branch trees of 10, 100, 1000 and 10^4 branches: the residue-flow
// generator after a change of flow rate (the slider; colours cached), the
// same on a fresh instance (colours found by bisection), and with the
// inclusion depictor first.  Prints a table; not a pass/fail test.  The goal
// (issue 5): well under a millisecond for 100 branches.
#include "branch_tree_builder.hpp"
#include "fastest_run.hpp"
#include "test_paths.hpp"

#include "host/plugin_registry.hpp"
#include "host/tf_generation.hpp"

#include <cstdio>
#include <string>

using namespace arbor;

namespace {

void set_number(PluginInstance &p, const char *id, double x)
{
    arbor_param_value v{};
    v.struct_size = sizeof v;
    v.type = ARBOR_PARAM_FLOAT;
    v.components = 1;
    v.number[0] = x;
    p.set_param(id, v);
}

} // namespace

int main()
{
    PluginRegistry registry;
    registry.load_directories({test::plugin_dir()});
    std::printf("arbor_bench_tf: transfer-function regeneration through the ABI, fastest of 20 runs, lut 256\n\n");
    std::printf("%10s %18s %18s %18s\n", "branches", "Q change (ms)", "cold colours (ms)", "+inclusion (ms)");
    for (uint32_t n : {10u, 100u, 1000u, 10000u}) {
        test::BranchTreeBuilder builder = test::BranchTreeBuilder::random(n, 42);
        const arbor_branch_tree &tree = builder.record();
        arbor_tf_request request{};
        request.struct_size = sizeof request;
        request.tree = &tree;
        request.value_range[0] = 0;
        request.value_range[1] = 160;
        request.min_spacing = 1;
        TransferFunctions out(n, 256, 1.0);
        PluginInstance generator = registry.create("org.arbor.tf.residue-flow");
        generate_transfer_functions(generator, request, out); // colours into the cache
        double q = 10;
        const double warm = bench::fastest_seconds(
            [&] {
                set_number(generator, "flow-rate", q += 1);
                generate_transfer_functions(generator, request, out);
            },
            20);
        const double cold = bench::fastest_seconds(
            [&] {
                PluginInstance fresh = registry.create("org.arbor.tf.residue-flow");
                generate_transfer_functions(fresh, request, out);
            },
            n >= 10000 ? 3 : 20);
        PluginInstance inclusion = registry.create("org.arbor.depictor.inclusion");
        DepictionRecord depiction(n);
        arbor_depiction_request dr{};
        dr.struct_size = sizeof dr;
        dr.selected_branch = -1;
        dr.tree = &tree;
        const double with_depiction = bench::fastest_seconds(
            [&] {
                set_number(generator, "flow-rate", q += 1);
                depict(inclusion, dr, depiction);
                request.depiction = &depiction.record();
                generate_transfer_functions(generator, request, out);
                request.depiction = nullptr;
            },
            20);
        std::printf("%10u %18.4f %18.4f %18.4f\n", n, warm * 1e3, cold * 1e3, with_depiction * 1e3);
    }
    return 0;
}
