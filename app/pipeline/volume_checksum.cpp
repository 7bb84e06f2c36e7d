#include "volume_checksum.hpp"

#include <xxhash.h>

#include <memory>
#include <new>

namespace arbor::pipeline {

namespace {

struct StateFree {
    void operator()(XXH3_state_t *s) const { XXH3_freeState(s); }
};

} // namespace

std::string volume_checksum(const Volume &volume)
{
    std::unique_ptr<XXH3_state_t, StateFree> state(XXH3_createState());
    if (!state)
        throw std::bad_alloc();
    XXH3_128bits_reset(state.get());
    const auto add = [&](const void *p, std::size_t n) { XXH3_128bits_update(state.get(), p, n); };
    const uint32_t type = volume.type();
    add(&type, sizeof type);
    const Geometry &g = volume.geometry();
    for (int i = 0; i < 3; ++i) {
        add(&g.dims[i], sizeof g.dims[i]);
        add(&g.spacing[i], sizeof g.spacing[i]);
        add(&g.origin[i], sizeof g.origin[i]);
    }
    for (const double x : g.direction)
        add(&x, sizeof x);
    const ValueMapping &m = volume.mapping();
    add(&m.scale, sizeof m.scale);
    add(&m.offset, sizeof m.offset);
    add(m.unit.data(), m.unit.size());
    add(volume.data(), volume.byte_size());
    XXH128_canonical_t canonical;
    XXH128_canonicalFromHash(&canonical, XXH3_128bits_digest(state.get()));
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out = "xxh3-128:";
    for (const unsigned char byte : canonical.digest) {
        out += kHex[byte >> 4];
        out += kHex[byte & 15];
    }
    return out;
}

} // namespace arbor::pipeline
