#include "order_pieces.hpp"

#include <algorithm>
#include <stdexcept>

namespace arbor::topology {

OrderPieces::OrderPieces(UninitializedBuffer<uint32_t> order)
    : n_(static_cast<uint32_t>(order.size())), whole_(std::move(order))
{
}

OrderPieces::OrderPieces(arbor_voxel_type type, const void *values, uint32_t n, uint32_t piece)
    : n_(n), type_(type), values_(values), piece_(std::max<uint32_t>(piece, 1))
{
    if (!orders_by_counting(type))
        throw std::invalid_argument("only 8- and 16-bit values can be ordered a piece at a time");
    if (n > 0 && !values)
        throw std::invalid_argument("OrderPieces: no values");
    starts_ = count_value_starts(type, values, n);
}

uint64_t OrderPieces::walk_bytes(uint64_t n, uint64_t piece)
{
    return piece >= n ? 4 * n : 2 * 4 * (piece + kLookahead);
}

void OrderPieces::fill(bool downwards, uint32_t first, uint32_t *out) const
{
    const uint32_t end = static_cast<uint32_t>(std::min<uint64_t>(n_, uint64_t{first} + piece_ + kLookahead));
    // Step s of a downward walk is rank n - 1 - s.
    const uint32_t lo = downwards ? n_ - end : first, hi = downwards ? n_ - first : end;
    fill_order_range(type_, values_, n_, starts_, lo, hi, downwards, out);
}

} // namespace arbor::topology
