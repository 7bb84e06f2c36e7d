// order_pieces.hpp - the vertex order as the sweeps and the merge read it:
// front to back or back to front, a piece at a time.
//
// Whole, it is sort_vertices' array, 4 bytes a vertex, read as one piece.
// Streamed (8- and 16-bit values only), it is never whole: each piece is
// made by one scan of the values (fill_order_range) on a second thread
// while the previous piece is read, two pieces of memory in all.  A
// 512 x 512 x 2000 CT's order is 2 GB whole; streamed in eighths, 0.5 GB.
#pragma once

#include "uninitialized_buffer.hpp"
#include "vertex_order.hpp"

#include <arbor/volume.h>

#include <cstddef>
#include <cstdint>
#include <future>
#include <vector>

namespace arbor::topology {

// Consecutive ranks of the order, in the direction it is walked: (*this)[i]
// for i < count, and past count the next piece's first vertices, up to
// OrderPieces::kLookahead of them (fewer only where the order ends).
struct OrderPiece {
    const uint32_t *ids;
    std::ptrdiff_t stride; // 1, or -1 for the whole order walked downwards
    uint32_t count;
    uint32_t operator[](uint32_t i) const { return ids[stride * static_cast<std::ptrdiff_t>(i)]; }
};

class OrderPieces {
public:
    // How far past its end a piece can be read: for prefetching.
    static constexpr uint32_t kLookahead = 64;

    OrderPieces() = default;
    // The whole order, one piece.
    explicit OrderPieces(UninitializedBuffer<uint32_t> order);
    // Streamed in pieces of `piece` vertices: the values must outlive this
    // and be of a type for which orders_by_counting holds.
    OrderPieces(arbor_voxel_type type, const void *values, uint32_t n, uint32_t piece);

    uint32_t size() const { return n_; }
    bool streamed() const { return values_ != nullptr; }
    // Bytes held while a walk runs: the whole order, or two pieces.
    static uint64_t walk_bytes(uint64_t n, uint64_t piece);

    // Calls visit(const OrderPiece &, uint32_t first_step) for each piece,
    // lowest ranks first, or highest first when `downwards`; first_step is
    // how many vertices came before the piece in the walk.
    template <class Visit>
    void walk(bool downwards, Visit &&visit) const
    {
        if (n_ == 0)
            return;
        if (!streamed()) {
            const uint32_t *ids = whole_.data();
            visit(OrderPiece{downwards ? ids + (n_ - 1) : ids, downwards ? -1 : 1, n_}, 0u);
            return;
        }
        UninitializedBuffer<uint32_t> buffers[2] = {UninitializedBuffer<uint32_t>(piece_ + kLookahead, Pages::Small),
                                                    UninitializedBuffer<uint32_t>(piece_ + kLookahead, Pages::Small)};
        fill(downwards, 0, buffers[0].data());
        std::future<void> next;
        for (uint32_t first = 0, b = 0; first < n_; first += piece_, b ^= 1) {
            if (n_ - first > piece_)
                next = std::async(std::launch::async, [this, downwards, &buffers, b, first] {
                    fill(downwards, first + piece_, buffers[b ^ 1].data());
                });
            visit(OrderPiece{buffers[b].data(), 1, std::min(piece_, n_ - first)}, first);
            if (next.valid())
                next.get();
        }
    }

    // Frees the whole order (a streamed one holds nothing between walks).
    void release() { whole_.release(); }

private:
    // Steps [first, first + piece + kLookahead) of a walk, cut at the end.
    void fill(bool downwards, uint32_t first, uint32_t *out) const;

    uint32_t n_ = 0;
    UninitializedBuffer<uint32_t> whole_;
    arbor_voxel_type type_ = ARBOR_VOXEL_U8;
    const void *values_ = nullptr;
    std::vector<uint32_t> starts_;
    uint32_t piece_ = 0;
};

} // namespace arbor::topology
