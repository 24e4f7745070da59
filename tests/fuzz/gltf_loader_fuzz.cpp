// glTF loader from memory: any .gltf or .glb bytes load or are refused with a
// message, without a crash, a hang or a file read (no resource folder: only
// data: URIs and GLB chunks).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<std::string> warnings;
    lc::Result<lc::Scene> scene =
        lc::client::load_scene_from_memory(std::span(data, size), {}, warnings);
    lc::fuzz::check(scene.ok() || !scene.error().empty(), "a refused scene says why");
    return 0;
}
