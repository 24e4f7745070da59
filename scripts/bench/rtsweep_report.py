#!/usr/bin/env python3
"""The real-time sweep's report (scripts/bench/realtime_modes.sh): from each
scene's rtsweep_SCENE.csv and rtsweep_SCENE_equal.csv (render --sweep-realtime
--sweep-csv) writes OUT/rtsweep.md, a table per scene with the winner at
equal time, and OUT/rtsweep_SCENE.png (relative MSE against GPU time for the
still view, and per frame along the orbit) where matplotlib is installed.

Usage: rtsweep_report.py OUT SCENE... [--command TEXT]"""
import argparse
import csv
import math
import os
import sys


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def number(text):
    value = float(text)
    return value if math.isfinite(value) else None


def fmt(value, spec):
    return "n/a" if value is None else format(value, spec)


def winner(summary, column):
    scored = [(number(r[column]), r["variant"]) for r in summary if number(r[column]) is not None]
    return min(scored)[1] if scored else "none"


def scene_table(scene, rows, summary):
    still = [r for r in rows if r["camera"] == "still"]
    counts = sorted({int(r["frames"]) for r in still})
    first, last = counts[0], counts[-1]
    baseline = summary[0]
    lines = [f"### {scene}: {rows[0]['lights']} lights, reference {float(rows[0]['reference_ms']) / 1000:.1f} s GPU",
             "",
             f"Equal time: each variant's still-view error after the {float(baseline['budget_ms']):.0f} ms and "
             f"{float(baseline['budget_rays']):.0f} shadow rays a pixel that {baseline['baseline']} (the cheapest "
             f"frame) spent over {last} frames. Moving: means over the orbit's frames.",
             "",
             f"| variant | ms/frame | rays/px | rel MSE @{first} | @{last} | err mean @{last} | p99 @{last} "
             f"| within 2% @{last} | MSE equal time | MSE equal rays | moving ms | moving MSE | moving MSE equal time |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in summary:
        mine = [r for r in still if r["variant"] == s["variant"]]
        at = {int(r["frames"]): r for r in mine}
        lines.append("| %s | %.1f | %.1f | %.3g | %.3g | %.4f | %.4f | %.1f%% | %s | %s | %s | %s | %s |" % (
            s["variant"], float(s["frame_ms"]), float(at[last]["shadow_rays_per_pixel"]),
            float(at[first]["rel_mse"]), float(at[last]["rel_mse"]), float(at[last]["rel_err_mean"]),
            float(at[last]["rel_err_p99"]), 100.0 * float(at[last]["within_2pct"]),
            fmt(number(s["equal_time_rel_mse"]), ".3g"), fmt(number(s["equal_rays_rel_mse"]), ".3g"),
            fmt(number(s["path_frame_ms"]), ".1f"), fmt(number(s["path_rel_mse"]), ".3g"),
            fmt(number(s["path_equal_time_rel_mse"]), ".3g")))
    lines += ["", f"Winner at equal time (still): **{winner(summary, 'equal_time_rel_mse')}**; "
              f"moving: **{winner(summary, 'path_equal_time_rel_mse')}**.", ""]
    return lines


def plot(scene, rows, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    fig, (still_ax, moving_ax) = plt.subplots(1, 2, figsize=(11, 4.2))
    for variant in dict.fromkeys(r["variant"] for r in rows):
        still = [r for r in rows if r["variant"] == variant and r["camera"] == "still"]
        moving = [r for r in rows if r["variant"] == variant and r["camera"] == "moving"]
        still_ax.plot([float(r["total_ms"]) for r in still], [float(r["rel_mse"]) for r in still], "o-",
                      label=variant)
        moving_ax.plot([int(r["frames"]) for r in moving], [float(r["rel_mse"]) for r in moving], ".-",
                       label=variant)
    still_ax.set(xscale="log", yscale="log", xlabel="GPU ms, all frames", ylabel="relative MSE",
                 title=f"{scene}: still camera, frames accumulated")
    moving_ax.set(yscale="log", xlabel="frame of the orbit", ylabel="relative MSE",
                  title=f"{scene}: moving camera")
    still_ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return True


def kept_notes(report):
    """The hand-written '## Notes' section of an earlier report, from its heading on."""
    if not os.path.exists(report):
        return []
    with open(report) as f:
        old = f.read().splitlines()
    return ["", *old[old.index("## Notes"):]] if "## Notes" in old else []


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("scenes", nargs="+")
    parser.add_argument("--command", default="scripts/bench/realtime_modes.sh")
    args = parser.parse_args()
    lines = ["# Real-time modes side by side (issue 38, part 2)", "",
             f"Made by `{args.command}`; lavapipe (llvmpipe), one run, GPU timestamps.", ""]
    plotted = []
    for scene in args.scenes:
        rows = read(os.path.join(args.out, f"rtsweep_{scene}.csv"))
        summary = read(os.path.join(args.out, f"rtsweep_{scene}_equal.csv"))
        lines += scene_table(scene, rows, summary)
        if plot(scene, rows, os.path.join(args.out, f"rtsweep_{scene}.png")):
            plotted.append(f"rtsweep_{scene}.png")
    lines.append("Plots: " + (", ".join(plotted) if plotted else "none (python3 without matplotlib here; "
                                                               "scripts/install_deps.sh installs it)") + ".")
    report = os.path.join(args.out, "rtsweep.md")
    lines += kept_notes(report)
    with open(report, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
