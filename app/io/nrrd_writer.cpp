#include "nrrd_writer.hpp"

#include "core/atomic_file.hpp"

#include <zlib.h>

#include <bit>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace arbor::io {

static_assert(std::endian::native == std::endian::little,
              "the NRRD writer assumes a little-endian host");

const char *nrrd_type_name(arbor_voxel_type type)
{
    switch (type) {
    case ARBOR_VOXEL_U8: return "uint8";
    case ARBOR_VOXEL_I8: return "int8";
    case ARBOR_VOXEL_U16: return "uint16";
    case ARBOR_VOXEL_I16: return "int16";
    case ARBOR_VOXEL_U32: return "uint32";
    case ARBOR_VOXEL_I32: return "int32";
    case ARBOR_VOXEL_F32: return "float";
    case ARBOR_VOXEL_F64: return "double";
    default: throw std::invalid_argument("no NRRD type for voxel type code " + std::to_string(type));
    }
}

namespace {

std::string number(double x)
{
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

std::string header(const Volume &v, const NrrdWriteOptions &o)
{
    const Geometry &g = v.geometry();
    std::ostringstream h;
    h << "NRRD0004\n# Written by Arbor\n";
    if (!o.content.empty())
        h << "content: " << o.content << "\n";
    h << "type: " << nrrd_type_name(v.type()) << "\n";
    h << "dimension: 3\n";
    h << "space: left-posterior-superior\n";
    h << "sizes: " << g.dims[0] << " " << g.dims[1] << " " << g.dims[2] << "\n";
    h << "space directions:";
    for (int c = 0; c < 3; ++c)
        h << " (" << number(g.direction[c] * g.spacing[c]) << ","
          << number(g.direction[3 + c] * g.spacing[c]) << ","
          << number(g.direction[6 + c] * g.spacing[c]) << ")";
    h << "\n";
    h << "kinds: domain domain domain\n";
    if (arbor_voxel_size(v.type()) > 1)
        h << "endian: little\n";
    h << "encoding: " << (o.gzip ? "gzip" : "raw") << "\n";
    h << "space origin: (" << number(g.origin[0]) << "," << number(g.origin[1]) << ","
      << number(g.origin[2]) << ")\n";
    const ValueMapping &m = v.mapping();
    if (m.scale != 1.0 || m.offset != 0.0) {
        h << "arbor_value_scale:=" << number(m.scale) << "\n";
        h << "arbor_value_offset:=" << number(m.offset) << "\n";
    }
    if (!m.unit.empty())
        h << "arbor_value_unit:=" << m.unit << "\n";
    for (const auto &[k, val] : o.key_values)
        h << k << ":=" << val << "\n";
    h << "\n";
    return h.str();
}

void write_gzip(AtomicFile &out, const void *data, uint64_t size, int level,
                const std::string &name)
{
    z_stream z{};
    // 15 + 16: a gzip wrapper, as NRRD's "gzip" encoding requires.
    if (deflateInit2(&z, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw std::runtime_error("cannot start gzip compression for " + name);
    std::vector<unsigned char> buffer(1 << 20);
    const auto *in = static_cast<const unsigned char *>(data);
    uint64_t left = size;
    int flush = Z_NO_FLUSH;
    do {
        const uInt chunk = static_cast<uInt>(std::min<uint64_t>(left, 1u << 30));
        z.next_in = const_cast<unsigned char *>(in);
        z.avail_in = chunk;
        in += chunk;
        left -= chunk;
        flush = left == 0 ? Z_FINISH : Z_NO_FLUSH;
        do {
            z.next_out = buffer.data();
            z.avail_out = static_cast<uInt>(buffer.size());
            if (deflate(&z, flush) == Z_STREAM_ERROR) {
                deflateEnd(&z);
                throw std::runtime_error("gzip compression failed for " + name);
            }
            out.write(buffer.data(), buffer.size() - z.avail_out);
        } while (z.avail_out == 0);
    } while (flush != Z_FINISH);
    deflateEnd(&z);
}

} // namespace

void write_nrrd(const Volume &volume, const std::filesystem::path &path,
                const NrrdWriteOptions &options)
{
    if (volume.empty())
        throw std::invalid_argument("cannot write an empty volume to " + path.string());
    AtomicFile out(path);
    out.write(header(volume, options));
    if (options.gzip)
        write_gzip(out, volume.data(), volume.byte_size(), options.gzip_level, path.string());
    else
        out.write(volume.data(), volume.byte_size());
    out.commit();
}

} // namespace arbor::io
