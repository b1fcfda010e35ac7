#!/usr/bin/env python3
"""Digests of everything skinmesh writes, for refactors that must keep every output byte-identical.

    python3 bench/output_digests.py build/skinmesh [--quick] [--out FILE]

Meshes every bundled molecule (data/) at probes 1.4 and 0 and every test input (tests/data, regressions
included) at both probes with the sweep; the small inputs with the dynamic-skin baseline (growth and static);
crambin in every output format; records a trace and runs `info` and `check`. For each run it prints one
Markdown table row: the input, the run, the exit code, the triangle count, the md5 of the written file(s)
and the md5 of the `--stats` JSON with its timings (seconds, peak memory) and output path left out. Two
binaries give the same rows exactly when their outputs are the same. --quick leaves out the probe-0 runs of
the two largest molecules. --ignore KEY,KEY leaves more keys out of the --stats digests, to compare binaries
across a schema that gained keys (every other value must still agree).
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "data")
TEST_DATA = os.path.join(ROOT, "tests", "data")
# Keys whose values depend on the clock or the machine, not on the computation.
TIMING_KEYS = {"seconds", "peak_memory_bytes", "peak_memory_bytes_per_stage", "output"}
LARGE = {"maltoporin_1af6.pdb", "src_kinase_2src.pdb"}
IGNORED = set()


def md5(path):
    h = hashlib.md5()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k not in TIMING_KEYS | IGNORED}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def stats_digest(path):
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        return "-"
    with open(path) as f:
        text = json.dumps(without_timings(json.load(f)), sort_keys=True)
    return hashlib.md5(text.encode()).hexdigest()


def run(binary, args, outputs, stats, tmp):
    """Runs `binary args`; returns (exit code, triangles, md5 of the outputs, md5 of the stats)."""
    for p in outputs + ([stats] if stats else []):
        if os.path.exists(p):
            os.remove(p)
    proc = subprocess.run([binary] + args, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    triangles = "-"
    digests = []
    for p in outputs:
        digests.append(md5(p) if os.path.exists(p) else "-")
    if stats and os.path.exists(stats) and os.path.getsize(stats) > 0:
        with open(stats) as f:
            triangles = json.load(f).get("triangles", "-")
    if proc.returncode != 0:  # the refusal's message is an output too
        digests.append(hashlib.md5(proc.stderr).hexdigest()[:12] + "(stderr)")
    if not outputs and proc.returncode == 0:  # a report on stdout
        digests.append(hashlib.md5(proc.stdout).hexdigest())
    return proc.returncode, triangles, " ".join(digests), stats_digest(stats) if stats else "-"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("binary")
    ap.add_argument("--quick", action="store_true", help="skip the probe-0 runs of the two largest molecules")
    ap.add_argument("--out", help="also write the table to this file")
    ap.add_argument("--ignore", default="", help="comma-separated --stats keys to leave out of the digests")
    a = ap.parse_args()
    IGNORED.update(k for k in a.ignore.split(",") if k)
    binary = os.path.abspath(a.binary)
    rows = ["| input | run | exit | triangles | md5 of the output | md5 of --stats (no timings) |",
            "|---|---|---|---|---|---|"]

    def emit(name, label, result):
        code, tri, dig, st = result
        rows.append(f"| {name} | {label} | {code} | {tri} | {dig} | {st} |")
        print(rows[-1], flush=True)

    print("\n".join(rows), flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "m.ply")
        stats = os.path.join(tmp, "s.json")
        molecules = sorted(f for f in os.listdir(DATA) if f.endswith((".pdb", ".pqr")))
        tests = sorted(os.path.join("tests/data", f) for f in os.listdir(TEST_DATA) if f.endswith(".xyzr"))
        tests += sorted(os.path.join("tests/data/regression", f)
                        for f in os.listdir(os.path.join(TEST_DATA, "regression")) if f.endswith(".xyzr"))
        inputs = [os.path.join("data", f) for f in molecules] + tests
        for rel in inputs:
            for probe in ("1.4", "0"):
                if a.quick and probe == "0" and os.path.basename(rel) in LARGE:
                    continue
                emit(rel, f"sweep probe {probe}",
                     run(binary, ["mesh", os.path.join(ROOT, rel), "-o", out, "--probe", probe, "--stats", stats,
                                  "-q"], [out], stats, tmp))
        small = tests + ["data/ligand_1hpv_amprenavir.pdb"]
        for rel in small:
            for label, extra in (("dynamic static probe 1.4", ["--no-growth"]), ("dynamic growth probe 1.4", [])):
                if "regression" in rel and extra == []:
                    continue  # growth on the regression inputs takes minutes
                emit(rel, label, run(binary, ["mesh", os.path.join(ROOT, rel), "-o", out, "--algorithm", "dynamic",
                                              "--stats", stats, "-q"] + extra, [out], stats, tmp))
        crambin = os.path.join(DATA, "crambin_1crn.pdb")
        for ext in ("ply", "off", "obj", "stl", "vtk"):
            path = os.path.join(tmp, "c." + ext)
            emit("data/crambin_1crn.pdb", f"format .{ext}",
                 run(binary, ["mesh", crambin, "-o", path, "-q"], [path], None, tmp))
        vert, face = os.path.join(tmp, "c.vert"), os.path.join(tmp, "c.face")
        emit("data/crambin_1crn.pdb", "format .vert/.face",
             run(binary, ["mesh", crambin, "-o", vert, "-q"], [vert, face], None, tmp))
        ply = os.path.join(tmp, "c.ply")
        run(binary, ["mesh", crambin, "-o", ply, "-q"], [ply], None, tmp)
        emit("data/crambin_1crn.pdb", "check of its mesh", run(binary, ["check", crambin, ply], [], None, tmp))
        for rel in ("data/crambin_1crn.pdb", "tests/data/cube_corners.xyzr"):
            emit(rel, "info", run(binary, ["info", os.path.join(ROOT, rel)], [], None, tmp))
        trace = os.path.join(tmp, "t.json")
        for rel in ("tests/data/cube_corners.xyzr", "data/ligand_1hpv_amprenavir.pdb"):
            emit(rel, "trace .json", run(binary, ["trace", os.path.join(ROOT, rel), "-o", trace, "-q"], [trace],
                                         None, tmp))
    if a.out:
        with open(a.out, "w") as f:
            f.write("\n".join(rows) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
