#pragma once
// Shows bake progress: a redrawn bar on a terminal, plain lines otherwise
// (logs, CI), each stage change and every 10% at most once.
#include <cstdio>
#include <string>

namespace lc::client {

class ProgressDisplay {
public:
    explicit ProgressDisplay(std::FILE* out);
    void update(const std::string& stage, double percent);
    // Ends the bar's line on a terminal.
    void finish();

private:
    std::FILE* out_;
    bool terminal_;
    std::string stage_;
    int last_decile_ = -1;
    bool drawn_ = false;
};

}  // namespace lc::client
