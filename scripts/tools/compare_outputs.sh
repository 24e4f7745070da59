#!/usr/bin/env bash
# Whether a restructuring changed what the programs make: runs the same
# `render`, `view` and `bake` commands with two builds' binaries on a small
# generated scene (200 lights, a tree baked by each build) and compares
# the images byte for byte, the stats JSON without its timings, the printed
# lines without their times, the exit codes, and the baked dump and recorded
# channels. Window screenshots (xvfb, panels shown) may differ only in the
# overlay's first line, the frame time (rows 19-26); the script prints the
# bounding box of the differing pixels. About 4 minutes on 2 cores.
# Usage: scripts/tools/compare_outputs.sh BEFORE_BIN_DIR AFTER_BIN_DIR [WORK_DIR]
set -uo pipefail
before=$(realpath "${1:?usage: tools/compare_outputs.sh BEFORE_BIN_DIR AFTER_BIN_DIR [WORK_DIR]}")
after=$(realpath "${2:?usage: tools/compare_outputs.sh BEFORE_BIN_DIR AFTER_BIN_DIR [WORK_DIR]}")
work=${3:-$(mktemp -d -t compare-outputs-XXXXXX)}
mkdir -p "$work" && work=$(realpath "$work")
echo "compare-outputs: work in $work"

"$before/editor_client" make-scene room -o "$work/room.gltf" >/dev/null || exit 1
"$before/editor_client" add-lights "$work/room.gltf" --count 200 --layout random --seed 3 --type mixed \
  -o "$work/lit.gltf" >/dev/null || exit 1
# Each build renders from the tree it bakes itself: a protocol change alters
# the dump's schema hash, which the other build then refuses; the trees'
# records are compared with the bakes below.
for side in before after; do
  bin=$before; [[ $side == after ]] && bin=$after
  LC_SERVER_BIN="$bin/lightmass_server" "$bin/editor_client" bake "$work/lit.gltf" --spawn-server \
    -o "$work/$side.lcut" >/dev/null || exit 1
done

renders() {  # BIN OUT SIDE (whose tree)
  local bin=$1 out=$2 size="--size 96x72" tree="--tree $work/$3.lcut"
  mkdir -p "$out"
  run() {
    local name=$1; shift
    LC_SERVER_BIN="$bin/lightmass_server" "$bin/editor_client" render "$work/lit.gltf" "$@" \
      -o "$out/$name.png" --float "$out/$name.pfm" --stats "$out/$name.json" >"$out/$name.out" 2>"$out/$name.err"
    echo "$name rc=$?" >>"$out/rc.txt"
  }
  run lightcuts $size $tree
  run reference $size
  run reference_exposure $size --exposure 1.5
  run error $size $tree --mode error
  run compare $size $tree --compare-reference --exposure 1.5 --criterion radius
  run sweep $size $tree --sweep-error 0.01,0.05
  run spp_gpu $size $tree --spp 2
  run spp_lightcuts $size $tree --spp 2 --spp-method lightcuts --threads 1
  run spp_reconstruction $size $tree --spp 2 --spp-method reconstruction --threads 1
  run realtime $size $tree --mode realtime --frames 3
  run realtime_unfiltered $size $tree --mode realtime --frames 2 --realtime-filter off
  run pixel_stride $size --mode reference --pixel-stride 2
  run tile_stride --size 64x48 --mode reference --tile-stride 2
  run cutsize $size $tree --mode cutsize
  run cutsize_heap $size $tree --mode cutsize --bound-search heap
  run cuts_shared $size $tree --mode cuts --share-cuts
  run importance $size $tree --representatives importance --representative-seed 5
  run camera_index $size $tree --camera-index 0 --shadows off
  run spawned $size --spawn-server --seed 1
  run sky $size $tree --sky 30,40,3
  run bad_tile_stride $size --mode reference --tile-stride 2
  run bad_frames $size $tree --frames 2
  run bad_sweep $size --sweep-error 0.01
  run bad_csv $size $tree --sweep-csv x.csv
  run bad_strides $size --pixel-stride 2 --tile-stride 2 --mode reference
  run bad_spp $size $tree --spp 2 --mode cuts
}

views() {  # BIN OUT SIDE
  local bin=$1 out=$2
  local view=("$bin/editor_client" view "$work/lit.gltf" --tree "$work/$3.lcut" --size 320x240)
  mkdir -p "$out"
  printf '%s\n' wait-refined "save-view $out/B1.png" "camera 1 1.5 3 0 1 0 50" wait-refined \
    "screenshot $out/B2.pfm" "mode cuts" wait-refined "save-view $out/B3.png" "error-ratio 0.05" \
    "mode lightcuts" wait-refined "save-view $out/B4.png" quit >"$out/b.script"
  xvfb-run -a "${view[@]}" --no-progressive --frames 6 --screenshot "$out/A.png" --window-screenshot "$out/Aw.png" \
    >"$out/A.log" 2>&1; echo "A rc=$?" >>"$out/rc.txt"
  xvfb-run -a "${view[@]}" --frame-budget-ms 0.5 --script "$out/b.script" --window-screenshot "$out/Bw.png" \
    >"$out/B.log" 2>&1; echo "B rc=$?" >>"$out/rc.txt"
  xvfb-run -a "${view[@]}" --mode realtime --frames 8 --screenshot "$out/C.png" --window-screenshot "$out/Cw.png" \
    >"$out/C.log" 2>&1; echo "C rc=$?" >>"$out/rc.txt"
  "${view[@]}" --headless --orbit 3 --frames 10 --screenshot "$out/D.png" >"$out/D.log" 2>&1
  echo "D rc=$?" >>"$out/rc.txt"
  xvfb-run -a "${view[@]}" --no-panels --exposure 2 --frames 5 --screenshot "$out/E.pfm" >"$out/E.log" 2>&1
  echo "E rc=$?" >>"$out/rc.txt"
}

bakes() {  # BIN OUT
  local bin=$1 out=$2
  mkdir -p "$out"
  LC_SERVER_BIN="$bin/lightmass_server" "$bin/editor_client" bake "$work/lit.gltf" --spawn-server --seed 3 \
    --record "$out/record" -o "$out/tree.lcut" >"$out/bake.out" 2>&1
  echo "bake rc=$?" >>"$out/rc.txt"
}

for side in before after; do
  bin=$before; [[ $side == after ]] && bin=$after
  renders "$bin" "$work/$side/render" "$side"
  command -v xvfb-run >/dev/null && views "$bin" "$work/$side/view" "$side"
  bakes "$bin" "$work/$side/bake"
done

/usr/bin/python3 - "$work/before" "$work/after" <<'PY'
import filecmp, json, os, re, sys
before, after = sys.argv[1], sys.argv[2]
def timing(key): return key.endswith('_ms') or 'seconds' in key
def strip(o):
    if isinstance(o, dict): return {k: strip(v) for k, v in o.items() if not timing(k)}
    if isinstance(o, list): return [strip(v) for v in o]
    return o
def text(path, root):
    t = open(path, errors='replace').read().replace(root, 'ROOT')
    t = re.sub(r'\[\d{4}-[^\]]*\]', '', t)
    t = re.sub(r'(?m)^(\s+[\d.]+)\s+[\d.]+\s+[\d.]+\s+[\d.]+x', r'\1 T T Tx', t)  # the sweep's times
    t = re.sub(r'\d+(\.\d+)? (ms|s|fps)\b', r'T \2', t)
    return re.sub(r'\d+(\.\d+)? fps', 'T fps', t)
differ = compared = 0
for folder, _, files in os.walk(before):
    rel = os.path.relpath(folder, before)
    for name in sorted(files):
        p, q = os.path.join(folder, name), os.path.join(after, rel, name)
        if name.endswith('.script'): continue
        if not os.path.exists(q): print('MISSING', rel, name); differ += 1; continue
        compared += 1
        if name.endswith('w.png'):  # window screenshots: the frame-time line may differ
            from PIL import Image
            import numpy as np
            a = np.asarray(Image.open(p)).astype(int); b = np.asarray(Image.open(q)).astype(int)
            ys, xs = np.nonzero(np.abs(a - b).sum(axis=2))
            box = f'rows {ys.min()}-{ys.max()}' if len(ys) else 'identical'
            print(f'window {rel}/{name}: {len(ys)} pixels differ, {box}')
            if len(ys) and (ys.min() < 19 or ys.max() > 26): differ += 1
            continue
        if name.endswith('.json'): same = strip(json.load(open(p))) == strip(json.load(open(q)))
        elif name.endswith(('.out', '.err', '.log')):
            # Progressive and adaptive views size their frames by the measured GPU time:
            # their logs' frame counts and sizes differ from run to run (their images do not).
            if name in ('B.log', 'D.log', 'E.log'): continue
            same = text(p, before) == text(q, after)
        else: same = filecmp.cmp(p, q, shallow=False)
        if not same: print('DIFFER', rel, name); differ += 1
print(f'compare-outputs: {compared} files compared, {differ} differ')
sys.exit(1 if differ else 0)
PY
