// transfer_functions.cpp - fuzzes reading a transfer-function file
// (app/pipeline/transfer_function_file: "arbor-transfer-functions/1" JSON),
// as `arbor render --tf` reads it.  The input is the file, written as tf.json.
#include "fuzz_support.hpp"

#include "pipeline/transfer_function_file.hpp"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    const auto path = arbor::fuzz::write_input("tf.json", data, size);
    try {
        arbor::pipeline::read_transfer_functions(path);
    } catch (const std::invalid_argument &) {
        // Refused with a message naming the file and what is wrong with it.
    } catch (...) {
        arbor::fuzz::unexpected_exception(std::current_exception());
    }
    return 0;
}
