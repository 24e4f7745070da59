#!/usr/bin/env python3
"""A bake's measured peak against the estimate it was admitted by.

Starts a fresh lightmass_server (127.0.0.1, a budget large enough to admit
the bake), runs hostile_bake_bench SCENARIO [BENCH ARGS...] to the end (or
to its --cancel-after-ms, for a bake too slow to finish), and
reads the server's VmHWM (the kernel's high-water mark of its resident
memory, exact, not sampled). The estimate is the reservation the server
logged ("bake N reserves X MB ... beside Y MB of stored channels"); the
stored channels are their own reservations.
Prints one CSV row:
  stage,size,builder,threads,estimate_mib,channels_mib,base_mib,peak_mib,bake_peak_mib,headroom_mib,outcome
where bake_peak_mib = peak - base (the server's RSS before the bake) and
headroom_mib = estimate + channels + base - peak (negative: the estimate was
not an upper bound). Every wait is bounded.
"""
import argparse
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import server_launch  # noqa: E402


def status_mib(pid, field):
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024
    return -1.0


def start_server(args, folder, log_path):
    with open(log_path, "wb") as log:
        return server_launch.start_server(
            args.server_bin, folder,
            ["--memory-budget-mb", str(args.budget_mb), "--max-bake-seconds", str(args.limit_s),
             "--threads", str(args.threads)], log)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--server-bin", default="build/bin/lightmass_server")
    parser.add_argument("--hostile-bin", default="build/bin/hostile_bake_bench")
    parser.add_argument("--budget-mb", type=int, default=16384)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--limit-s", type=int, default=900)
    parser.add_argument("--label", default="")
    parser.add_argument("scenario")
    parser.add_argument("bench_args", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        log_path = os.path.join(folder, "server.log")
        server, port = start_server(args, folder, log_path)
        time.sleep(0.2)
        base = status_mib(server.pid, "VmRSS")
        try:
            bench = subprocess.run([args.hostile_bin, f"127.0.0.1:{port}", args.scenario] + args.bench_args,
                                   capture_output=True, text=True, timeout=args.limit_s + 60)
            row = bench.stdout.strip().splitlines()[-1] if bench.stdout.strip() else "no output"
        except subprocess.TimeoutExpired:
            row = "timed out"
        peak = status_mib(server.pid, "VmHWM")
        server.send_signal(signal.SIGTERM)
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()
        log = open(log_path).read()
    reserved = re.search(r"reserves ([\d,]+) MB", log)
    estimate = int(reserved.group(1).replace(",", "")) if reserved else -1
    stored = re.search(r"beside ([\d,]+) MB of stored channels", log)
    channels = int(stored.group(1).replace(",", "")) if stored else -1
    size = "default"
    if "--size" in args.bench_args:
        size = args.bench_args[args.bench_args.index("--size") + 1]
    if "--patch-size" in args.bench_args:
        size += " patch " + args.bench_args[args.bench_args.index("--patch-size") + 1]
    builder = "optimal-pair"
    if "--builder" in args.bench_args:
        builder = args.bench_args[args.bench_args.index("--builder") + 1]
    if "--exact" in args.bench_args:
        builder += " exact"
    outcome = row.split(",")[1] if row.count(",") >= 1 else row
    # A bake too slow to finish here (radiosity's shooting is quadratic) is cancelled inside its
    # heaviest stage instead: its peak so far, against the same estimate.
    if "--cancel-after-ms" in args.bench_args and outcome == "refused-or-stopped" and "cancelled" in row:
        outcome = "cancelled " + row.split(",")[2]
    headroom = estimate + channels + base - peak
    print(f"{args.label or args.scenario},{size},{builder},{args.threads},{estimate},{channels},"
          f"{base:.0f},{peak:.0f},{peak - base:.0f},{headroom:.0f},{outcome}", flush=True)
    return 0 if outcome.split(" ")[0] in ("baked", "cancelled") and headroom >= 0 else 1


if __name__ == "__main__":
    sys.exit(main())
