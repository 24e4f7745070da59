// Confines tinygltf's file access to regular files inside the scene's folder.
#include "editor_client/scene/gltf/gltf_resource_access.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

namespace lc::client {
namespace {

// Larger resources are refused rather than read into memory.
constexpr off_t kMaxResourceBytes = off_t(1) << 32;

// `path` is `folder` or lies below it; both canonical.
bool inside(const std::filesystem::path& path, const std::filesystem::path& folder) {
    return std::mismatch(folder.begin(), folder.end(), path.begin(), path.end()).first ==
           folder.end();
}

// Closes the descriptor on every path out of read_regular_file.
struct FileDescriptor {
    int fd = -1;
    ~FileDescriptor() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

GltfResourceAccess::GltfResourceAccess(std::filesystem::path folder, bool allow_external)
    : base_dir_(folder.string()), allow_external_(allow_external) {
    if (folder.empty()) return;
    std::error_code ec;
    folder_ = std::filesystem::canonical(folder, ec);
    if (ec) folder_ = std::filesystem::absolute(folder, ec).lexically_normal();
}

tinygltf::FsCallbacks GltfResourceAccess::callbacks() {
    return tinygltf::FsCallbacks{&exists, &expand, &read, &write, this};
}

bool GltfResourceAccess::admits(const std::string& path) {
    if (folder_.empty()) {
        refusals_.push_back("'" + path +
                            "' is an external file; a scene loaded from memory reads none");
        return false;
    }
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) return false;
    if (!std::filesystem::is_regular_file(status)) {
        refusals_.push_back("'" + path + "' is not a regular file");
        return false;
    }
    if (allow_external_) return true;
    const std::filesystem::path resolved = std::filesystem::canonical(path, ec);
    if (ec || !inside(resolved, folder_)) {
        refusals_.push_back("'" + path + "' lies outside the scene's folder " + folder_.string() +
                            " (--allow-external-resources reads it)");
        return false;
    }
    return true;
}

void GltfResourceAccess::expect_buffer_sizes(const std::vector<BufferFileSize>& sizes) {
    for (const BufferFileSize& buffer : sizes) {
        // tinygltf joins the base folder and the URI with one '/'.
        const std::string joined = base_dir_.empty()          ? buffer.uri
                                   : base_dir_.ends_with('/') ? base_dir_ + buffer.uri
                                                              : base_dir_ + "/" + buffer.uri;
        expected_sizes_[std::filesystem::path(joined).lexically_normal()] = buffer.byte_length;
    }
}

bool GltfResourceAccess::read_regular_file(const std::filesystem::path& path, std::vector<unsigned char>& out,
                                           std::string& error, std::optional<uint64_t> expected_size) {
    FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0) {
        error = "cannot open '" + path.string() + "': " + std::strerror(errno);
        return false;
    }
    struct stat info {};
    if (::fstat(file.fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        error = "'" + path.string() + "' is not a regular file";
        return false;
    }
    if (info.st_size > kMaxResourceBytes) {
        error = "'" + path.string() + "' is larger than 4 GiB";
        return false;
    }
    if (expected_size && uint64_t(info.st_size) != *expected_size) {
        error = "'" + path.string() + "' holds " + std::to_string(info.st_size) +
                " bytes but its buffer's byteLength is " + std::to_string(*expected_size) + "; not read";
        return false;
    }
    out.resize(size_t(info.st_size));
    size_t done = 0;
    while (done < out.size()) {
        const ssize_t got = ::read(file.fd, out.data() + done, out.size() - done);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) {
            error = "cannot read '" + path.string() + "'" +
                    (got < 0 ? std::string(": ") + std::strerror(errno) : " (it shrank)");
            return false;
        }
        done += size_t(got);
    }
    return true;
}

std::filesystem::path GltfResourceAccess::resolve(const std::string& uri) const {
    const std::filesystem::path path(uri);
    if (path.is_absolute() || base_dir_.empty()) return path;
    return std::filesystem::path(base_dir_) / path;
}

bool GltfResourceAccess::read_resource(const std::filesystem::path& path,
                                       std::vector<unsigned char>& out, std::string& error) {
    const size_t refused = refusals_.size();
    if (!admits(path.string())) {
        error = refusals_.size() > refused ? "refused: " + refusals_.back()
                                           : "'" + path.string() + "' does not exist";
        return false;
    }
    return read_regular_file(path, out, error);
}

bool GltfResourceAccess::exists(const std::string& path, void* self) {
    return static_cast<GltfResourceAccess*>(self)->admits(path);
}

// No expansion of '~' or variables: a URI names a file, nothing more. tinygltf
// prefixes every URI with the base folder (or "./"), which turns an absolute
// URI into a path that names nothing; take the URI back so that it is refused
// by name, or read where --allow-external-resources allows it.
std::string GltfResourceAccess::expand(const std::string& path, void* self) {
    const std::string& base = static_cast<GltfResourceAccess*>(self)->base_dir_;
    for (const std::string& prefix : {base.ends_with('/') ? base : base + "/", std::string("./")}) {
        if (prefix.size() > 1 && path.size() > prefix.size() && path.starts_with(prefix) &&
            path[prefix.size()] == '/') {
            return path.substr(prefix.size());
        }
    }
    return path;
}

bool GltfResourceAccess::read(std::vector<unsigned char>* out, std::string* err,
                              const std::string& path, void* self) {
    // Checked again at the read: the file may have changed since tinygltf asked.
    if (!static_cast<GltfResourceAccess*>(self)->admits(path)) {
        if (err) *err += "refused to read '" + path + "'\n";
        return false;
    }
    const auto& expected = static_cast<GltfResourceAccess*>(self)->expected_sizes_;
    const auto size = expected.find(std::filesystem::path(path).lexically_normal());
    std::string error;
    if (!read_regular_file(path, *out, error,
                           size == expected.end() ? std::nullopt : std::optional<uint64_t>(size->second))) {
        if (err) *err += error + "\n";
        return false;
    }
    return true;
}

bool GltfResourceAccess::write(std::string* err, const std::string& path,
                               const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader writes no files ('" + path + "')\n";
    return false;
}

}  // namespace lc::client
