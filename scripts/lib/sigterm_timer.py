#!/usr/bin/env python3
"""SIGTERM to exit of a lightmass_server in the middle of a heavy bake.

Starts the server (127.0.0.1, any free port), starts hostile_bake_bench's
SCENARIO against it, and AT_MS after the client started sends the server
SIGTERM; the time is from the signal to waitpid() returning, so it includes
the bake's stop, the server's shutdown and the kernel giving the process's
memory back. With --disconnect-at-ms the client is killed first (its socket
closed by the kernel), as a client that gives up would, and the time until
the server's RSS is back within 64 MiB of where it started is measured too
(the disconnect stops the bake and gives its memory back). Prints one CSV row:
  scenario,signal_at_ms,disconnect_at_ms,rss_at_signal_mib,exit_ms,status,load1,freed_after_disconnect_ms
where status is the server's exit status (0: a clean stop) or "RUNNING"
(still there after --limit-ms, then killed). Every wait is bounded.
"""
import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import server_launch  # noqa: E402


def rss_mib(pid):
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) // 1024
    except OSError:
        pass
    return -1


def wait_exit(pid, limit_s):
    """Polls waitpid without blocking past limit_s; returns the status or None."""
    end = time.monotonic() + limit_s
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done == pid:
            return os.waitstatus_to_exitcode(status)
        if time.monotonic() >= end:
            return None
        time.sleep(0.0002)


def disconnect(client, pid, base_mib, until):
    """Kills the client (the kernel closes its socket) and polls the server's RSS every
    millisecond until the bake's memory is back (within 64 MiB of the RSS before it):
    the milliseconds that took, or "" when it was not back by `until`."""
    held = rss_mib(pid)
    t0 = time.monotonic()
    client.kill()
    while held > base_mib + 64 and time.monotonic() < until:
        time.sleep(0.001)
        held = rss_mib(pid)
    return f"{(time.monotonic() - t0) * 1000:.1f}" if held <= base_mib + 64 else ""


def start_server(args, folder):
    log = open(args.log, "ab") if args.log else subprocess.DEVNULL
    return server_launch.start_server(
        args.server_bin, folder,
        ["--memory-budget-mb", str(args.budget_mb), "--read-timeout-ms", "2000"] + args.server_arg, log)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--server-bin", default="build/bin/lightmass_server")
    parser.add_argument("--hostile-bin", default="build/bin/hostile_bake_bench")
    parser.add_argument("--scenario", default="area")
    parser.add_argument("--at-ms", type=int, default=2000)
    parser.add_argument("--disconnect-at-ms", type=int, default=0)
    parser.add_argument("--budget-mb", type=int, default=4096)
    parser.add_argument("--limit-ms", type=int, default=5000)
    parser.add_argument("--log", default="")
    parser.add_argument("--server-arg", action="append", default=[])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        server, port = start_server(args, folder)
        base = rss_mib(server.pid)
        client = subprocess.Popen([args.hostile_bin, f"127.0.0.1:{port}", args.scenario],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        started = time.monotonic()
        freed_ms = ""
        if args.disconnect_at_ms > 0:
            time.sleep(max(0.0, started + args.disconnect_at_ms / 1000 - time.monotonic()))
            freed_ms = disconnect(client, server.pid, base, started + args.at_ms / 1000)
        time.sleep(max(0.0, started + args.at_ms / 1000 - time.monotonic()))
        rss = rss_mib(server.pid)
        t0 = time.monotonic()
        server.send_signal(signal.SIGTERM)
        status = wait_exit(server.pid, args.limit_ms / 1000)
        exit_ms = (time.monotonic() - t0) * 1000
        if status is None:
            server.kill()
            server.wait()
        client.kill()
        client.wait()
        load1 = os.getloadavg()[0]
        print(f"{args.scenario},{args.at_ms},{args.disconnect_at_ms},{rss},{exit_ms:.1f},"
              f"{'RUNNING' if status is None else status},{load1:.2f},{freed_ms}", flush=True)
        return 0 if status == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
