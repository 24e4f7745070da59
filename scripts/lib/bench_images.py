"""What the render benchmarks' reports share (scripts/bench/speedup_report.py,
scripts/bench/supersampling_report.py): an image's error columns against a reference
(sweep_accuracy.py's error_stats: error_stats.cpp's definition), and the CSV."""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sweep_accuracy import error_stats, read_pfm  # noqa: E402,F401


def strided_pixels(image, stride=1, tile=1):
    """The pixels of a full image that a strided reference holds, as its image.

    --pixel-stride K (tile 1): every K-th pixel in x and y, the first of each K.
    --tile-stride K (tile 8): the middle tile of every KxK block of tiles, the
    tiles side by side (pixel_stride.h's strided_tiles and gather_tiles)."""
    if tile == 1:
        return image[::stride, ::stride]
    height, width = image.shape[:2]
    rows = [y for y in range(height) if (y // tile) % stride == stride // 2]
    columns = [x for x in range(width) if (x // tile) % stride == stride // 2]
    return image[rows][:, columns]


def error_columns(pfm_path, reference, geometry_pixels, stride=1, tile=1):
    """Mean, p99 and largest relative error, and the share of lit pixels within 2%.

    A strided reference (strided_pixels) holds some of the pixels only: the
    image is measured at those."""
    e = error_stats(strided_pixels(read_pfm(pfm_path), stride, tile), reference, geometry_pixels,
                    0.02)
    return {"rel_err_mean": round(e["rel_err_mean"], 5), "rel_err_p99": round(e["rel_err_p99"], 5),
            "within_2pct": round(1.0 - e["frac_over_error"], 5), "max_err": round(e["max_err"], 4)}


def write_rows(path, columns, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for row in rows:
            w.writerow(row)
