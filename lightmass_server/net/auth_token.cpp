#include "lightmass_server/net/auth_token.h"

namespace lc::bake {

bool tokens_equal(std::string_view expected, std::string_view given) {
    // Accumulate differences over the longer length so timing does not reveal
    // the position of the first mismatch.
    size_t n = expected.size() > given.size() ? expected.size() : given.size();
    unsigned diff = static_cast<unsigned>(expected.size() ^ given.size());
    for (size_t i = 0; i < n; ++i) {
        unsigned char a = i < expected.size() ? static_cast<unsigned char>(expected[i]) : 0;
        unsigned char b = i < given.size() ? static_cast<unsigned char>(given[i]) : 0;
        diff |= static_cast<unsigned>(a ^ b);
    }
    return diff == 0 && !expected.empty();
}

}  // namespace lc::bake
