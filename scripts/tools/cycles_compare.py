"""Our image against a Cycles reference (scripts/tools/cycles_reference.py), both linear PFMs
in the renderer's units: scale, mean and signed mean relative error, p95, the share of pixels
within 2% and 5%, silhouettes and unlit pixels left out; a side-by-side PNG and an error map.

    /usr/bin/python3 scripts/tools/cycles_compare.py OURS.pfm CYCLES.pfm
        [--minus-ours A.pfm --minus-cycles B.pfm] [--png OUT_PREFIX] [--label TEXT]

--minus-*: subtract an image from each side first (the indirect part: all bounces minus
direct). Per channel, over pixels whose Cycles value is above 1e-3 of the image's mean and
whose 3x3 neighbourhood holds no silhouette (a neighbour more than 4x brighter or darker).
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lib"))
from sweep_accuracy import read_pfm  # noqa: E402


def silhouette_free(image):
    """Pixels whose 3x3 neighbourhood's luminance stays within 4x of theirs."""
    lum = image.astype(np.float64).mean(axis=2)
    padded = np.pad(lum, 1, mode="edge")
    keep = np.ones(lum.shape, dtype=bool)
    h, w = lum.shape
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            other = padded[1 + dy:1 + dy + h, 1 + dx:1 + dx + w]
            keep &= (other <= 4.0 * lum) & (lum <= 4.0 * other)
    return keep


def compare(ours, cycles):
    """Statistics of ours / cycles over the pixels both light, silhouettes out."""
    ours = ours.astype(np.float64)
    cycles = cycles.astype(np.float64)
    lit = cycles > 1e-3 * max(cycles.mean(), 1e-30)
    mask = lit & silhouette_free(cycles)[..., None] & silhouette_free(ours)[..., None]
    ratio = ours[mask] / cycles[mask]
    error = ratio - 1.0
    return {
        "pixels": int(mask.sum()),
        "scale": float(ours[mask].sum() / cycles[mask].sum()),
        "mean": float(np.abs(error).mean()),
        "signed_mean": float(error.mean()),
        "p95": float(np.percentile(np.abs(error), 95)),
        "within_2pct": float((np.abs(error) <= 0.02).mean()),
        "within_5pct": float((np.abs(error) <= 0.05).mean()),
    }


def write_pngs(prefix, ours, cycles):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    peak = max(np.percentile(cycles, 99), 1e-30)
    side = np.concatenate([ours, cycles], axis=1) / peak
    plt.imsave(prefix + "_side_by_side.png", np.clip(side, 0, 1) ** (1 / 2.2))
    lum_o, lum_c = ours.mean(axis=2), cycles.mean(axis=2)
    error = np.where(lum_c > 0, lum_o / np.maximum(lum_c, 1e-30) - 1.0, 0.0)
    plt.imsave(prefix + "_error.png", np.clip(error, -0.05, 0.05), cmap="coolwarm", vmin=-0.05, vmax=0.05)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("ours")
    p.add_argument("cycles")
    p.add_argument("--minus-ours")
    p.add_argument("--minus-cycles")
    p.add_argument("--png", help="write PREFIX_side_by_side.png and PREFIX_error.png (+-5%%, blue: darker)")
    p.add_argument("--label", default="")
    args = p.parse_args()
    ours, cycles = read_pfm(args.ours), read_pfm(args.cycles)
    if ours.shape != cycles.shape:
        sys.exit("cycles_compare: %s is %s, %s is %s" % (args.ours, ours.shape, args.cycles, cycles.shape))
    if bool(args.minus_ours) != bool(args.minus_cycles):
        sys.exit("cycles_compare: --minus-ours and --minus-cycles go together")
    if args.minus_ours:
        ours = ours.astype(np.float64) - read_pfm(args.minus_ours)
        cycles = cycles.astype(np.float64) - read_pfm(args.minus_cycles)
    s = compare(ours, cycles)
    print("%s scale %.4f  mean %.3f%%  signed %+.3f%%  p95 %.3f%%  within 2%% %.1f%%  within 5%% %.1f%%  "
          "(%d pixel channels)" % (args.label, s["scale"], 100 * s["mean"], 100 * s["signed_mean"], 100 * s["p95"],
                                   100 * s["within_2pct"], 100 * s["within_5pct"], s["pixels"]))
    if args.png:
        write_pngs(args.png, ours, cycles)


if __name__ == "__main__":
    main()
