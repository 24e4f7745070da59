#!/usr/bin/python3
"""Checks the output of scripts/sweep_accuracy.sh (docs/ACCURACY.md).

Usage: check_sweep.py OUT_DIR [--skip-images]
  OUT_DIR holds bench/accuracy_renders.csv, bench/accuracy_bakes.csv and
  images/accuracy_*.png. Exit 0 when every check passes; otherwise exit 1 and
  print each failed check by name ("FAILED [name] ...").

The checks: the columns exist; no configuration failed; every number is finite
and in its range; the numpy error statistics agree with the client's; a smaller
error ratio (or a larger max cut) never gives a larger measured error, beyond
noise, nor a smaller cut; the cut grows sublinearly with the light count; every
tree is binary; every pairing costs at least its lower bound, and exact pairing
is not costlier than approximate pairing (beyond EXACT_PAIRING_SLACK).
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

RENDER_COLUMNS = [
    "sweep", "group", "scene", "lights", "size", "builder", "pairing", "criterion",
    "error_ratio", "max_cut_setting", "status", "note",
    "render_ms", "lighting_ms", "wall_ms", "command_ms", "render_repeats",
    "reference_status", "reference_ms", "reference_wall_ms", "speedup",
    "build_ms", "transfer_import_ms",
    "avg_cut", "cut_p99", "max_cut", "max_cut_hits", "light_evaluations",
    "rel_err_mean", "rel_err_p99", "frac_over_error", "max_err", "error_pixels", "ssim",
    "error_source", "numpy_err_mean", "numpy_err_p99",
]
# Columns a newer client fills; checked (finite, >= 0) when the CSV has them.
OPTIONAL_RENDER_COLUMNS = ["bound_search", "loop_limit_stops", "load_1min"]
BAKE_COLUMNS = [
    "sweep", "group", "scene", "lights", "builder", "pairing", "status", "note",
    "exact", "nodes", "build_ms", "upload_ms", "download_ms", "total_ms",
    "transfer_import_ms", "bake_command_ms", "pairing_cost", "pairing_lower_bound",
]
TEXT_COLUMNS = {"sweep", "group", "scene", "size", "builder", "pairing", "criterion", "status",
                "note", "reference_status", "error_source", "exact", "bound_search"}
IMAGES = ["accuracy_pareto.png", "accuracy_time_vs_lights.png", "accuracy_cut_vs_lights.png",
          "accuracy_build_vs_lights.png", "accuracy_pairing.png", "accuracy_side_by_side.png"]
# Columns every successful render must fill; the error columns too when it had a reference.
REQUIRED_RENDER = ["lights", "render_ms", "wall_ms", "avg_cut", "max_cut", "max_cut_hits",
                   "build_ms", "transfer_import_ms"]
REQUIRED_ERROR = ["reference_ms", "speedup", "rel_err_mean", "rel_err_p99", "frac_over_error",
                  "max_err", "error_pixels", "ssim"]
REQUIRED_BAKE = ["lights", "nodes", "build_ms", "upload_ms", "download_ms", "total_ms",
                 "transfer_import_ms"]
# Noise allowed in the monotonicity checks: the cut is chosen per pixel from
# bounds, not from the true error, so aggregate error can wobble a little.
ERROR_NOISE_RELATIVE = 0.10
ERROR_NOISE_ABSOLUTE = 1e-4
CUT_NOISE_RELATIVE = 0.02
CUT_NOISE_RELATIVE_AT_CAP = 0.10
CUT_NOISE_ABSOLUTE = 0.5
# pairing_cost sums the matchings of every level. Each exact level is optimal for
# its own points, but the points of the next level depend on the previous
# matching, so the exact total is not provably below the approximate one; on
# the sweep's rooms the approximate total is 0.6-4.6% higher. Exact above it by
# more than this slack means the exact matching is broken.
EXACT_PAIRING_SLACK = 0.01


class Report:
    def __init__(self):
        self.failures = defaultdict(list)
        self.checks = 0

    def check(self, name, ok, detail):
        self.checks += 1
        if not ok:
            self.failures[name].append(detail)

    def fail(self, name, detail):
        self.check(name, False, detail)


def read_csv(path, report, columns, name):
    if not os.path.exists(path):
        report.fail("files", "%s is missing" % path)
        return []
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        header = reader.fieldnames or []
        rows = list(reader)
    missing = [c for c in columns if c not in header]
    report.check("columns", not missing, "%s lacks columns: %s" % (name, ", ".join(missing)))
    for i, r in enumerate(rows):
        r["_where"] = "%s row %d (%s %s %s %s E=%s K=%s)" % (
            name, i + 2, r.get("group"), r.get("scene"), r.get("builder"),
            r.get("criterion", r.get("pairing")), r.get("error_ratio", ""),
            r.get("max_cut_setting", ""))
    return rows


def value(row, column, report=None):
    """The cell as a float; None when empty or not a finite number (a failure when
    a report is given: check_numbers reports each bad cell once)."""
    text = (row.get(column) or "").strip()
    if text == "":
        return None
    try:
        v = float(text)
    except ValueError:
        if report:
            report.fail("finite", "%s: %s = '%s' is not a number" % (row["_where"], column, text))
        return None
    if not math.isfinite(v):
        if report:
            report.fail("finite", "%s: %s = %s" % (row["_where"], column, text))
        return None
    return v


def check_numbers(rows, columns, report):
    for r in rows:
        for c in columns:
            if c not in TEXT_COLUMNS:
                value(r, c, report)


def check_status(rows, report):
    for r in rows:
        status = r.get("status", "")
        report.check("status", status in ("ok", "skipped", "failed"),
                     "%s: unknown status '%s'" % (r["_where"], status))
        report.check("no-failures", status != "failed",
                     "%s failed: %s" % (r["_where"], r.get("note", "")))
        if status == "skipped" or r.get("reference_status") == "skipped":
            report.check("skip-reason", bool(r.get("note")),
                         "%s skipped without a reason in 'note'" % r["_where"])


def check_renders(rows, report):
    for r in rows:
        if r.get("status") != "ok":
            continue
        v = {c: value(r, c) for c in RENDER_COLUMNS if c not in TEXT_COLUMNS}
        required = REQUIRED_RENDER + (REQUIRED_ERROR if r.get("reference_status") == "ok" else [])
        for c in required:
            report.check("required", v[c] is not None, "%s: %s is empty" % (r["_where"], c))
        if any(v[c] is None for c in required):
            continue
        where = r["_where"]
        report.check("range", v["render_ms"] > 0 and v["wall_ms"] > 0, "%s: times <= 0" % where)
        stops = value(r, "loop_limit_stops")
        report.check("range", stops is None or stops >= 0,
                     "%s: loop_limit_stops %s < 0" % (where, stops))
        report.check("range", 1 <= v["avg_cut"] <= v["max_cut"] + 1e-9,
                     "%s: avg cut %g outside [1, max cut %g]" % (where, v["avg_cut"], v["max_cut"]))
        report.check("range", v["max_cut"] <= v["lights"],
                     "%s: max cut %g above the light count %g" % (where, v["max_cut"], v["lights"]))
        if r.get("criterion") == "bound" and v["max_cut_setting"] is not None:
            report.check("range", v["max_cut"] <= v["max_cut_setting"],
                         "%s: max cut %g above the setting %g" % (where, v["max_cut"],
                                                                   v["max_cut_setting"]))
        if v["cut_p99"] is not None:
            report.check("range", 1 <= v["cut_p99"] <= v["max_cut"],
                         "%s: cut_p99 %g outside [1, max cut]" % (where, v["cut_p99"]))
        if r.get("reference_status") != "ok":
            continue
        report.check("range", 0 <= v["frac_over_error"] <= 1,
                     "%s: frac_over_error %g outside [0, 1]" % (where, v["frac_over_error"]))
        report.check("range", 0 <= v["rel_err_mean"] <= v["max_err"] * (1 + 1e-9) + 1e-12,
                     "%s: mean error %g outside [0, max %g]" % (where, v["rel_err_mean"],
                                                                v["max_err"]))
        report.check("range", 0 <= v["rel_err_p99"] <= v["max_err"] * (1 + 1e-9) + 1e-12,
                     "%s: p99 error %g outside [0, max %g]" % (where, v["rel_err_p99"],
                                                               v["max_err"]))
        report.check("range", -1 <= v["ssim"] <= 1 + 1e-9,
                     "%s: SSIM %g outside [-1, 1]" % (where, v["ssim"]))
        report.check("range", v["error_pixels"] > 0, "%s: no pixel measured" % where)
        # An image within 1e-4 of the reference everywhere is structurally identical.
        if v["max_err"] < 1e-4:
            report.check("ssim-identity", v["ssim"] > 0.9999,
                         "%s: max error %g but SSIM %g" % (where, v["max_err"], v["ssim"]))
        for mine, theirs in (("numpy_err_mean", "rel_err_mean"), ("numpy_err_p99", "rel_err_p99")):
            if v[mine] is not None:
                report.check("numpy-vs-client",
                             abs(v[mine] - v[theirs]) <= 1e-4 + 1e-3 * abs(v[theirs]),
                             "%s: numpy %s %g, client %s %g" % (where, mine, v[mine], theirs,
                                                               v[theirs]))


def capped(row):
    """Most of the row's measured pixels stopped at max cut."""
    pixels = float(row.get("error_pixels") or 0)
    return pixels > 0 and float(row.get("max_cut_hits") or 0) >= 0.5 * pixels


def not_larger(smaller_setting_value, larger_setting_value):
    return smaller_setting_value <= (larger_setting_value * (1 + ERROR_NOISE_RELATIVE)
                                     + ERROR_NOISE_ABSOLUTE)


def check_monotone(rows, report):
    """Bound criterion: a tighter setting refines at least as far, so errs no more."""
    usable = [r for r in rows if r.get("status") == "ok" and r.get("criterion") == "bound"
              and r.get("reference_status") == "ok" and r.get("error_ratio")
              and r.get("max_cut_setting")]
    by_max_cut = defaultdict(list)
    by_ratio = defaultdict(list)
    for r in usable:
        key = (r["group"], r["scene"], r["size"], r["builder"])
        by_max_cut[key + (float(r["max_cut_setting"]),)].append(r)
        by_ratio[key + (float(r["error_ratio"]),)].append(r)
    series = 0
    for key, sel in by_max_cut.items():
        sel.sort(key=lambda r: float(r["error_ratio"]))
        series += len(sel) > 1
        for i, a in enumerate(sel):
            for b in sel[i + 1:]:  # error_ratio(a) < error_ratio(b)
                for metric in ("rel_err_mean", "rel_err_p99"):
                    ea, eb = float(a[metric]), float(b[metric])
                    report.check("monotone-error", not_larger(ea, eb),
                                 "%s vs %s: %s %g at E=%s > %g at E=%s" % (
                                     a["_where"], b["error_ratio"], metric, ea, a["error_ratio"],
                                     eb, b["error_ratio"]))
                ca, cb = float(a["avg_cut"]), float(b["avg_cut"])
                # At the cap the cut's size is the cap's, not the ratio's: the
                # walk search bisects its threshold to a cut within about 10%
                # of max cut (bound_walk.h), so capped pairs get that slack.
                noise = CUT_NOISE_RELATIVE_AT_CAP if (capped(a) and capped(b)) else CUT_NOISE_RELATIVE
                report.check("monotone-cut",
                             ca >= cb * (1 - noise) - CUT_NOISE_ABSOLUTE,
                             "%s: avg cut %g at E=%s < %g at E=%s" % (
                                 a["_where"], ca, a["error_ratio"], cb, b["error_ratio"]))
    for key, sel in by_ratio.items():
        sel.sort(key=lambda r: -float(r["max_cut_setting"]))  # largest max cut first
        for i, a in enumerate(sel):
            for b in sel[i + 1:]:  # max_cut(a) > max_cut(b)
                for metric in ("rel_err_mean", "rel_err_p99"):
                    ea, eb = float(a[metric]), float(b[metric])
                    report.check("monotone-max-cut", not_larger(ea, eb),
                                 "%s: %s %g at max cut %s > %g at max cut %s" % (
                                     a["_where"], metric, ea, a["max_cut_setting"], eb,
                                     b["max_cut_setting"]))
    report.check("monotone-error", series > 0,
                 "no error-ratio series with two or more measured rows to check")


def loglog_slope(xs, ys):
    n = len(xs)
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((x - mx) ** 2 for x in lx)
    return sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sxx


def check_sublinear(rows, report):
    sel = defaultdict(dict)
    for r in rows:
        if r.get("group") == "lights" and r.get("status") == "ok" and r.get("avg_cut"):
            sel[r["builder"]][float(r["lights"])] = float(r["avg_cut"])
    report.check("sublinear-cut", bool(sel), "no rows of the 'lights' group")
    for builder, points in sel.items():
        if len(points) < 3:
            report.fail("sublinear-cut", "%s: only %d light counts" % (builder, len(points)))
            continue
        xs = sorted(points)
        slope = loglog_slope(xs, [points[x] for x in xs])
        report.check("sublinear-cut", slope < 1.0,
                     "%s: average cut grows as lights^%.3f (not sublinear)" % (builder, slope))


def check_bakes(rows, report):
    exact_cost, approximate_cost = {}, {}
    for r in rows:
        if r.get("status") != "ok":
            continue
        v = {c: value(r, c) for c in BAKE_COLUMNS if c not in TEXT_COLUMNS}
        if any(v[c] is None for c in REQUIRED_BAKE):
            report.fail("required", "%s: a time or count is empty" % r["_where"])
            continue
        where = r["_where"]
        report.check("binary-tree", v["nodes"] == 2 * v["lights"] - 1,
                     "%s: %g nodes for %g lights (a binary tree has 2n-1)" % (
                         where, v["nodes"], v["lights"]))
        report.check("range", v["build_ms"] >= 0 and v["transfer_import_ms"] >= 0,
                     "%s: negative time" % where)
        if r.get("builder") != "optimal-pair":
            continue
        cost, bound = v["pairing_cost"], v["pairing_lower_bound"]
        if cost is None or bound is None:
            report.fail("required", "%s: optimal-pair without pairing cost" % where)
            continue
        report.check("pairing-bound", cost >= bound * (1 - 1e-9) - 1e-9,
                     "%s: pairing cost %g below its lower bound %g" % (where, cost, bound))
        if r.get("pairing") == "exact":
            report.check("pairing-exact", r.get("exact") == "true",
                         "%s: exact pairing not reported exact" % where)
            exact_cost[r["scene"]] = (cost, where)
        elif r.get("pairing") == "approximate":
            approximate_cost[r["scene"]] = (cost, where)
    for scene, (cost, where) in exact_cost.items():
        if scene in approximate_cost:
            other, _ = approximate_cost[scene]
            report.check("pairing-exact", cost <= other * (1 + EXACT_PAIRING_SLACK),
                         "%s: exact pairing cost %g above the approximate %g" % (where, cost,
                                                                                 other))


def check_groups(renders, bakes, report):
    for group, rows in (("pareto", renders), ("lights", renders), ("pairing", bakes)):
        report.check("groups", any(r.get("group") == group and r.get("status") == "ok"
                                   for r in rows), "no successful row in group '%s'" % group)


def check_images(out_dir, report):
    for name in IMAGES:
        path = os.path.join(out_dir, "images", name)
        ok = os.path.exists(path) and os.path.getsize(path) > 1000
        if ok:
            with open(path, "rb") as f:
                ok = f.read(8) == b"\x89PNG\r\n\x1a\n"
        report.check("images", ok, "%s is missing or not a PNG" % path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir")
    parser.add_argument("--skip-images", action="store_true")
    args = parser.parse_args()
    report = Report()
    renders = read_csv(os.path.join(args.out_dir, "bench", "accuracy_renders.csv"), report,
                       RENDER_COLUMNS, "accuracy_renders.csv")
    bakes = read_csv(os.path.join(args.out_dir, "bench", "accuracy_bakes.csv"), report,
                     BAKE_COLUMNS, "accuracy_bakes.csv")
    if not report.failures:
        check_numbers(renders, RENDER_COLUMNS + OPTIONAL_RENDER_COLUMNS, report)
        check_numbers(bakes, BAKE_COLUMNS, report)
        check_status(renders + bakes, report)
        check_groups(renders, bakes, report)
        check_renders(renders, report)
        check_monotone(renders, report)
        check_sublinear(renders, report)
        check_bakes(bakes, report)
    if not args.skip_images:
        check_images(args.out_dir, report)
    if report.failures:
        for name, details in report.failures.items():
            for d in details[:10]:
                print("FAILED [%s] %s" % (name, d))
            if len(details) > 10:
                print("FAILED [%s] ... and %d more" % (name, len(details) - 10))
        print("check_sweep: %d of %d checks failed (%s)" % (
            sum(len(d) for d in report.failures.values()), report.checks,
            ", ".join(report.failures)))
        sys.exit(1)
    print("check_sweep: OK, %d checks on %d render rows and %d bake rows" % (
        report.checks, len(renders), len(bakes)))


if __name__ == "__main__":
    main()
