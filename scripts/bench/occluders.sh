#!/usr/bin/env bash
# Shadow rays per second before and after a change to the occluder BVH (issue
# 37): the same frames with two builds, both sides measured back to back.
#   gpu: the furnished room with LIGHTS unbounded point lights (the agglomerative
#        tree each build bakes), `render --mode lightcuts --error 0.02` at SIZE
#        with shadows and with `--shadows off`, ROUNDS rounds alternating the
#        builds; rays/s = the frame's shadow rays over (lighting_ms with shadows
#        - lighting_ms without), GPU timestamps, each the fastest of its rounds
#        (on a shared box the slower ones measure the other load).
#        The two builds' lightcuts PFMs are compared: max_abs_diff, the largest
#        difference of any channel, and differing_pixels.
#   cpu: tests/benchmarks/occluder_rays_bench (ShadowBvh::occluded through
#        light_visibility, the same rays in both builds): rays_per_s.
# Writes docs/bench/occluders.csv: side, build, metric, value.
# Usage: scripts/bench/occluders.sh BEFORE_BUILD_DIR AFTER_BUILD_DIR [lights] [size] [rounds]
# The "before" build is a checkout of the base commit (its source tree is the
# build dir's parent); occluder_rays_bench.cpp is copied into it when absent.
set -euo pipefail
cd "$(dirname "$0")/../.."
before="$(realpath "$1")"
after="$(realpath "$2")"
lights="${3:-16384}"
size="${4:-256x256}"
rounds="${5:-3}"
out=docs/bench/occluders.csv
mkdir -p docs/bench
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export LC_VALIDATION=0  # the benchmark measures the renderer, not the validation layers

bench_src=tests/benchmarks/occluder_rays_bench.cpp
before_src="$(dirname "$before")"
if [[ ! -f "$before_src/$bench_src" ]]; then
    cp "$bench_src" "$before_src/$bench_src"
    cmake "$before" >/dev/null  # the benchmarks' glob picks the copy up
fi
for build in "$before" "$after"; do
    cmake --build "$build" --target editor_client lightmass_server occluder_rays_bench -j 2 >/dev/null
done

# One scene for both builds; each build bakes its own tree (a dump carries its
# build's schema hash).
LC_CLIENT="$before/bin/editor_client"
intensity="$(python3 -c "print(819.2 / $lights)")"
"$LC_CLIENT" make-scene furnished-room -o "$work/empty.gltf" >/dev/null
"$LC_CLIENT" add-lights "$work/empty.gltf" --count "$lights" --layout random --type point \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity "$intensity" --range 0 -o "$work/scene.gltf" >/dev/null
for name in before after; do
    bin="$before/bin"
    [[ $name == after ]] && bin="$after/bin"
    "$bin/editor_client" bake "$work/scene.gltf" --spawn-server --builder agglomerative \
        -o "$work/tree.$name.lcut" >/dev/null 2>&1
done
for round in $(seq 1 "$rounds"); do
    for name in before after; do
        bin="$before/bin"
        [[ $name == after ]] && bin="$after/bin"
        for shadows in on off; do
            "$bin/editor_client" render "$work/scene.gltf" --tree "$work/tree.$name.lcut" --size "$size" \
                --mode lightcuts --error 0.02 --shadows "$shadows" -o "$work/$name.$shadows.png" \
                --float "$work/$name.$shadows.pfm" --stats "$work/$name.$shadows.$round.json" >/dev/null
        done
    done
done
for name in before after; do
    bin="$before/bin"
    [[ $name == after ]] && bin="$after/bin"
    "$bin/occluder_rays_bench" --benchmark_filter='BM_OccluderRays/0' --benchmark_repetitions=3 \
        --benchmark_report_aggregates_only=true --benchmark_out="$work/cpu.$name.json" \
        --benchmark_out_format=json >/dev/null
done

python3 - "$work" "$out" "$rounds" <<'PY'
import csv, json, struct, sys
work, out, rounds = sys.argv[1], sys.argv[2], int(sys.argv[3])

def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = f.read()
    fmt = ("<" if scale < 0 else ">") + "%df" % (3 * w * h)
    return struct.unpack(fmt, data[: 12 * w * h])

rows = []
def fastest(name, shadows):
    frames = [json.load(open("%s/%s.%s.%d.json" % (work, name, shadows, r))) for r in range(1, rounds + 1)]
    return min(frames, key=lambda j: j["lighting_ms"]), [j["lighting_ms"] for j in frames]

for name in ("before", "after"):
    (on, on_all), (off, off_all) = fastest(name, "on"), fastest(name, "off")
    shadow_ms = on["lighting_ms"] - off["lighting_ms"]
    rows += [("gpu", name, "device", on["device"]),
             ("gpu", name, "shadow_rays", on["shadow_rays"]),
             ("gpu", name, "lighting_ms_shadows", "%.1f" % on["lighting_ms"]),
             ("gpu", name, "lighting_ms_no_shadows", "%.1f" % off["lighting_ms"]),
             ("gpu", name, "lighting_ms_shadows_all_rounds", " ".join("%.0f" % x for x in on_all)),
             ("gpu", name, "lighting_ms_no_shadows_all_rounds", " ".join("%.0f" % x for x in off_all)),
             ("gpu", name, "rays_per_s", "%.4g" % (on["shadow_rays"] / (shadow_ms / 1000.0)))]
    cpu = json.load(open("%s/cpu.%s.json" % (work, name)))
    median = [b for b in cpu["benchmarks"] if b.get("aggregate_name") == "median"][0]
    rows.append(("cpu", name, "rays_per_s", "%.4g" % median["rays_per_s"]))
a, b = pfm(work + "/before.on.pfm"), pfm(work + "/after.on.pfm")
diffs = [abs(x - y) for x, y in zip(a, b)]
differing = sum(1 for i in range(0, len(diffs), 3) if max(diffs[i:i + 3]) > 0)
rows += [("image", "after", "max_abs_diff", "%.6g" % max(diffs)),
         ("image", "after", "max_value", "%.6g" % max(a)),
         ("image", "after", "differing_pixels", differing)]
get = {(s, n, m): v for s, n, m, v in rows}
for side in ("gpu", "cpu"):
    ratio = float(get[(side, "after", "rays_per_s")]) / float(get[(side, "before", "rays_per_s")])
    rows.append((side, "after/before", "rays_per_s_ratio", "%.3f" % ratio))
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["side", "build", "metric", "value"])
    w.writerows(rows)
PY
cat "$out"
