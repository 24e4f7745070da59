#!/usr/bin/python3
"""Errors of ReSTIR and real-time frames against the reference (scripts/bench/restir.sh).

Usage: restir_report.py WORK_DIR REFERENCE_PFM OUT_CSV TAG...
Each TAG has WORK_DIR/TAG.pfm (the image) and WORK_DIR/TAG.json (render --stats).
Per row: GPU ms per frame (lighting included), shadow rays per lit pixel, the
relative MSE over lit pixels (sum of squared errors over the sum of squared
reference values) and the mean relative error per pixel (|a - r| / r over
channels' sums, pixels with r > 0). Plain Python: no numpy on the bench box.
"""
import json
import struct
import sys


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        count = width * height * channels
        fmt = ("<" if scale < 0 else ">") + "%df" % count
        return struct.unpack(fmt, f.read(4 * count)), channels


def errors(image, reference, channels):
    squared = energy = relative = 0.0
    pixels = 0
    for i in range(0, len(reference), channels):
        r = reference[i:i + channels]
        a = image[i:i + channels]
        total = sum(r)
        if total <= 0.0:
            continue
        squared += sum((x - y) ** 2 for x, y in zip(a, r))
        energy += sum(y * y for y in r)
        relative += abs(sum(a) - total) / total
        pixels += 1
    return squared / energy if energy > 0 else 0.0, relative / pixels if pixels else 0.0


def main():
    work, reference_path, out_csv, tags = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    reference, channels = read_pfm(reference_path)
    rows = ["tag,gpu_ms,rays_per_pixel,relative_mse,mean_relative_error"]
    for tag in tags:
        image, _ = read_pfm(f"{work}/{tag}.pfm")
        with open(f"{work}/{tag}.json") as f:
            stats = json.load(f)
        lit = max(stats.get("geometry_pixels", 1), 1)
        frames = max(stats.get("realtime_frames", 1), 1)
        rays = stats.get("shadow_rays", 0) / lit
        mse, mean = errors(image, reference, channels)
        rows.append(f"{tag},{stats.get('render_ms', 0.0):.3f},{rays:.2f},{mse:.5g},{mean:.4f}")
        print(rows[-1], flush=True)
    with open(out_csv, "w") as f:
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
