#!/usr/bin/env python3
"""Fails when a production file is too long or a production folder holds too many concepts.

Production code is every file under lightcuts/, protocol/, lightmass_server/ and
editor_client/ but README.md and CMakeLists.txt. A concept is a name at a folder's
top level: a header and its source (everything before the first dot) count once,
and so does each subfolder. Long files and crowded folders are what a newcomer
cannot read in one sitting (issue 40), so the tests run this.
Usage: check_sizes.py [--max-lines N] [--max-concepts N] [REPO_ROOT]
(exit 1, each offender named on stderr).
"""
import argparse
import os
import sys

ROOTS = ("lightcuts", "protocol", "lightmass_server", "editor_client")
NOT_CODE = ("README.md", "CMakeLists.txt")


def production_folders(repo):
    for root in ROOTS:
        for here, dirs, files in os.walk(os.path.join(repo, root)):
            dirs[:] = sorted(d for d in dirs if not d.startswith("."))
            yield here, dirs, sorted(f for f in files if f not in NOT_CODE and not f.startswith("."))


def long_files(repo, max_lines):
    found = []
    for here, _, files in production_folders(repo):
        for name in files:
            path = os.path.join(here, name)
            with open(path, encoding="utf-8", errors="replace") as f:
                lines = sum(1 for _ in f)
            if lines > max_lines:
                found.append(f"{os.path.relpath(path, repo)}: {lines} lines, more than {max_lines}")
    return found


def crowded_folders(repo, max_concepts):
    found = []
    for here, dirs, files in production_folders(repo):
        concepts = {name.split(".", 1)[0] for name in files} | {d + "/" for d in dirs}
        if len(concepts) > max_concepts:
            found.append(f"{os.path.relpath(here, repo)}/: {len(concepts)} concepts at its top level, "
                         f"more than {max_concepts}")
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--max-lines", type=int, default=700)
    parser.add_argument("--max-concepts", type=int, default=25)
    parser.add_argument("repo", nargs="?", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    args = parser.parse_args()
    repo = os.path.abspath(args.repo)
    problems = long_files(repo, args.max_lines) + crowded_folders(repo, args.max_concepts)
    for p in problems:
        print(p, file=sys.stderr)
    if not problems:
        print(f"no production file over {args.max_lines} lines, no folder over {args.max_concepts} concepts")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
