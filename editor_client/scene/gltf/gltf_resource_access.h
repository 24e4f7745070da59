#pragma once
// What a glTF file may make the loader read besides itself. Buffer and image
// URIs come from the file, so a scene from elsewhere must not open arbitrary
// paths ("/etc/...", "../../") or block on a FIFO: by default only regular
// files inside the scene's folder are read (data: URIs never touch the disk).
#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/gltf_buffer_sizes.h"

namespace lc::client {

class GltfResourceAccess {
public:
    // `folder`: the scene's folder; empty: no file is read at all (a scene
    // loaded from memory). `allow_external`: any regular file may be read.
    GltfResourceAccess(std::filesystem::path folder, bool allow_external);

    // Callbacks for tinygltf; they refer to this object, which must outlive the load.
    tinygltf::FsCallbacks callbacks();

    // A URI of the file (not a data: URI) as a path: relative ones below the
    // scene's folder, absolute ones as they are.
    std::filesystem::path resolve(const std::string& uri) const;
    // Reads `path` under the same rules as tinygltf's reads (the environment
    // map a file names, gltf_environment.h); `error` says why not.
    bool read_resource(const std::filesystem::path& path, std::vector<unsigned char>& out,
                       std::string& error);

    // The buffers' byteLengths (gltf_buffer_sizes.h): a buffer file of another
    // size is refused by its size before a byte of it is read.
    void expect_buffer_sizes(const std::vector<BufferFileSize>& sizes);

    // Why each refused URI was refused, in order ("'../x.bin' lies outside ...").
    const std::vector<std::string>& refusals() const { return refusals_; }

    // Reads a regular file without blocking on a FIFO or a device: the file is
    // opened non-blocking and checked with fstat before a byte is read, and
    // refused when `expected_size` is set and the file's size differs.
    static bool read_regular_file(const std::filesystem::path& path, std::vector<unsigned char>& out,
                                  std::string& error, std::optional<uint64_t> expected_size = std::nullopt);

private:
    // True when `path` may be read; otherwise records why in refusals_. A path
    // that does not exist is not a refusal (tinygltf reports it as not found).
    bool admits(const std::string& path);

    static bool exists(const std::string& path, void* self);
    static std::string expand(const std::string& path, void* self);
    static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* self);
    static bool write(std::string* err, const std::string& path,
                      const std::vector<unsigned char>& contents, void* self);

    std::string base_dir_;          // the folder as tinygltf joins it to URIs
    std::filesystem::path folder_;  // canonical; empty when nothing may be read
    bool allow_external_ = false;
    std::vector<std::string> refusals_;
    // Normalised path (as tinygltf joins it) -> the byteLength its buffer announces.
    std::map<std::filesystem::path, uint64_t> expected_sizes_;
};

}  // namespace lc::client
