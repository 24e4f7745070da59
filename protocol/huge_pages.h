#pragma once
// Asks the kernel to back a large array with transparent huge pages. A 10^6-node
// tree decoded from the result channel is 136 MB: filled 4 KiB at a time that
// is 33,000 page faults, which cost the client more than the channel's bytes
// (docs/BENCHMARKS.md, "Result-channel streaming"); 2 MiB pages make it 68.
#include <cstddef>

namespace lc {

// Advises the 2 MiB-aligned pages inside [data, data + bytes); small ranges,
// and systems without transparent huge pages, are left as they are. Only a
// hint: the memory's contents and ownership do not change.
void advise_huge_pages(void* data, size_t bytes);

}  // namespace lc
