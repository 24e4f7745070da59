#!/usr/bin/env python3
"""Fails when production folders include each other in a cycle.

Each folder of production code (a directory holding .h/.cpp/.glsl.h files under
lightcuts/, protocol/, lightmass_server/, editor_client/) is a node; an edge
A -> B means a file in A includes a file in B. A cycle of folders means the
layout no longer says what depends on what, so the tests run this.
Usage: check_include_cycles.py [REPO_ROOT]  (exit 1 and the cycles on stderr).
"""
import os
import re
import sys

ROOTS = ("lightcuts", "protocol", "lightmass_server", "editor_client")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def folder_edges(repo):
    edges = {}
    for root in ROOTS:
        for here, _, files in os.walk(os.path.join(repo, root)):
            src = os.path.relpath(here, repo)
            for name in files:
                if not name.endswith((".h", ".cpp")):
                    continue
                with open(os.path.join(here, name), encoding="utf-8") as f:
                    for target in INCLUDE.findall(f.read()):
                        dst = os.path.dirname(target)
                        if dst and dst != src and os.path.isfile(os.path.join(repo, target)):
                            edges.setdefault(src, set()).add(dst)
    return edges


def strongly_connected(edges):
    """Tarjan's components with more than one folder."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    nodes = set(edges) | {d for ds in edges.values() for d in ds}
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return found


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    edges = folder_edges(os.path.abspath(repo))
    cycles = strongly_connected(edges)
    for comp in cycles:
        pairs = [f"{a} -> {b}" for a in comp for b in sorted(edges.get(a, ())) if b in comp]
        print("include cycle between folders: " + ", ".join(pairs), file=sys.stderr)
    if not cycles:
        print(f"no include cycle among {len(edges)} folders")
    return 1 if cycles else 0


if __name__ == "__main__":
    sys.exit(main())
