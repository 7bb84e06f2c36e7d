// byte_order.cpp - see byte_order.hpp.  memcpy keeps the loads legal for any
// alignment; compilers turn each loop into bswap instructions.
#include "byte_order.hpp"

#include <cstring>

namespace arbor::importers {

namespace {

template <class T, class Swap>
void swap_all(unsigned char *p, uint64_t count, Swap swap)
{
    for (uint64_t i = 0; i < count; ++i, p += sizeof(T)) {
        T v;
        std::memcpy(&v, p, sizeof v);
        v = swap(v);
        std::memcpy(p, &v, sizeof v);
    }
}

} // namespace

void swap_byte_order(void *data, uint64_t count, uint32_t element_size)
{
    auto *p = static_cast<unsigned char *>(data);
    switch (element_size) {
    case 2: swap_all<uint16_t>(p, count, [](uint16_t v) { return __builtin_bswap16(v); }); break;
    case 4: swap_all<uint32_t>(p, count, [](uint32_t v) { return __builtin_bswap32(v); }); break;
    case 8: swap_all<uint64_t>(p, count, [](uint64_t v) { return __builtin_bswap64(v); }); break;
    default: break;
    }
}

} // namespace arbor::importers
