"""Plots docs/bench/environment_sampling.csv (scripts/bench/environment.sh) as
docs/bench/environment_sampling.png: sampling and build time against lights."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

source = sys.argv[1] if len(sys.argv) > 1 else "docs/bench/environment_sampling.csv"
rows = list(csv.DictReader(open(source)))
fig, ax = plt.subplots(figsize=(6, 4))
for name in sorted({r["source"] for r in rows}):
    sampled = {}
    for r in rows:
        if r["source"] == name:
            sampled[int(r["lights"])] = float(r["sample_ms"])
    counts = sorted(sampled)
    ax.plot(counts, [sampled[c] for c in counts], "o-", label=f"{name}: sampling")
    for builder, style in (("lbvh", "s--"), ("agglomerative", "^:")):
        pts = [(int(r["lights"]), float(r["build_ms"])) for r in rows if r["source"] == name and r["builder"] == builder]
        if pts:
            ax.plot(*zip(*pts), style, label=f"{name}: {builder} build")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("environment lights")
ax.set_ylabel("ms (2 cores)")
ax.legend(fontsize=7)
ax.grid(True, which="both", alpha=0.3)
fig.tight_layout()
fig.savefig(source.replace(".csv", ".png"), dpi=100)
