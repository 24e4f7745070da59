#pragma once
// A property a fuzz target asserts: on failure it names the property and
// aborts, so libFuzzer saves the input as a crash reproducer.
#include <cstdio>
#include <cstdlib>

namespace lc::fuzz {

inline void check(bool holds, const char* property) {
    if (holds) return;
    std::fprintf(stderr, "fuzz property broken: %s\n", property);
    std::abort();
}

}  // namespace lc::fuzz
