#!/usr/bin/env python3
"""Meshes inputs in many random height directions, with and without the fallback (papers/front/patch.md).

    python3 bench/sweep_directions.py build/skinmesh IN [IN ...] [--probe P ...] [--directions N] [--seed S]
                                      [--no-fallback-too] [--mesh-arg=ARG ...] [--out FILE]

For every input, probe and direction (N unit vectors drawn uniformly from random.Random(S)), runs
`skinmesh mesh IN --probe P --direction X,Y,Z -o TMP.ply --stats TMP.json` (the built-in check included: exit 0
means every check passed; --mesh-arg adds arguments, e.g. --mesh-arg=--no-patch) and prints one Markdown row:
the input, the probe, the direction, the exit code, the triangle count, the fallback's patches, its openings
left for the seal plus its folds, "yes" if the whole skin was meshed by the static baseline
(papers/mesher/pipeline.md), the seconds, and the last line of stderr on a failure. With --no-fallback-too the
runs that used a fallback are repeated with --no-fallback, to show that they fail without it. Ends with one
summary line per input and probe: "ok N/M, fallback in K, failing without it F/K".
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time


def directions(n, seed):
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        z = rng.uniform(-1, 1)
        phi = rng.uniform(0, 2 * math.pi)
        s = math.sqrt(max(0.0, 1 - z * z))
        out.append((s * math.cos(phi), s * math.sin(phi), z))
    return out


def run(binary, inp, probe, d, tmp, extra=()):
    mesh = os.path.join(tmp, "out.ply")
    stats = os.path.join(tmp, "stats.json")
    for p in (mesh, stats):
        if os.path.exists(p):
            os.remove(p)
    cmd = [binary, "mesh", inp, "--probe", str(probe), "--direction", "%.6f,%.6f,%.6f" % d, "-o", mesh,
           "--stats", stats, "--quiet", *extra]
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.time() - t0
    tris = patched = left = 0
    static = ""
    if r.returncode == 0 and os.path.exists(stats):
        with open(stats) as f:
            j = json.load(f)
        tris = j.get("triangles", 0)
        ops = j.get("operations", {})
        patched, left = ops.get("patched_holes", 0), ops.get("left_holes", 0) + ops.get("folds", 0)
        static = "yes" if "static_fallback" in j else ""
    err = (r.stderr.strip().splitlines() or [""])[-1][:160] if r.returncode else ""
    return r.returncode, tris, patched, left, static, seconds, err


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary")
    ap.add_argument("inputs", nargs="+")
    ap.add_argument("--probe", type=float, action="append")
    ap.add_argument("--directions", type=int, default=20)
    ap.add_argument("--seed", type=int, default=25)
    ap.add_argument("--no-fallback-too", action="store_true")
    ap.add_argument("--mesh-arg", action="append", default=[],
                    help="one more argument of every `skinmesh mesh` run (e.g. --mesh-arg=--no-patch)")
    ap.add_argument("--out")
    a = ap.parse_args()
    probes = a.probe or [1.4]
    rows = ["| input | probe | direction | exit | triangles | patches | left | static | s | error |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    summary = []
    with tempfile.TemporaryDirectory() as tmp:
        for inp in a.inputs:
            for probe in probes:
                ok = used = failing_without = 0
                dirs = directions(a.directions, a.seed)
                for d in dirs:
                    code, tris, patched, left, static, s, err = run(a.binary, inp, probe, d, tmp, a.mesh_arg)
                    ok += code == 0
                    row = "| %s | %g | %.6f,%.6f,%.6f | %d | %d | %d | %d | %s | %.1f | %s |" % (
                        os.path.basename(inp), probe, *d, code, tris, patched, left, static, s, err)
                    rows.append(row)
                    print(row, flush=True)
                    if patched + left > 0 or static:
                        used += 1
                        if a.no_fallback_too:
                            code2, _, _, _, _, s2, err2 = run(a.binary, inp, probe, d, tmp, ("--no-fallback",))
                            failing_without += code2 != 0
                            row = "| %s | %g | %.6f,%.6f,%.6f --no-fallback | %d | | | | | %.1f | %s |" % (
                                os.path.basename(inp), probe, *d, code2, s2, err2)
                            rows.append(row)
                            print(row, flush=True)
                line = "%s probe %g: ok %d/%d, fallback in %d%s" % (
                    os.path.basename(inp), probe, ok, len(dirs), used,
                    ", failing without it %d/%d" % (failing_without, used) if a.no_fallback_too else "")
                summary.append(line)
                print(line, flush=True)
    if a.out:
        with open(a.out, "w") as f:
            f.write("\n".join(rows + [""] + summary) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
