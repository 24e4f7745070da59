// Order-independent identity of a cut: the sum (mod 2^32) of cut_hash_term(i)
// over its node indices, exactly as cpu_evaluator.cpp computes it.
#ifndef LC_CUT_HASH_GLSL
#define LC_CUT_HASH_GLSL

// murmur3's fmix32 finaliser of i + 1 (so node 0 does not hash to 0).
uint cut_hash_term(uint node_index) {
    uint h = node_index + 1u;
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

#endif
