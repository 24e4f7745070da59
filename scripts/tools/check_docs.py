#!/usr/bin/env python3
"""Checks that a doc stays readable and true: no line over --max-width, at most
--max-lines lines, and every file or folder it names in backticks exists.

A name resolves against the repository root or any folder of the repository
(so `net/connection.cpp` under a lightmass_server heading is found as
lightmass_server/net/connection.cpp). Patterns and outputs (out/, build*/, generated headers) are skipped.
Usage: check_docs.py [--max-width N] [--max-lines N] FILE.md...  (exit 1 on a problem).
"""
import argparse
import os
import re
import sys

PATH = re.compile(r"`([\w./-]+(?:\.(?:h|cpp|md|sh|py|comp|glsl|fbs|txt|csv|png|json|in)|/))`")


def repo_folders(repo):
    folders = [""]
    for here, dirs, _ in os.walk(repo):
        dirs[:] = [d for d in dirs if not d.startswith(".") and d != "build" and not d.startswith("build-")]
        folders.append(os.path.relpath(here, repo))
    return folders


def exists(name, repo, folders):
    name = name.rstrip("/") if name.endswith("/") else name
    return any(os.path.exists(os.path.join(repo, f, name)) for f in folders)


def generated(name):
    """Names of outputs that a build or a run makes, and patterns."""
    return ("*" in name or name.startswith((".", "out/", "build")) or name.endswith("_generated.h")
            or "regressions/" in name)


def check(path, repo, folders, max_width, max_lines):
    problems = []
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    if max_lines and len(lines) > max_lines:
        problems.append(f"{path}: {len(lines)} lines, more than {max_lines}")
    for number, line in enumerate(lines, 1):
        if max_width and len(line) > max_width:
            problems.append(f"{path}:{number}: {len(line)} characters, more than {max_width}")
        for name in PATH.findall(line):
            if not generated(name) and not exists(name, repo, folders):
                problems.append(f"{path}:{number}: names `{name}`, which does not exist")
    return problems


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--max-width", type=int, default=200)
    parser.add_argument("--max-lines", type=int, default=0)
    parser.add_argument("--repo", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    repo = os.path.abspath(args.repo)
    folders = repo_folders(repo)
    problems = []
    for path in args.files:
        problems += check(path, repo, folders, args.max_width, args.max_lines)
    for p in problems:
        print(p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
