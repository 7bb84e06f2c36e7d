// metaimage.cpp - fuzzes the MetaImage importer (plugins/importers): the
// "Key = Value" header, HeaderSize and CompressedDataSize, and raw, zlib and
// ASCII data, through the host's import flow.  The input is one .mha file,
// written as input.mha (ElementDataFile may name it).
#include "fuzz_support.hpp"
#include "host_import.hpp"

// Deflate expands at most 1032:1; raw and ASCII data need more file than that.
constexpr uint64_t kMaxExpansion = 1032;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    const auto path = arbor::fuzz::write_input("input.mha", data, size);
    arbor::fuzz::import_through_host("org.arbor.importer.metaimage", path, {kMaxExpansion * size, {}});
    return 0;
}
