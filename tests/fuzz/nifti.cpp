// nifti.cpp - fuzzes the NIfTI importer (plugins/importer-vtk): our header
// checks, which stand between the file and vtkNIFTIImageReader, and what the
// importer does with the reader's answer, through the host's import flow.
// The input is one .nii file, plain or gzip-compressed.
#include "fuzz_support.hpp"
#include "host_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    const auto path = arbor::fuzz::write_input("input.nii", data, size);
    arbor::fuzz::import_through_host("org.arbor.importer.nifti", path);
    return 0;
}
