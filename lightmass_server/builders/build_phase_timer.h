#pragma once
// Wall-clock time per step of a tree build, summed over the step's repeats
// (the agglomerative rounds), into BuildReport::phases: the profile that
// tree_build_bench prints and docs/BENCHMARKS.md quotes.
#include <chrono>
#include <string_view>

#include "lightmass_server/builders/tree_builder.h"

namespace lc::bake {

class BuildPhaseTimer {
public:
    explicit BuildPhaseTimer(BuildReport& report)
        : report_(report), last_(std::chrono::steady_clock::now()) {}

    // Adds the time since the previous lap (or construction) to phase `name`.
    void lap(std::string_view name) {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
        last_ = now;
        for (BuildPhase& phase : report_.phases) {
            if (phase.name == name) {
                phase.ms += ms;
                return;
            }
        }
        report_.phases.push_back(BuildPhase{std::string(name), ms});
    }

    // Starts the next lap now: the time since the last one is some other timer's.
    void skip() { last_ = std::chrono::steady_clock::now(); }

private:
    BuildReport& report_;
    std::chrono::steady_clock::time_point last_;
};

}  // namespace lc::bake
