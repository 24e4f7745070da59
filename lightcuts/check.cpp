#include "lightcuts/check.h"

#include <cstdio>
#include <cstdlib>

namespace lc::detail {

void check_failed(const char* condition, const char* file, int line) {
    std::fprintf(stderr, "%s:%d: check failed: %s\n", file, line, condition);
    std::fflush(stderr);
    std::abort();
}

}  // namespace lc::detail
