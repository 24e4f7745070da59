#pragma once
// std::nth_element that a bake's stop interrupts: quickselect with a
// median-of-three pivot and Hoare's partition, asking the poll every 4,096
// swaps, down to ranges of kSelectDirect elements that std::nth_element
// finishes. A k-d tree's top split of 4 M points took 70-190 ms in one
// std::nth_element call, unpolled. Under a strict total order the elements
// before `nth` are the same set as std::nth_element's (their order may differ).
#include <algorithm>
#include <cstddef>
#include <utility>

#include "lightmass_server/control/bake_stop.h"

namespace lc::bake {

inline constexpr size_t kSelectDirect = size_t(1) << 15;

// False when stopped: the range is then partly arranged and must be dropped.
// `less` must be a strict total order (no two elements equivalent).
template <class T, class Less>
bool stoppable_nth_element(T* items, size_t begin, size_t nth, size_t end, Less less, StopPoll& poll) {
    // Past this many partition rounds the pivots are unlucky: std::nth_element
    // (introselect) bounds the rest.
    int rounds_left = 64;
    while (end - begin > kSelectDirect && rounds_left-- > 0) {
        if (poll.now()) return false;
        const size_t mid = begin + (end - begin) / 2;
        // The median of three distinct elements lies strictly inside the
        // range's order, so both sides of the split are non-empty.
        T a = items[begin], b = items[mid], c = items[end - 1];
        if (less(b, a)) std::swap(a, b);
        if (less(c, b)) std::swap(b, c);
        if (less(b, a)) std::swap(a, b);
        const T pivot = b;
        size_t i = begin, j = end - 1;
        for (size_t swaps = 1;; ++swaps) {
            while (less(items[i], pivot)) ++i;
            while (less(pivot, items[j])) --j;
            if (i >= j) break;
            std::swap(items[i], items[j]);
            ++i;
            --j;
            if ((swaps & 4095) == 0 && poll()) return false;
        }
        // [begin, j] holds no element above the pivot, [j + 1, end) none below.
        if (nth <= j) {
            end = j + 1;
        } else {
            begin = j + 1;
        }
    }
    if (poll.now()) return false;
    std::nth_element(items + begin, items + nth, items + end, less);
    return true;
}

}  // namespace lc::bake
