"""The sample-weighted mean of linear colour PFMs: Cycles references rendered in parts at
different seeds (scripts/tools/cycles_reference.py --seed), joined into one of their summed
samples. Rows are copied as they are stored (no flip), so the output matches its inputs.

    /usr/bin/python3 scripts/tools/pfm_mean.py -o OUT.pfm IMAGE.pfm:SAMPLES [IMAGE.pfm:SAMPLES ...]
"""
import argparse
import sys

import numpy as np


def read_rows(path):
    """(width, height, float64 pixels in stored order) of a little-endian colour PFM."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            sys.exit(path + ": not a colour PFM")
        width, height = (int(v) for v in f.readline().split())
        if float(f.readline()) >= 0:
            sys.exit(path + ": big-endian PFM; only little-endian ones are read")
        data = np.frombuffer(f.read(), dtype="<f4")
    if data.size != width * height * 3:
        sys.exit(path + ": PFM pixel data is truncated")
    return width, height, data.astype(np.float64)


def main():
    p = argparse.ArgumentParser(prog="pfm_mean.py", description=__doc__.split("\n")[0])
    p.add_argument("-o", "--output", required=True)
    p.add_argument("images", nargs="+", help="IMAGE.pfm:SAMPLES")
    args = p.parse_args()
    total, weight, size = None, 0.0, None
    for item in args.images:
        path, _, samples = item.rpartition(":")
        if not path or not samples.isdigit() or int(samples) < 1:
            sys.exit(item + ": expected IMAGE.pfm:SAMPLES with SAMPLES a positive integer")
        width, height, data = read_rows(path)
        if size not in (None, (width, height)):
            sys.exit(path + ": %dx%d, unlike the first image's %dx%d" % (width, height, *size))
        size = (width, height)
        total = data * int(samples) if total is None else total + data * int(samples)
        weight += int(samples)
    with open(args.output, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % size)
        f.write((total / weight).astype("<f4").tobytes())


if __name__ == "__main__":
    main()
