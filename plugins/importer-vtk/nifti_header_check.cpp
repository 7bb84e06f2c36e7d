// nifti_header_check.cpp - independent parse of the NIfTI-1/-2 fields that
// decide how vtkNIFTIImageReader sizes and reads the voxels.
#include "nifti_header_check.hpp"

#include <arbor/sdk/error.hpp>

#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <utility>

namespace arbor::importer_vtk {

namespace {

constexpr std::size_t kNifti1Size = 348;
constexpr std::size_t kNifti2Size = 540;

struct HeaderBytes {
    unsigned char data[kNifti2Size] = {};
    std::size_t size = 0;
    bool compressed = false;
    bool swapped = false;

    template <class T>
    T at(std::size_t offset) const
    {
        unsigned char b[sizeof(T)];
        std::memcpy(b, data + offset, sizeof(T));
        if (swapped)
            for (std::size_t i = 0; i < sizeof(T) / 2; ++i)
                std::swap(b[i], b[sizeof(T) - 1 - i]);
        T v;
        std::memcpy(&v, b, sizeof(T));
        return v;
    }
};

// gzread reads plain files unchanged, so one path serves .nii and .nii.gz.
HeaderBytes read_header_bytes(const std::string &path, const std::string &name)
{
    HeaderBytes h;
    gzFile file = gzopen(path.c_str(), "rb");
    if (!file)
        sdk::fail(ARBOR_ERROR_IO, name + ": cannot be opened for reading");
    const int got = gzread(file, h.data, sizeof h.data);
    h.compressed = gzdirect(file) == 0;
    gzclose(file);
    if (got < 0)
        sdk::fail(ARBOR_ERROR_FORMAT, name + ": the compressed header cannot be inflated");
    h.size = static_cast<std::size_t>(got);
    return h;
}

struct TypeInfo {
    int code;
    int bits;
    const char *name;
    int components;
    bool importable;
};

// nifti1.h datatype codes with their sizes; VTK and Arbor take the scalar ones.
constexpr TypeInfo kTypes[] = {
    {2, 8, "uint8", 1, true},          {4, 16, "int16", 1, true},
    {8, 32, "int32", 1, true},         {16, 32, "float32", 1, true},
    {32, 64, "complex64", 2, false},   {64, 64, "float64", 1, true},
    {128, 24, "RGB24", 3, false},      {256, 8, "int8", 1, true},
    {512, 16, "uint16", 1, true},      {768, 32, "uint32", 1, true},
    {1024, 64, "int64", 1, false},     {1280, 64, "uint64", 1, false},
    {1536, 128, "float128", 1, false}, {1792, 128, "complex128", 2, false},
    {2048, 256, "complex256", 2, false}, {2304, 32, "RGBA32", 4, false},
};

const TypeInfo *type_info(int code)
{
    for (const TypeInfo &t : kTypes)
        if (t.code == code)
            return &t;
    return nullptr;
}

bool magic_is(const unsigned char *m, char version)
{
    return m[0] == 'n' && (m[1] == '+' || m[1] == 'i') && m[2] == version && m[3] == 0;
}

// NIfTI-2 (nifti2.h): magic at 4, datatype 12, bitpix 14, dim[8] int64 at 16,
// vox_offset int64 at 168.
void read_nifti2(const HeaderBytes &h, const std::string &what, NiftiEssentials &e, int &bitpix)
{
    if (h.size < kNifti2Size)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": " + std::to_string(h.size) +
                                          " bytes, shorter than a NIfTI-2 header (540)");
    const unsigned char *m = h.data + 4;
    if (!magic_is(m, '2'))
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": sizeof_hdr is 540 but the NIfTI-2 magic is "
                                             "missing");
    if (std::memcmp(m + 4, "\r\n\032\n", 4) != 0)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the NIfTI-2 magic was damaged by a newline "
                                             "conversion (transferred as text?)");
    e.version = 2;
    e.single_file = m[1] == '+';
    for (int i = 0; i < 8; ++i)
        e.dim[i] = h.at<int64_t>(16 + 8 * i);
    e.datatype = h.at<int16_t>(12);
    bitpix = h.at<int16_t>(14);
    e.vox_offset = static_cast<double>(h.at<int64_t>(168));
}

// NIfTI-1 (nifti1.h): dim[8] int16 at 40, datatype 70, bitpix 72,
// vox_offset float at 108, magic at 344.
void read_nifti1(const HeaderBytes &h, const std::string &what, NiftiEssentials &e, int &bitpix)
{
    const unsigned char *m = h.data + 344;
    if (!magic_is(m, '1'))
        sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                  what + ": no NIfTI magic (an Analyze 7.5 header, which says nothing reliable "
                         "about orientation)");
    e.version = 1;
    e.single_file = m[1] == '+';
    for (int i = 0; i < 8; ++i)
        e.dim[i] = h.at<int16_t>(40 + 2 * i);
    e.datatype = h.at<int16_t>(70);
    bitpix = h.at<int16_t>(72);
    e.vox_offset = h.at<float>(108);
}

void check_dims(NiftiEssentials &e, const std::string &what)
{
    const int64_t ndim = e.dim[0];
    if (ndim < 1 || ndim > 7)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": dim[0] is " + std::to_string(ndim) +
                                          ", the number of dimensions must lie in 1..7");
    for (int i = 1; i <= ndim; ++i)
        if (e.dim[i] < 1 || e.dim[i] > std::numeric_limits<int32_t>::max())
            sdk::fail(ARBOR_ERROR_FORMAT, what + ": dim[" + std::to_string(i) + "] is " +
                                              std::to_string(e.dim[i]) +
                                              ", sizes must lie in 1..2147483647");
    for (int i = int(ndim) + 1; i < 8; ++i)
        e.dim[i] = 1;
    if (e.dim[5] > 1)
        sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                  what + ": a vector image (dim[5] = " + std::to_string(e.dim[5]) +
                      " components per voxel); only single-component scalars can be imported");
}

const TypeInfo &check_type(int datatype, int bitpix, const std::string &what)
{
    const TypeInfo *type = type_info(datatype);
    if (!type)
        sdk::fail(ARBOR_ERROR_FORMAT,
                  what + ": unknown NIfTI datatype code " + std::to_string(datatype));
    if (type->bits != bitpix)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": bitpix " + std::to_string(bitpix) +
                                          " does not match datatype " + type->name + " (" +
                                          std::to_string(type->bits) + " bits)");
    if (type->components > 1)
        sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                  what + ": datatype " + type->name + " has " + std::to_string(type->components) +
                      " components per voxel; only single-component scalars can be imported");
    if (!type->importable)
        sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                  what + ": datatype " + type->name +
                      " has no Arbor voxel type (8-, 16- and 32-bit integers, float32 and "
                      "float64 are supported)");
    return *type;
}

// A byte count that may not fit in 64 bits (dims up to 2^31 - 1 each).
std::string byte_count(double bytes)
{
    char text[64];
    std::snprintf(text, sizeof text, "%.0f", bytes);
    return text;
}

void check_voxel_room(const NiftiEssentials &e, const TypeInfo &type, bool compressed,
                      uint64_t file_size, const std::string &what)
{
    const double header_size = e.version == 2 ? double(kNifti2Size) : double(kNifti1Size);
    if (!std::isfinite(e.vox_offset) || e.vox_offset < 0 ||
        (e.single_file && e.vox_offset < header_size) || e.vox_offset > 0x1p53)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": vox_offset " + std::to_string(e.vox_offset) +
                                          " does not point past the header");
    // An uncompressed single file must hold the voxels it announces; saying
    // so here is clearer than VTK's "truncated" after a full-size allocation.
    if (!e.single_file || compressed)
        return;
    const double bytes =
        double(e.dim[1]) * double(e.dim[2]) * double(e.dim[3]) * double(type.bits / 8);
    if (e.vox_offset + bytes > double(file_size))
        sdk::fail(ARBOR_ERROR_FORMAT,
                  what + ": vox_offset " + std::to_string(int64_t(e.vox_offset)) + " + " +
                      std::to_string(e.dim[1]) + " x " + std::to_string(e.dim[2]) + " x " +
                      std::to_string(e.dim[3]) + " " + type.name + " voxels need " +
                      byte_count(e.vox_offset + bytes) +
                      " bytes but the file holds " + std::to_string(file_size) + " (truncated)");
}

} // namespace

NiftiEssentials check_nifti_header(const std::string &path, const std::string &name,
                                   uint64_t file_size)
{
    const std::string what = "header of " + name;
    HeaderBytes h = read_header_bytes(path, name);
    if (h.size < kNifti1Size)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": " + std::to_string(h.size) +
                                          " bytes, shorter than a NIfTI-1 header (348)");
    int32_t sizeof_hdr = h.at<int32_t>(0);
    if (sizeof_hdr != int32_t(kNifti1Size) && sizeof_hdr != int32_t(kNifti2Size)) {
        h.swapped = true;
        sizeof_hdr = h.at<int32_t>(0);
    }
    NiftiEssentials e;
    int bitpix = 0;
    if (sizeof_hdr == int32_t(kNifti2Size))
        read_nifti2(h, what, e, bitpix);
    else if (sizeof_hdr == int32_t(kNifti1Size))
        read_nifti1(h, what, e, bitpix);
    else
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": not a NIfTI header (sizeof_hdr is neither 348 "
                                             "nor 540 in either byte order)");
    check_dims(e, what);
    const TypeInfo &type = check_type(e.datatype, bitpix, what);
    check_voxel_room(e, type, h.compressed, file_size, what);
    return e;
}

} // namespace arbor::importer_vtk
