#!/usr/bin/env python3
"""The module graph of skinmesh, printed and checked one-way.

    python3 tests/layers/check_layers.py SOURCE_DIR [--cmake CMAKE]

Configures the project in a scratch folder with `cmake --graphviz`, reads the link graph of the module libraries
(skinmesh_<module>, one per folder: core, geometry/<layer>, skin, morse, front, decompose, refine, verify, dynamic, mesher,
trace), prints each module with the modules it links directly, and fails (exit 1) if
  - the graph has a cycle, or
  - a module's sources include a header of a module it does not link, directly or through the modules it links
    (a header-only use that the linker would not catch).
The programs above the modules (apps/, python/, bench/, tests/) are not checked.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

MODULE_DIRS = ["core", "geometry/kernel", "geometry/triangulation", "geometry/mesh", "geometry/io", "geometry/check",
               "skin", "morse", "front", "decompose", "refine", "verify", "dynamic", "mesher", "trace"]


def target_of(folder):
    return "skinmesh_" + folder.replace("/", "_")


def link_graph(source, cmake):
    with tempfile.TemporaryDirectory() as tmp:
        dot = os.path.join(tmp, "modules.dot")
        subprocess.run([cmake, "-S", source, "-B", os.path.join(tmp, "build"), "-DSKINMESH_BUILD_BENCH=OFF",
                        "-DSKINMESH_PYTHON=OFF", f"--graphviz={dot}"], check=True, stdout=subprocess.DEVNULL)
        text = open(dot).read()
    names = dict(re.findall(r'"(node\d+)" \[ label = "([^"]+)"', text))
    edges = {}
    for a, b in re.findall(r'"(node\d+)" -> "(node\d+)"', text):
        edges.setdefault(names[a], set()).add(names[b])
    modules = {target_of(f) for f in MODULE_DIRS}
    return {m: sorted(d for d in edges.get(m, ()) if d in modules) for m in sorted(modules)}


def closure(graph, m, seen=None):
    seen = set() if seen is None else seen
    for d in graph.get(m, []):
        if d not in seen:
            seen.add(d)
            closure(graph, d, seen)
    return seen


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("source")
    ap.add_argument("--cmake", default="cmake")
    a = ap.parse_args()
    graph = link_graph(a.source, a.cmake)
    problems = []
    # One way: no module reaches itself.
    for m in graph:
        if m in closure(graph, m):
            problems.append(f"cycle: {m} reaches itself through {', '.join(graph[m])}")
    # Includes within the links.
    folders = sorted(MODULE_DIRS, key=len, reverse=True)
    for folder in MODULE_DIRS:
        m = target_of(folder)
        allowed = closure(graph, m) | {m}
        path = os.path.join(a.source, folder)
        for name in sorted(os.listdir(path)):
            if not name.endswith((".h", ".cpp")):
                continue
            for line_no, line in enumerate(open(os.path.join(path, name)), 1):
                inc = re.match(r'\s*#include "([^"]+)"', line)
                if not inc:
                    continue
                owner = next((f for f in folders if inc.group(1).startswith(f + "/")), None)
                if owner is None or target_of(owner) in allowed:
                    continue
                problems.append(f"{folder}/{name}:{line_no}: includes {inc.group(1)}, but {m} does not link "
                                f"{target_of(owner)}")
    print("module graph (each module: the modules it links directly), bottom to top:")
    order = [target_of(f) for f in MODULE_DIRS]
    for m in order:
        deps = [d.replace("skinmesh_", "") for d in graph[m]]
        print(f"  {m.replace('skinmesh_', ''):24s} -> {', '.join(deps) if deps else '(Eigen, threads)'}")
    for p in problems:
        print("problem: " + p)
    print(f"{len(graph)} modules, {sum(len(v) for v in graph.values())} links, "
          f"{'one-way' if not any(p.startswith('cycle') for p in problems) else 'NOT one-way'}; "
          f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
