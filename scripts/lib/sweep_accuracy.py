#!/usr/bin/python3
"""Accuracy/time sweep of the Lightcuts renderer (issue #5).

Runs the real programs (editor_client add-lights / bake / render, which spawns
lightmass_server) over named scenes and writes, into OUT/bench and OUT/images:

  accuracy_renders.csv  one row per render configuration (times, cut sizes, errors, SSIM)
  accuracy_bakes.csv    one row per bake (build, transfer and import times, pairing cost)
  accuracy_runinfo.csv  machine, device, command line, runtime
  accuracy_*.png        the figures of docs/ACCURACY.md

Groups (--only picks some; rows of the other groups are kept from an earlier run):
  pareto   one generated room, every builder x criterion x error ratio x max cut
  lights   generated rooms of 2^8 .. 2^17 (and 2^20 in full mode) unbounded point lights
  pairing  optimal-pair with exact and approximate pairing on the same rooms
  shared   the shared scenes (cornell_box with generated lights, LightsPunctualLamp)
  figure   one scene side by side: reference, lightcuts, error and cut-size heatmaps

Error columns come from the client's own comparison (render --compare-reference,
editor_client/render/analysis/error_stats.h) when the reference is cheap; otherwise they
are computed here from the float images with the same definition (the column
error_source says which). When both exist, the numpy values are kept too
(numpy_err_mean, numpy_err_p99) so the checker can hold one against the other.
SSIM is always computed here (see ssim() below).

Usage: sweep_accuracy.py --build-dir DIR (--quick | --full) --out-dir OUT [--only G,...]
"""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field

import numpy as np

ERROR_RATIOS = [0.005, 0.01, 0.02, 0.05, 0.1, 0.2]
BUILDERS = ["optimal-pair", "agglomerative", "lbvh"]
GROUPS = ["pareto", "lights", "pairing", "shared", "figure"]
# Light evaluations per second of lavapipe on this machine (docs/BENCHMARKS.md);
# used only to decide whether a reference is affordable before running it.
LAVAPIPE_EVALS_PER_S = 2e8
REFERENCE_BUDGET_S = 60.0
# Renders faster than this are timed again (Sweep.timed).
RETIME_BELOW_MS = 5000.0
# Below this reference time the client's --compare-reference is cheap enough
# to run with every lightcuts render; above it the errors are computed here.
CLIENT_COMPARE_BELOW_MS = 1500.0
NEGLIGIBLE_FRACTION = 1e-3  # error_stats.h kNegligibleFraction
DEFAULT_MAX_CUT = 1000      # cpu_evaluator.h kDefaultMaxCut
LUMA = (0.2126, 0.7152, 0.0722)
CORNELL_CAMERA = "278,273,-800,278,273,0,39"  # looks in through the open side

RENDER_COLUMNS = [
    "sweep", "group", "scene", "lights", "size", "builder", "pairing", "criterion",
    "error_ratio", "max_cut_setting", "status", "note",
    "render_ms", "lighting_ms", "wall_ms", "command_ms", "render_repeats",
    "reference_status", "reference_ms", "reference_wall_ms", "speedup",
    "build_ms", "transfer_import_ms",
    "avg_cut", "cut_p99", "max_cut", "max_cut_hits", "light_evaluations",
    "rel_err_mean", "rel_err_p99", "frac_over_error", "max_err", "error_pixels", "ssim",
    "error_source", "numpy_err_mean", "numpy_err_p99",
    # Written by newer clients only (empty otherwise).
    "bound_search", "loop_limit_stops",
    # 1-minute load average when the row was measured: other jobs on the machine.
    "load_1min",
]
BAKE_COLUMNS = [
    "sweep", "group", "scene", "lights", "builder", "pairing", "status", "note",
    "exact", "nodes", "build_ms", "upload_ms", "download_ms", "total_ms",
    "transfer_import_ms", "bake_command_ms", "pairing_cost", "pairing_lower_bound",
]


@dataclass
class Plan:
    """How much of each group a sweep mode runs."""
    name: str
    pareto_lights: int
    pareto_size: int
    pareto_max_cuts: dict  # builder -> max-cut settings swept over every error ratio
    light_counts: list
    lights_size: int
    pairing_counts: list
    figure_size: int
    shared_size: int
    shared_lights: int = 1024


QUICK = Plan(
    name="quick", pareto_lights=1024, pareto_size=64,
    pareto_max_cuts={"optimal-pair": [1000], "agglomerative": [100, 1000], "lbvh": [1000]},
    light_counts=[2**8, 2**10, 2**12, 2**14, 2**16], lights_size=64,
    pairing_counts=[2**8, 2**10, 2**12], figure_size=96, shared_size=64)
FULL = Plan(
    name="full", pareto_lights=4096, pareto_size=128,
    pareto_max_cuts={b: [64, 256, 1000] for b in BUILDERS},
    light_counts=[2**k for k in range(8, 18)] + [2**20], lights_size=128,
    pairing_counts=[2**k for k in range(8, 17)], figure_size=256, shared_size=128)


# ---------------------------------------------------------------------------
# Running the programs

class ProgramError(Exception):
    pass


class Runner:
    """Runs editor_client with validation off and logs every command line."""

    def __init__(self, build_dir, work_dir, log_path):
        self.client = os.path.join(build_dir, "bin", "editor_client")
        self.work = work_dir
        self.log = open(log_path, "a", encoding="utf-8")
        self.env = dict(os.environ, LC_VALIDATION="0")

    def run(self, args, timeout=900):
        cmd = [self.client] + [str(a) for a in args]
        self.log.write("$ LC_VALIDATION=0 " + " ".join(cmd) + "\n")
        self.log.flush()
        start = time.monotonic()
        try:
            proc = subprocess.run(cmd, env=self.env, capture_output=True, text=True,
                                  timeout=timeout)
        except subprocess.TimeoutExpired:
            raise ProgramError("timed out after %d s" % timeout)
        elapsed_ms = (time.monotonic() - start) * 1000.0
        self.log.write(proc.stdout[-4000:] + proc.stderr[-4000:] + "\n")
        if proc.returncode != 0:
            lines = [l for l in proc.stderr.splitlines() if l.startswith("error")]
            message = lines[-1] if lines else (proc.stderr.strip().splitlines() or ["?"])[-1]
            raise ProgramError("exit %d: %s" % (proc.returncode, message))
        return proc.stdout, elapsed_ms

    def path(self, name):
        return os.path.join(self.work, name)


def say(text):
    print("sweep: " + text, flush=True)


# ---------------------------------------------------------------------------
# Images: PFM, tone curve, error statistics, SSIM

def read_pfm(path):
    """Colour PFM (as image_io.cpp writes it) -> H x W x 3 float32, top row first."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            raise ProgramError(path + ": not a colour PFM")
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    if data.size != width * height * 3:
        raise ProgramError(path + ": PFM pixel data is truncated")
    return data.reshape(height, width, 3)[::-1]


def luminance(rgb):
    rgb = rgb.astype(np.float64)
    return LUMA[0] * rgb[..., 0] + LUMA[1] * rgb[..., 1] + LUMA[2] * rgb[..., 2]


def error_stats(lightcuts, reference, geometry_pixels, error_ratio):
    """error_stats.cpp's statistics from float images.

    The PFM has no alpha, so the geometry mask is recovered from the reference's
    geometry_pixels count: background pixels are black, add nothing to the mean,
    and never pass the negligible-luminance threshold.
    """
    y_ref = luminance(reference)
    y = luminance(lightcuts)
    mean = y_ref[np.isfinite(y_ref)].sum() / max(geometry_pixels, 1)
    measured = np.isfinite(y_ref) & (y_ref > NEGLIGIBLE_FRACTION * mean)
    if not measured.any():
        return None
    e = np.where(np.isfinite(y[measured]),
                 np.abs(y[measured] - y_ref[measured]) / y_ref[measured], 1e30)
    rank = min(max(int(math.ceil(0.99 * e.size)), 1), e.size) - 1  # nearest rank
    return {
        "rel_err_mean": float(e.mean()),
        "rel_err_p99": float(np.partition(e, rank)[rank]),
        # The client compares against the float32 setting.
        "frac_over_error": float((e > float(np.float32(error_ratio))).mean()),
        "max_err": float(e.max()),
        "error_pixels": int(e.size),
    }


def display_luma(rgb, exposure):
    """tone_mapping.h: exposure, ACES filmic fit, sRGB encoding; then Rec. 709 luma."""
    x = np.maximum(np.nan_to_num(rgb.astype(np.float64), nan=0.0, posinf=0.0) * exposure, 0.0)
    film = np.clip((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)
    srgb = np.where(film <= 0.0031308, 12.92 * film, 1.055 * np.power(film, 1.0 / 2.4) - 0.055)
    return LUMA[0] * srgb[..., 0] + LUMA[1] * srgb[..., 1] + LUMA[2] * srgb[..., 2]


def gaussian_window(sigma=1.5, radius=5):
    x = np.arange(-radius, radius + 1, dtype=np.float64)
    w = np.exp(-x * x / (2.0 * sigma * sigma))
    return w / w.sum()


def filter_valid(image, window):
    """Separable filter over the positions where the whole window fits."""
    n = window.size
    rows = np.lib.stride_tricks.sliding_window_view(image, n, axis=1) @ window
    return np.lib.stride_tricks.sliding_window_view(rows, n, axis=0) @ window


def ssim(a, b, data_range=1.0):
    """Mean SSIM (Wang et al. 2004): 11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03.

    a, b: 2-D arrays of display luma in [0, 1]. Only windows that fit inside
    the image count (no padding).
    """
    if min(a.shape) < 11:
        return float("nan")
    w = gaussian_window()
    c1 = (0.01 * data_range) ** 2
    c2 = (0.03 * data_range) ** 2
    mu_a, mu_b = filter_valid(a, w), filter_valid(b, w)
    var_a = filter_valid(a * a, w) - mu_a * mu_a
    var_b = filter_valid(b * b, w) - mu_b * mu_b
    cov = filter_valid(a * b, w) - mu_a * mu_b
    s = ((2 * mu_a * mu_b + c1) * (2 * cov + c2)) / (
        (mu_a ** 2 + mu_b ** 2 + c1) * (var_a + var_b + c2))
    return float(s.mean())


# ---------------------------------------------------------------------------
# Scenes, bakes, renders

@dataclass
class Scene:
    name: str
    path: str
    lights: int
    camera: list = field(default_factory=lambda: ["--camera-index", "0"])
    # glTF loading flags for bake and render (a scene written beside the shared
    # one's buffers points back into ../shared: --allow-external-resources).
    load: list = field(default_factory=list)


def room_points(runner, count, seed=1):
    """The bench-bound room: unbounded point lights, total intensity fixed (819 cd)."""
    name = "room_points_%d" % count
    path = runner.path(name + ".gltf")
    if not os.path.exists(path):
        runner.run(["add-lights", "--count", count, "--layout", "random", "--seed", seed,
                    "--type", "point", "--intensity", "%.6g" % (0.05 * 16384 / count),
                    "--range", 0, "-o", path])
    return Scene(name, path, count)


def room_mixed(runner, count):
    """The demo room scaled to COUNT lights: 3/4 point, 1/4 spot, with ranges.

    Intensity scales with 1/count and range with count^(-1/3), so the total
    power and the number of lights reaching a point stay those of the demo.
    """
    name = "room_mixed_%d" % count
    path = runner.path(name + ".gltf")
    if not os.path.exists(path):
        scale = 1024.0 / count
        points = runner.path(name + "_points.gltf")
        runner.run(["add-lights", "--count", count * 3 // 4, "--layout", "random", "--seed", 7,
                    "--type", "point", "--intensity", "%.6g" % (0.4 * scale),
                    "--range", "%.6g" % (2.5 * scale ** (1 / 3)), "-o", points])
        runner.run(["add-lights", points, "--count", count // 4, "--layout", "random",
                    "--seed", 8, "--type", "spot", "--intensity", "%.6g" % (1.5 * scale),
                    "--range", "%.6g" % (3.5 * scale ** (1 / 3)), "-o", path])
    return Scene(name, path, count)


def cornell_scene(runner, shared_dir, count):
    source = os.path.join(shared_dir, "cornell_box", "cornell_box.gltf")
    if not os.path.exists(source):
        return None
    name = "cornell_box_%d" % count
    path = runner.path(name + ".gltf")
    if not os.path.exists(path):
        # Unbounded point lights under the ceiling (millimetre units); cornell_box has none.
        runner.run(["add-lights", source, "--count", count, "--layout", "random", "--seed", 3,
                    "--type", "point", "--intensity", "%.6g" % (30.0 * 1024 / count),
                    "--range", 0, "--box", "120,480,120,440,530,440", "-o", path])
    return Scene(name, path, count, ["--camera", CORNELL_CAMERA], ["--allow-external-resources"])


def lamp_scene(runner, shared_dir):
    """The lamp's five punctual lights. Its bulb is emissive, and a bake would sample
    that into area lights of the tree; the sweep measures the punctual-light tree (area
    lights have their own benchmark, scripts/bench/area_lights.sh), so it bakes and
    renders a copy whose materials emit nothing, its resources read from ../shared."""
    source = os.path.join(shared_dir, "LightsPunctualLamp", "LightsPunctualLamp.gltf")
    if not os.path.exists(source):
        return None
    with open(source, encoding="utf-8") as f:
        gltf = json.load(f)
    lights = len(gltf.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", []))
    path = runner.path("LightsPunctualLamp_no_emission.gltf")
    here, there = os.path.dirname(os.path.abspath(path)), os.path.dirname(os.path.abspath(source))
    for material in gltf.get("materials", []):
        material.pop("emissiveFactor", None)
        material.pop("emissiveTexture", None)
        material.get("extensions", {}).pop("KHR_materials_emissive_strength", None)
    for resource in gltf.get("buffers", []) + gltf.get("images", []):
        if "uri" in resource and not resource["uri"].startswith("data:"):
            resource["uri"] = os.path.relpath(os.path.join(there, resource["uri"]), here)
    with open(path, "w", encoding="utf-8") as f:
        json.dump(gltf, f)
    return Scene("LightsPunctualLamp", path, lights, [], ["--allow-external-resources"])


def fmt(value):
    if value is None or value == "":
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return "%.6g" % value
    return str(value)


class Sweep:
    def __init__(self, runner, plan, shared_dir):
        self.runner = runner
        self.plan = plan
        self.shared_dir = shared_dir
        self.render_rows = []
        self.bake_rows = []
        self.trees = {}       # (scene, builder, pairing) -> (tree path, bake row)
        self.references = {}  # (scene, size, camera) -> reference info
        self.device = ""

    # -- bakes ---------------------------------------------------------------
    def bake(self, group, scene, builder, pairing=""):
        key = (scene.name, builder, pairing)
        if key in self.trees:
            return self.trees[key]
        suffix = "_" + pairing if pairing else ""
        tree = self.runner.path("%s_%s%s.lcut" % (scene.name, builder, suffix))
        row = {"sweep": self.plan.name, "group": group, "scene": scene.name,
               "lights": scene.lights, "builder": builder,
               # Only optimal-pair pairs; its default is auto (bake_options.cpp).
               "pairing": pairing or ("auto" if builder == "optimal-pair" else "")}
        args = ["bake", scene.path, "--spawn-server", "--builder", builder, "--seed", 1,
                "--json", "-o", tree] + scene.load
        if pairing:
            args += ["--pairing", pairing]
        try:
            out, command_ms = self.runner.run(args)
            j = json.loads(out[out.index("{"):])
            row.update(status="ok", exact=bool(j["exact"]), nodes=j["nodes"],
                       build_ms=j["build_ms"], upload_ms=j["upload_ms"],
                       download_ms=j["download_ms"], total_ms=j["total_ms"],
                       transfer_import_ms=j["total_ms"] - j["build_ms"],
                       bake_command_ms=command_ms)
            if builder == "optimal-pair":
                row.update(pairing_cost=j["pairing_cost"],
                           pairing_lower_bound=j["pairing_lower_bound"])
        except (ProgramError, ValueError, KeyError) as e:
            row.update(status="failed", note=str(e))
            tree = None
        self.bake_rows.append(row)
        say("bake %s %s%s: %s" % (scene.name, builder, " " + pairing if pairing else "",
                                  "%.1f ms" % row["build_ms"] if tree else row["note"]))
        self.trees[key] = (tree, row)
        return tree, row

    def drop_trees(self, scene):
        """Big trees take hundreds of MB each: delete them once a scene is done."""
        for key, (tree, _) in list(self.trees.items()):
            if key[0] == scene.name and tree and os.path.exists(tree):
                os.remove(tree)

    # -- renders -------------------------------------------------------------
    def render_once(self, scene, tree, size, extra, tag, float_out=True, stats=True):
        png = self.runner.path(tag + ".png")
        args = (["render", scene.path, "--size", "%dx%d" % (size, size), "-o", png] + scene.camera +
                scene.load)
        if tree:
            # The sweep measures the paper's cut per pixel, not the default's reconstruction cuts.
            args += ["--tree", tree, "--reconstruction", "off"]
        pfm = self.runner.path(tag + ".pfm") if float_out else None
        if pfm:
            args += ["--float", pfm]
        stats_path = self.runner.path(tag + ".json")
        args += ["--stats", stats_path] + extra
        _, command_ms = self.runner.run(args)
        with open(stats_path, encoding="utf-8") as f:
            s = json.load(f)
        self.device = s.get("device", self.device)
        return s, command_ms, pfm, png

    def timed(self, scene, tree, size, extra, tag):
        """Renders once for the images and statistics, then again for the time.

        The machine is shared: a busy neighbour can stretch one frame tenfold.
        Frames under RETIME_BELOW_MS are rendered again (a third time when the
        two disagree by more than a quarter) and the fastest run is kept.
        """
        s, command_ms, pfm, png = self.render_once(scene, tree, size, extra, tag)
        timing_extra = [a for a in extra if a != "--compare-reference"]
        times = [s["render_ms"]]
        while s["render_ms"] < RETIME_BELOW_MS and (
                len(times) == 1 or (len(times) == 2 and max(times) > 1.25 * min(times))):
            t, _, _, _ = self.render_once(scene, tree, size, timing_extra, tag + "_t",
                                          float_out=False)
            times.append(t["render_ms"])
            if t["render_ms"] < s["render_ms"]:
                for k in ("render_ms", "lighting_ms", "wall_ms"):
                    s[k] = t[k]
        return s, command_ms, pfm, png, len(times)

    def reference(self, scene, size):
        key = (scene.name, size, tuple(scene.camera))
        if key in self.references:
            return self.references[key]
        estimate_s = scene.lights * size * size / LAVAPIPE_EVALS_PER_S
        info = {"status": "skipped", "note": ""}
        if estimate_s > REFERENCE_BUDGET_S:
            info["note"] = "reference skipped: about %.0f s > %.0f s budget" % (
                estimate_s, REFERENCE_BUDGET_S)
        else:
            try:
                s, _, pfm, png, _ = self.timed(scene, None, size, ["--mode", "reference"],
                                               "%s_%d_reference" % (scene.name, size))
                info = {"status": "ok", "note": "", "stats": s, "image": read_pfm(pfm),
                        "png": png}
            except ProgramError as e:
                info = {"status": "failed", "note": "reference: " + str(e)}
        say("reference %s %dx%d: %s" % (scene.name, size, size,
                                        "%.0f ms" % info["stats"]["render_ms"]
                                        if info["status"] == "ok" else info["note"]))
        self.references[key] = info
        return info

    def render(self, group, scene, builder, criterion, size, error_ratio=None, max_cut=None):
        tree, bake_row = self.bake(group, scene, builder)
        row = {"sweep": self.plan.name, "group": group, "scene": scene.name,
               "lights": scene.lights, "size": "%dx%d" % (size, size), "builder": builder,
               "pairing": bake_row.get("pairing", ""), "criterion": criterion}
        if criterion == "bound":
            row.update(error_ratio=error_ratio, max_cut_setting=max_cut)
        if tree is None:
            row.update(status="failed", note="bake failed: " + bake_row.get("note", ""))
            self.render_rows.append(row)
            return row
        row.update(build_ms=bake_row["build_ms"],
                   transfer_import_ms=bake_row["transfer_import_ms"])
        ref = self.reference(scene, size)
        row["reference_status"] = ref["status"]
        extra = ["--mode", "lightcuts", "--criterion", criterion]
        if criterion == "bound":
            extra += ["--error", error_ratio, "--max-cut", max_cut]
        client_compare = (ref["status"] == "ok" and
                          ref["stats"]["render_ms"] < CLIENT_COMPARE_BELOW_MS)
        if client_compare:
            extra.append("--compare-reference")
        tag = "%s_%d_%s_%s_%s_%s" % (scene.name, size, builder, criterion, error_ratio, max_cut)
        try:
            s, command_ms, pfm, _, repeats = self.timed(scene, tree, size, extra, tag)
        except ProgramError as e:
            row.update(status="failed", note=str(e))
            self.render_rows.append(row)
            say("render %s: FAILED %s" % (tag, e))
            return row
        row.update(status="ok", note=ref["note"], render_ms=s["render_ms"],
                   lighting_ms=s.get("lighting_ms"), wall_ms=s["wall_ms"],
                   command_ms=command_ms, render_repeats=repeats, avg_cut=s["avg_cut"],
                   cut_p99=s.get("cut_p99", ""), max_cut=s["max_cut"],
                   max_cut_hits=s["max_cut_hits"],
                   light_evaluations=s.get("light_evaluations"),
                   bound_search=s.get("bound_search", "") if criterion == "bound" else "",
                   loop_limit_stops=s.get("loop_limit_stops", ""),
                   load_1min=os.getloadavg()[0])
        if ref["status"] == "ok":
            r = ref["stats"]
            image = read_pfm(pfm)
            mine = error_stats(image, ref["image"], r["geometry_pixels"],
                               error_ratio if error_ratio is not None else 0.02)
            row.update(reference_ms=r["render_ms"], reference_wall_ms=r["wall_ms"],
                       speedup=r["render_ms"] / s["render_ms"] if s["render_ms"] > 0 else "",
                       ssim=ssim(display_luma(image, r["exposure"]),
                                 display_luma(ref["image"], r["exposure"])))
            if client_compare and "rel_err_mean" in s:
                row.update({k: s[k] for k in ("rel_err_mean", "rel_err_p99", "frac_over_error",
                                              "max_err", "error_pixels")},
                           error_source="client")
                if mine:
                    row.update(numpy_err_mean=mine["rel_err_mean"],
                               numpy_err_p99=mine["rel_err_p99"])
            elif mine:
                row.update(mine, error_source="numpy")
        os.remove(pfm)
        self.render_rows.append(row)
        say("render %s: %.0f ms, avg cut %.1f, p99 error %s" % (
            tag, s["render_ms"], s["avg_cut"], fmt(row.get("rel_err_p99", "n/a"))))
        return row

    # -- groups --------------------------------------------------------------
    def run_pareto(self):
        p = self.plan
        scene = room_mixed(self.runner, p.pareto_lights)
        for builder in BUILDERS:
            self.render("pareto", scene, builder, "radius", p.pareto_size)
            for max_cut in p.pareto_max_cuts[builder]:
                for e in ERROR_RATIOS:
                    self.render("pareto", scene, builder, "bound", p.pareto_size, e, max_cut)

    def run_lights(self):
        p = self.plan
        for count in p.light_counts:
            scene = room_points(self.runner, count)
            for builder in BUILDERS:
                self.bake("lights", scene, builder)
            for builder in BUILDERS:
                self.render("lights", scene, builder, "bound", p.lights_size, 0.02,
                            DEFAULT_MAX_CUT)
            self.drop_trees(scene)
            self.references.pop((scene.name, p.lights_size, tuple(scene.camera)), None)
            if count >= 2**17:
                os.remove(scene.path)  # hundreds of MB of glTF JSON

    def run_pairing(self):
        for count in self.plan.pairing_counts:
            scene = room_points(self.runner, count)
            for pairing in ("exact", "approximate"):
                self.bake("pairing", scene, "optimal-pair", pairing)
            self.drop_trees(scene)

    def run_shared(self):
        p = self.plan
        scenes = []
        if not os.path.isdir(self.shared_dir):
            say("shared scenes absent (%s): group 'shared' skipped" % self.shared_dir)
        cornell = cornell_scene(self.runner, self.shared_dir, p.shared_lights)
        lamp = lamp_scene(self.runner, self.shared_dir)
        for name, scene in (("cornell_box", cornell), ("LightsPunctualLamp", lamp)):
            if scene is None:
                say("shared scene %s absent: skipped" % name)
                self.render_rows.append({"sweep": p.name, "group": "shared", "scene": name,
                                         "status": "skipped",
                                         "note": "not found under " + self.shared_dir})
            else:
                scenes.append(scene)
        for scene in scenes:
            self.render("shared", scene, "agglomerative", "bound", p.shared_size, 0.02,
                        DEFAULT_MAX_CUT)
            self.render("shared", scene, "agglomerative", "radius", p.shared_size)

    def run_figure(self, images_dir):
        """Reference, lightcuts, error and cut-size images of the pareto room, side by side."""
        p = self.plan
        scene = room_mixed(self.runner, p.pareto_lights)
        tree, _ = self.bake("figure", scene, "agglomerative")
        if tree is None:
            return
        size = p.figure_size
        bound = ["--criterion", "bound", "--error", 0.02]
        panels = {}
        try:
            for mode, extra in (("reference", []), ("lightcuts", bound),
                                ("error", bound), ("cutsize", bound)):
                s, _, pfm, png = self.render_once(scene, tree if mode != "reference" else None,
                                                  size, ["--mode", mode] + extra,
                                                  "figure_" + mode, float_out=False)
                panels[mode] = (png, s)
        except ProgramError as e:
            say("figure: FAILED %s" % e)
            return
        row = self.render("figure", scene, "agglomerative", "bound", size, 0.02, DEFAULT_MAX_CUT)
        if row.get("status") != "ok":
            return
        plot_side_by_side(panels, row, scene, os.path.join(images_dir,
                                                           "accuracy_side_by_side.png"))


# ---------------------------------------------------------------------------
# CSV

def write_csv(path, columns, rows):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(columns)
        for r in rows:
            w.writerow([fmt(r.get(c, "")) for c in columns])


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def num(row, column):
    """A CSV cell as float, None when empty or absent."""
    v = row.get(column, "")
    if v is None or v == "":
        return None
    return float(v)


# ---------------------------------------------------------------------------
# Plots

def plt_module():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


BUILDER_COLOURS = {"optimal-pair": "tab:blue", "agglomerative": "tab:orange", "lbvh": "tab:green"}
MAX_CUT_MARKERS = {64: "v", 100: "v", 256: "s", 1000: "o"}


def loglog_slope(xs, ys):
    """Least-squares exponent of y = c x^slope; None with fewer than two usable points."""
    nan = float("nan")
    xs = np.array([nan if x is None else x for x in xs], float)
    ys = np.array([nan if y is None else y for y in ys], float)
    keep = np.isfinite(xs) & np.isfinite(ys) & (xs > 0) & (ys > 0)
    if keep.sum() < 2:
        return None
    return float(np.polyfit(np.log(xs[keep]), np.log(ys[keep]), 1)[0])


def slope_text(slope, digits):
    return "n/a" if slope is None else "%.*f" % (digits, slope)


def ok_rows(rows, group):
    return [r for r in rows if r["group"] == group and r["status"] == "ok"]


def pareto_front(points):
    """Points (time, error) not beaten by any faster-or-equal point with less error."""
    front, best = [], math.inf
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


ERROR_FLOOR = 1e-5  # exact results (zero error) are drawn here on log axes


def finish_plot(plt, fig, ax, path):
    """The common end of a single-axes figure: grid, legend, layout, PNG."""
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def plot_pareto(rows, path):
    plt = plt_module()
    data = [r for r in ok_rows(rows, "pareto") if num(r, "rel_err_mean") is not None]
    if not data:
        return False
    metrics = [("rel_err_mean", "mean relative error"),
               ("rel_err_p99", "99th-percentile relative error"),
               ("ssim", "1 - SSIM (display luma)")]
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    for ax, (metric, label) in zip(axes, metrics):
        for builder in BUILDERS:
            for criterion, style in (("bound", "-"), ("radius", "--")):
                sel = [r for r in data if r["builder"] == builder and r["criterion"] == criterion]
                if not sel:
                    continue
                pts = []
                for r in sel:
                    v = num(r, metric)
                    if v is None:
                        continue
                    v = 1.0 - v if metric == "ssim" else v
                    pts.append((num(r, "render_ms"), max(v, ERROR_FLOOR), r))
                for t, v, r in pts:
                    marker = "*" if criterion == "radius" else MAX_CUT_MARKERS.get(
                        int(num(r, "max_cut_setting")), "o")
                    ax.plot(t, v, marker, color=BUILDER_COLOURS[builder], alpha=0.35,
                            markersize=9 if criterion == "radius" else 5)
                front = pareto_front([(t, v) for t, v, _ in pts])
                ax.plot([t for t, _ in front], [v for _, v in front], style,
                        marker="*" if criterion == "radius" else ".",
                        color=BUILDER_COLOURS[builder], label="%s, %s" % (builder, criterion))
        refs = [num(r, "reference_ms") for r in data if num(r, "reference_ms")]
        if refs:
            ax.axvline(float(np.median(refs)), color="grey", linestyle=":",
                       label="reference (median %.0f ms)" % float(np.median(refs)))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.axhline(ERROR_FLOOR, color="lightgrey", linewidth=0.8)
        ax.set_xlabel("render time, GPU timestamps (ms)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.25)
    axes[0].legend(fontsize=7)
    first = data[0]
    fig.suptitle("Error against time, %s (%s lights), %s: Pareto fronts per builder and "
                 "criterion; faint points: every error ratio x max cut (v 64/100, s 256, o 1000), "
                 "* radius; errors below %g drawn at %g"
                 % (first["scene"], first["lights"], first["size"], ERROR_FLOOR, ERROR_FLOOR),
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def pow2_axis(ax, counts):
    ax.set_xscale("log", base=2)
    ax.set_xticks(counts)
    ax.set_xticklabels(["2^%d" % int(round(math.log2(c))) for c in counts])


def start_light_count_plot(rows):
    """The common start of a plot against the light count: the 'lights' group's rows."""
    plt = plt_module()
    data = ok_rows(rows, "lights")
    if not data:
        return plt, data, None, None, []
    fig, ax = plt.subplots(figsize=(7.5, 5))
    return plt, data, fig, ax, sorted({int(r["lights"]) for r in data})


def light_count_axes(ax, counts, ylabel):
    """Log-log axes with the light counts as powers of two."""
    pow2_axis(ax, counts)
    ax.set_yscale("log")
    ax.set_xlabel("lights")
    ax.set_ylabel(ylabel)


def plot_time_vs_lights(rows, path):
    plt, data, fig, ax, counts = start_light_count_plot(rows)
    if not data:
        return False
    ref = {}
    for r in data:
        if num(r, "reference_ms"):
            ref[int(r["lights"])] = num(r, "reference_ms")
    if ref:
        xs = sorted(ref)
        slope = loglog_slope(xs, [ref[x] for x in xs])
        ax.plot(xs, [ref[x] for x in xs], "k-o", label="reference (slope %.2f)" % slope
                if slope is not None else "reference")
    for builder in BUILDERS:
        sel = sorted((int(r["lights"]), num(r, "render_ms"))
                     for r in data if r["builder"] == builder)
        if sel:
            slope = loglog_slope([x for x, _ in sel], [y for _, y in sel])
            ax.plot([x for x, _ in sel], [y for _, y in sel], "-s", color=BUILDER_COLOURS[builder],
                    label="lightcuts bound E=0.02, %s tree (slope %s)" % (
                        builder, slope_text(slope, 2)))
    light_count_axes(ax, counts, "render time, GPU timestamps (ms)")
    ax.set_title("Render time against light count, %s (log-log; slope = fitted exponent)"
                 % data[0]["size"], fontsize=9)
    return finish_plot(plt, fig, ax, path)


def plot_cut_vs_lights(rows, path):
    plt, data, fig, ax, counts = start_light_count_plot(rows)
    if not data:
        return False
    ax.plot(counts, counts, "k:", label="reference: every light (slope 1)")
    for builder in BUILDERS:
        sel = sorted((int(r["lights"]), num(r, "avg_cut"), num(r, "max_cut"), num(r, "cut_p99"))
                     for r in data if r["builder"] == builder)
        if not sel:
            continue
        xs = [s[0] for s in sel]
        slope = loglog_slope(xs, [s[1] for s in sel])
        colour = BUILDER_COLOURS[builder]
        ax.plot(xs, [s[1] for s in sel], "-o", color=colour,
                label="%s: average cut (slope %s)" % (builder, slope_text(slope, 3)))
        ax.plot(xs, [s[2] for s in sel], "--", color=colour, alpha=0.6,
                label="%s: max cut" % builder)
        p99 = [(s[0], s[3]) for s in sel if s[3] is not None]
        if p99:
            ax.plot([x for x, _ in p99], [y for _, y in p99], "-.", color=colour, alpha=0.8,
                    label="%s: 99th-percentile cut" % builder)
    light_count_axes(ax, counts, "cut size (nodes per pixel)")
    ax.set_title("Cut size against light count, bound criterion E=0.02, max cut %d, %s"
                 % (DEFAULT_MAX_CUT, data[0]["size"]), fontsize=9)
    return finish_plot(plt, fig, ax, path)


def plot_build_vs_lights(bakes, path):
    plt, data, fig, ax, counts = start_light_count_plot(bakes)
    if not data:
        return False
    for builder in BUILDERS:
        sel = sorted((int(r["lights"]), num(r, "build_ms"), num(r, "transfer_import_ms"),
                      r.get("exact") != "false") for r in data if r["builder"] == builder)
        if not sel:
            continue
        xs = [s[0] for s in sel]
        slope = loglog_slope(xs, [s[1] for s in sel])
        colour = BUILDER_COLOURS[builder]
        ax.plot(xs, [s[1] for s in sel], "-o", color=colour,
                label="%s: build (slope %s)" % (builder, slope_text(slope, 2)))
        approximate = [s for s in sel if not s[3]]
        if approximate:
            # optimal-pair's auto pairing turns approximate above the exact limit.
            ax.plot([s[0] for s in approximate], [s[1] for s in approximate], "o",
                    markerfacecolor="white", color=colour,
                    label="%s: approximate pairing (auto)" % builder)
        ax.plot(xs, [s[2] for s in sel], ":", color=colour, alpha=0.7,
                label="%s: transfer + import" % builder)
    light_count_axes(ax, counts, "time (ms)")
    ax.set_title("Tree build time (server) and transfer + import (client) against light count",
                 fontsize=9)
    return finish_plot(plt, fig, ax, path)


def plot_pairing(bakes, path):
    plt = plt_module()
    data = ok_rows(bakes, "pairing")
    if not data:
        return False
    exact = {int(r["lights"]): num(r, "pairing_cost") for r in data if r["pairing"] == "exact"}
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    ax = axes[0]
    for pairing, colour in (("exact", "tab:blue"), ("approximate", "tab:red")):
        sel = sorted((int(r["lights"]), num(r, "build_ms"), num(r, "pairing_cost"),
                      num(r, "pairing_lower_bound")) for r in data if r["pairing"] == pairing)
        pts = [(b, c / exact[n], n) for n, b, c, _ in sel if n in exact and exact[n] > 0]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", color=colour, label=pairing)
        for b, y, n in pts:
            ax.annotate("2^%d" % int(round(math.log2(n))), (b, y), fontsize=7,
                        textcoords="offset points", xytext=(3, 4), color=colour)
        lb = [(b, l / exact[n]) for n, b, _, l in sel if n in exact and exact[n] > 0 and l]
        if pairing == "approximate" and lb:
            ax.plot([p[0] for p in lb], [p[1] for p in lb], "x:", color=colour, alpha=0.6,
                    label="approximate: its lower bound")
        axes[1].plot([n for n, *_ in sel], [b for _, b, *_ in sel], "-o", color=colour,
                     label="%s (slope %s)" % (pairing, slope_text(loglog_slope(
                         [n for n, *_ in sel], [b for _, b, *_ in sel]), 2)))
    ax.set_xscale("log")
    ax.set_xlabel("optimal-pair build time (ms)")
    ax.set_ylabel("pairing cost / exact pairing cost (same lights)")
    ax.set_title("Pairing cost against build time (labels: light count)", fontsize=9)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8)
    counts = sorted({int(r["lights"]) for r in data})
    pow2_axis(axes[1], counts)
    axes[1].set_yscale("log")
    axes[1].set_xlabel("lights")
    axes[1].set_ylabel("build time (ms)")
    axes[1].set_title("optimal-pair build time, exact and approximate pairing", fontsize=9)
    axes[1].grid(True, which="both", alpha=0.25)
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def plot_side_by_side(panels, row, scene, path):
    plt = plt_module()
    import matplotlib.image as mpimg
    fig, axes = plt.subplots(1, 4, figsize=(16, 4.6))
    titles = {
        "reference": "reference (%.0f ms)" % row.get("reference_ms", float("nan")),
        "lightcuts": "lightcuts, bound E=0.02 (%.0f ms)" % row["render_ms"],
        "error": "relative error, 0 .. 2E (mean %.4f, p99 %.4f)" % (
            panels["error"][1].get("rel_err_mean", float("nan")),
            panels["error"][1].get("rel_err_p99", float("nan"))),
        "cutsize": "cut size, 0 .. max (avg %.0f, max %d)" % (panels["cutsize"][1]["avg_cut"],
                                                   panels["cutsize"][1]["max_cut"]),
    }
    for ax, mode in zip(axes, ("reference", "lightcuts", "error", "cutsize")):
        ax.imshow(mpimg.imread(panels[mode][0]))
        ax.set_title(titles[mode], fontsize=9)
        ax.axis("off")
    ssim_text = ", SSIM %.4f" % num(row, "ssim") if num(row, "ssim") is not None else ""
    fig.suptitle("%s (%d lights), agglomerative tree, %s%s" % (
        scene.name, scene.lights, row.get("size", ""), ssim_text), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def stringify(rows):
    return [{k: fmt(v) for k, v in r.items()} for r in rows]


# ---------------------------------------------------------------------------

def draw_plots(bench_dir, images_dir):
    """Every figure drawn from the CSV files; returns the names of the figures present."""
    os.makedirs(images_dir, exist_ok=True)
    renders = read_csv(os.path.join(bench_dir, "accuracy_renders.csv"))
    bakes = read_csv(os.path.join(bench_dir, "accuracy_bakes.csv"))
    drawn = []
    for name, fn, rows in (("accuracy_pareto.png", plot_pareto, renders),
                           ("accuracy_time_vs_lights.png", plot_time_vs_lights, renders),
                           ("accuracy_cut_vs_lights.png", plot_cut_vs_lights, renders),
                           ("accuracy_build_vs_lights.png", plot_build_vs_lights, bakes),
                           ("accuracy_pairing.png", plot_pairing, bakes)):
        if fn(rows, os.path.join(images_dir, name)):
            drawn.append(name)
    if os.path.exists(os.path.join(images_dir, "accuracy_side_by_side.png")):
        drawn.append("accuracy_side_by_side.png")
    return drawn


def source_info(build_dir):
    """The source tree the build directory was configured from, its commit and whether
    it had uncommitted changes (read-only git)."""
    source = ""
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt"), encoding="utf-8") as f:
            for line in f:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    source = line.split("=", 1)[1].strip()
    except OSError:
        return {}
    info = {"source": source}
    client = os.path.join(build_dir, "bin", "editor_client")
    if os.path.exists(client):
        # The commit below is the tree's when the sweep starts; the binary may be older.
        info["client_built"] = datetime.datetime.fromtimestamp(
            os.path.getmtime(client)).isoformat(timespec="seconds")
    try:
        head = subprocess.run(["git", "-C", source, "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, timeout=30)
        dirty = subprocess.run(["git", "-C", source, "status", "--porcelain",
                                "--untracked-files=no"], capture_output=True, text=True,
                               timeout=30)
        if head.returncode == 0:
            info["source_commit"] = head.stdout.strip() + (
                " (with uncommitted changes)" if dirty.stdout.strip() else "")
    except (OSError, subprocess.TimeoutExpired):
        pass
    return info


def machine_info():
    info = {"machine": platform.machine(), "kernel": platform.release(),
            "cores": str(os.cpu_count())}
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    info["cpu"] = line.split(":", 1)[1].strip()
                    break
        with open("/proc/meminfo", encoding="utf-8") as f:
            info["memory"] = "%.0f GiB" % (int(f.readline().split()[1]) / 2**20)
        with open("/etc/debian_version", encoding="utf-8") as f:
            info["os"] = "Debian " + f.read().strip()
        info["load_average_at_start"] = "%.2f %.2f %.2f" % os.getloadavg()
    except OSError:
        pass
    return info


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--quick", action="store_true")
    mode.add_argument("--full", action="store_true")
    parser.add_argument("--build-dir", required=True)
    parser.add_argument("--out-dir", required=True,
                        help="CSV files go to OUT/bench, figures to OUT/images")
    parser.add_argument("--only", default=",".join(GROUPS),
                        help="comma-separated groups to (re)run: " + ", ".join(GROUPS))
    parser.add_argument("--shared-scenes", default=None)
    parser.add_argument("--keep-work", action="store_true",
                        help="keep scenes, trees, images and the command log")
    parser.add_argument("--plots-only", action="store_true",
                        help="redraw the figures from the CSV files in OUT/bench, run nothing "
                             "(the side-by-side figure needs renders and is left as it is)")
    args = parser.parse_args()

    plan = QUICK if args.quick else FULL
    groups = [g.strip() for g in args.only.split(",") if g.strip()]
    for g in groups:
        if g not in GROUPS:
            sys.exit("sweep: unknown group '%s' (groups: %s)" % (g, ", ".join(GROUPS)))
    bench_dir = os.path.join(args.out_dir, "bench")
    images_dir = os.path.join(args.out_dir, "images")
    if args.plots_only:
        draw_plots(bench_dir, images_dir)
        return
    client = os.path.join(args.build_dir, "bin", "editor_client")
    if not os.access(client, os.X_OK):
        sys.exit("sweep: %s not found: build editor_client and lightmass_server first" % client)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    shared_dir = args.shared_scenes or os.path.join(os.path.dirname(root), "shared", "scenes")
    os.makedirs(bench_dir, exist_ok=True)
    os.makedirs(images_dir, exist_ok=True)
    work = tempfile.mkdtemp(prefix="sweep-accuracy-")
    runner = Runner(args.build_dir, work, os.path.join(work, "commands.log"))
    sweep = Sweep(runner, plan, shared_dir)
    info = machine_info()  # the load average before the sweep adds its own
    info.update(source_info(args.build_dir))
    started = time.monotonic()
    say("%s mode, groups %s, work dir %s" % (plan.name, ",".join(groups), work))
    try:
        for g in GROUPS:
            if g not in groups:
                continue
            group_start = time.monotonic()
            if g == "figure":
                sweep.run_figure(images_dir)
            else:
                getattr(sweep, "run_" + g)()
            say("group %s done in %.0f s" % (g, time.monotonic() - group_start))
    except ProgramError as e:
        # Scene generation failing leaves nothing to measure.
        sys.exit("sweep: %s (command log: %s)" % (e, runner.log.name))
    elapsed = time.monotonic() - started

    # Merge: rows of groups not rerun now are kept from the earlier CSV of this mode.
    renders_path = os.path.join(bench_dir, "accuracy_renders.csv")
    bakes_path = os.path.join(bench_dir, "accuracy_bakes.csv")
    keep = lambda r: r.get("group") not in groups and r.get("sweep") == plan.name
    renders = [r for r in read_csv(renders_path) if keep(r)] + stringify(sweep.render_rows)
    bakes = [r for r in read_csv(bakes_path) if keep(r)] + stringify(sweep.bake_rows)
    renders.sort(key=lambda r: GROUPS.index(r["group"]))
    bakes.sort(key=lambda r: GROUPS.index(r["group"]))
    write_csv(renders_path, RENDER_COLUMNS, renders)
    write_csv(bakes_path, BAKE_COLUMNS, bakes)

    info.update(sweep=plan.name, groups=",".join(groups), device=sweep.device,
                date=datetime.datetime.now().isoformat(timespec="seconds"),
                runtime_s="%.0f" % elapsed,
                command="bash scripts/sweep_accuracy.sh --%s%s" % (
                    plan.name, "" if groups == GROUPS else " --only " + ",".join(groups)))
    with open(os.path.join(bench_dir, "accuracy_runinfo.csv"), "w", newline="",
              encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["key", "value"])
        for k, v in info.items():
            w.writerow([k, v])

    drawn = draw_plots(bench_dir, images_dir)
    failed = [r for r in sweep.render_rows + sweep.bake_rows if r.get("status") == "failed"]
    say("%d renders, %d bakes (%d failed) in %.0f s; CSV in %s, figures (%s) in %s" % (
        len(sweep.render_rows), len(sweep.bake_rows), len(failed), elapsed, bench_dir,
        ", ".join(drawn), images_dir))
    runner.log.close()
    if args.keep_work:
        say("work files kept in " + work)
    else:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
