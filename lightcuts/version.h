#pragma once
// The project's version (CMake's project(VERSION), through the header it
// configures in the build folder): every program's --version and Hello.
namespace lc {

extern const char* const kVersion;  // "MAJOR.MINOR.PATCH"

}  // namespace lc
