#pragma once
// A sort that a bake's stop interrupts within a short stretch of work: std::sort
// over runs, then bottom-up merges through one buffer, asking the poll between
// runs and every 4,096 elements of a merge (std::inplace_merge of two
// 16 M-edge halves ran 100 ms and more without a poll, and allocated and freed
// its own buffer each call). Under a strict total order, or when equal elements
// are alike in every byte, the result is std::sort's.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <span>

#include "lightmass_server/control/bake_stop.h"

namespace lc::bake {

namespace stoppable_sort_detail {

inline constexpr size_t kRun = size_t(1) << 16;
inline constexpr size_t kStride = size_t(1) << 12;

// Copies `count` elements, asking the poll every stride (they can be 16 M).
template <class T>
bool copy_polled(const T* from, size_t count, T* to, StopPoll& poll) {
    for (size_t i = 0; i < count; i += kStride) {
        if (poll()) return false;
        std::copy(from + i, from + std::min(count, i + kStride), to + i);
    }
    return true;
}

// Merges sorted [begin, mid) and [mid, end) through `buffer`, which holds a
// copy of the shorter side: the left side merged front to back, the right
// side back to front, so the output never overtakes what is still to be read.
// Ties keep the left element first, as std::inplace_merge does.
template <class T, class Less>
bool merge_polled(T* items, size_t begin, size_t mid, size_t end, T* buffer, Less& less, StopPoll& poll) {
    if (mid - begin <= end - mid) {
        const size_t count = mid - begin;
        if (!copy_polled(items + begin, count, buffer, poll)) return false;
        size_t l = 0, r = mid, out = begin;
        while (l < count && r < end) {
            if ((out & (kStride - 1)) == 0 && poll()) return false;
            items[out++] = less(items[r], buffer[l]) ? items[r++] : buffer[l++];
        }
        return copy_polled(buffer + l, count - l, items + out, poll);
    }
    const size_t count = end - mid;
    if (!copy_polled(items + mid, count, buffer, poll)) return false;
    size_t l = mid, r = count, out = end;  // one past the next element of each
    while (l > begin && r > 0) {
        if ((out & (kStride - 1)) == 0 && poll()) return false;
        items[--out] = less(buffer[r - 1], items[l - 1]) ? items[--l] : buffer[--r];
    }
    return copy_polled(buffer, r, items + begin, poll);
}

}  // namespace stoppable_sort_detail

// False when stopped: the range is then partly permuted, partly overwritten, and must be dropped.
template <class T, class Less>
bool stoppable_sort(std::span<T> items, Less less, StopPoll& poll) {
    using namespace stoppable_sort_detail;
    const size_t n = items.size();
    for (size_t begin = 0; begin < n; begin += kRun) {
        if (poll.now()) return false;
        std::sort(items.begin() + begin, items.begin() + std::min(n, begin + kRun), less);
    }
    if (n <= kRun) return true;
    // The shorter side of the widest merges, allocated once, written before read:
    // at most half the range (a quarter of a 16 M-edge buffer saved at 22 M edges).
    size_t widest = kRun;
    while (widest * 2 < n) widest *= 2;
    const std::unique_ptr<T[]> buffer = std::make_unique_for_overwrite<T[]>(std::max(widest / 2, n - widest));
    for (size_t width = kRun; width < n; width *= 2) {
        for (size_t begin = 0; begin + width < n; begin += 2 * width) {
            const size_t mid = begin + width;
            if (!less(items[mid], items[mid - 1])) continue;  // already in order
            if (!merge_polled(items.data(), begin, mid, std::min(n, mid + width), buffer.get(), less, poll))
                return false;
        }
    }
    return true;
}

}  // namespace lc::bake
