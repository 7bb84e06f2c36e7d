// nrrd.cpp - fuzzes the NRRD importer (plugins/importers): the header parser,
// the checks that the data fit the file, and the raw, gzip and ASCII
// encodings, through the host's import flow.  The input is one .nrrd file,
// written as input.nrrd (a header may name itself as its 'data file').
#include "fuzz_support.hpp"
#include "host_import.hpp"

// Deflate expands at most 1032:1; raw and ASCII data need more file than that.
constexpr uint64_t kMaxExpansion = 1032;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    const auto path = arbor::fuzz::write_input("input.nrrd", data, size);
    arbor::fuzz::import_through_host("org.arbor.importer.nrrd", path, {kMaxExpansion * size, {}});
    return 0;
}
