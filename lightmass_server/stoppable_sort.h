#pragma once
// A sort that a bake's stop interrupts within a short stretch of work: std::sort
// over runs, then bottom-up merges through one buffer, asking the poll between
// runs and every kMergeStride elements of a merge (std::inplace_merge of two
// 16 M-edge halves ran 100 ms and more without a poll, and allocated and freed
// its own buffer each call). Under a strict total order, or when equal elements
// are alike in every byte, the result is std::sort's.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <span>

#include "lightmass_server/bake_stop.h"

namespace lc::bake {

// False when stopped: the range is then partly permuted, partly overwritten, and must be dropped.
template <class T, class Less>
bool stoppable_sort(std::span<T> items, Less less, StopPoll& poll) {
    constexpr size_t kRun = size_t(1) << 16;
    constexpr size_t kMergeStride = size_t(1) << 12;
    const size_t n = items.size();
    for (size_t begin = 0; begin < n; begin += kRun) {
        if (poll.now()) return false;
        std::sort(items.begin() + begin, items.begin() + std::min(n, begin + kRun), less);
    }
    if (n <= kRun) return true;
    // The left half of the widest merge, allocated once, written before read.
    size_t widest = kRun;
    while (widest * 2 < n) widest *= 2;
    const std::unique_ptr<T[]> left = std::make_unique_for_overwrite<T[]>(widest);
    // Copies of up to 16 M elements, polled like the merge.
    const auto copy_polled = [&](const T* from, size_t count, T* to) {
        for (size_t i = 0; i < count; i += kMergeStride) {
            if (poll()) return false;
            std::copy(from + i, from + std::min(count, i + kMergeStride), to + i);
        }
        return true;
    };
    for (size_t width = kRun; width < n; width *= 2) {
        for (size_t begin = 0; begin + width < n; begin += 2 * width) {
            const size_t mid = begin + width;
            const size_t end = std::min(n, mid + width);
            if (!less(items[mid], items[mid - 1])) continue;  // already in order
            if (!copy_polled(&items[begin], width, left.get())) return false;
            // Forward merge: the output never overtakes the right half's reads.
            // Ties take the left element first, as std::inplace_merge does.
            size_t l = 0, r = mid, out = begin;
            while (l < width && r < end) {
                if ((out & (kMergeStride - 1)) == 0 && poll()) return false;
                items[out++] = less(items[r], left[l]) ? items[r++] : left[l++];
            }
            if (!copy_polled(left.get() + l, width - l, &items[out])) return false;
        }
    }
    return true;
}

}  // namespace lc::bake
