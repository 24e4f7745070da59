#!/usr/bin/env bash
# Builds the fuzz preset (clang, -fsanitize=fuzzer,address,undefined) and runs
# the libFuzzer targets of tests/fuzz/, one after the other.
#   scripts/fuzz.sh                      every target, 60 seconds each
#   scripts/fuzz.sh --seconds 600        every target, 10 minutes each
#   scripts/fuzz.sh --runs 1000000 geometry_channel_fuzz environment_channel_fuzz
#   scripts/fuzz.sh --seed 7             libFuzzer's random seed (default 1: runs repeat)
# With --runs and --seconds, a target stops at whichever comes first.
# Every target has seeds: a target named here without seeds is an error.
# Corpora grow in build-fuzz/corpus/TARGET; seeds are build-fuzz/seeds (written
# from tests/data at build time), tests/data itself and tests/fuzz/regressions/
# TARGET (the reproducers of fixed findings). A finding is saved in
# build-fuzz/artifacts/TARGET/ and makes the script exit non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=""
runs=""
seed=1
targets=()
while [ $# -gt 0 ]; do
    case "$1" in
        --seconds) seconds="$2"; shift 2 ;;
        --runs) runs="$2"; shift 2 ;;
        --seed) seed="$2"; shift 2 ;;
        -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
        -*) echo "unknown option $1" >&2; exit 2 ;;
        *) targets+=("$1"); shift ;;
    esac
done
if [ -z "$seconds" ] && [ -z "$runs" ]; then seconds=60; fi
all=(frame_decoder_fuzz message_fuzz scene_channel_fuzz result_channel_fuzz geometry_channel_fuzz
     environment_channel_fuzz dump_fuzz gltf_loader_fuzz)
if [ ${#targets[@]} -eq 0 ]; then targets=("${all[@]}"); fi

cmake --preset fuzz >/dev/null
cmake --build build-fuzz -j "$(nproc)" >/dev/null

build=build-fuzz
data=tests/data
seeds_of() {
    case "$1" in
        frame_decoder_fuzz) echo "$build/seeds/frames" ;;
        message_fuzz) echo "$build/seeds/messages" ;;
        scene_channel_fuzz) echo "$build/seeds/scene" ;;
        result_channel_fuzz) echo "$build/seeds/result" ;;
        geometry_channel_fuzz) echo "$build/seeds/geometry" ;;
        environment_channel_fuzz) echo "$build/seeds/environment" ;;
        dump_fuzz) ls -d "$data"/replay/*/server "$data"/replay/*/client ;;
        gltf_loader_fuzz) echo "$data/broken_gltf" ;;
        *) echo "unknown target $1" >&2; return 1 ;;
    esac
}

# Inputs no longer than a target needs keep its executions fast.
max_len_of() {
    case "$1" in
        frame_decoder_fuzz) echo 2048 ;;
        message_fuzz) echo 4096 ;;
        *) echo 65536 ;;
    esac
}

status=0
printf '%-22s %12s %8s %s\n' target executions seconds result
for target in "${targets[@]}"; do
    mkdir -p "$build/corpus/$target" "$build/artifacts/$target" "$build/logs"
    # shellcheck disable=SC2207
    seed_dirs=($(seeds_of "$target"))
    for dir in "${seed_dirs[@]}"; do
        if [ -z "$(ls -A "$dir" 2>/dev/null)" ]; then
            echo "$target: its seed folder $dir is missing or empty" >&2
            exit 2
        fi
    done
    if [ -d "tests/fuzz/regressions/$target" ]; then seed_dirs+=("tests/fuzz/regressions/$target"); fi
    limits=(-seed="$seed")
    if [ -n "$runs" ]; then limits+=("-runs=$runs"); fi
    if [ -n "$seconds" ]; then limits+=("-max_total_time=$seconds"); fi
    log="$build/logs/$target.log"
    result=ok
    if ! "$build/bin/$target" "${limits[@]}" -max_len="$(max_len_of "$target")" -timeout=20 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$build/artifacts/$target/" \
        "$build/corpus/$target" "${seed_dirs[@]}" >"$log" 2>&1; then
        result="FINDING (see $log and $build/artifacts/$target/)"
        status=1
    fi
    executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    elapsed=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
    printf '%-22s %12s %8s %s\n' "$target" "${executions:-?}" "${elapsed:-?}" "$result"
done
exit $status
