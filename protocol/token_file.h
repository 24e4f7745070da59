#pragma once
// The shared secret of a server that listens off loopback, read from a file by
// both programs with one rule, so a token file authenticates on both sides or
// on neither.
#include <filesystem>
#include <string>

#include "lightcuts/result.h"

namespace lc {

// The shortest token accepted: a guessable secret is refused where it is read.
inline constexpr size_t kMinTokenLength = 16;
// A token file is one line; longer files are refused rather than cut.
inline constexpr size_t kMaxTokenFileBytes = 4096;

// The file's first line with the white space around it removed. Refuses a
// missing file, an empty token, one under kMinTokenLength characters and a
// file over kMaxTokenFileBytes, each naming the file.
Result<std::string> read_token_file(const std::filesystem::path& path);

}  // namespace lc
