#pragma once
// Where the glTF loader's messages go. Errors and warnings start with the
// file's name ("scene.gltf: node 3 ..."); warnings are kept in order for the
// caller, who logs them or hands them back (gltf_loader.h).
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "lightcuts/result.h"

namespace lc::client {

class GltfDiagnostics {
public:
    // `file` names the file in every message; `warnings` outlives this object.
    GltfDiagnostics(std::string file, std::vector<std::string>& warnings)
        : file_(std::move(file)), warnings_(warnings) {}

    Error fail(const std::string& message) const { return Error{file_ + ": " + message}; }
    void warn(const std::string& message) { warnings_.push_back(file_ + ": " + message); }
    // Warnings another GltfDiagnostics of this file collected, already formatted.
    void take_warnings(const std::vector<std::string>& formatted) {
        warnings_.insert(warnings_.end(), formatted.begin(), formatted.end());
    }

    const std::string& file() const { return file_; }

private:
    std::string file_;
    std::vector<std::string>& warnings_;
};

// Shortest readable form of a number for messages ("0.8", "-2", "1e+39").
inline std::string message_number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

}  // namespace lc::client
