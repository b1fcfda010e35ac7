#!/usr/bin/env python3
"""The share of inputs that needed the sweep's fallbacks, with the reasons (papers/front/patch.md).

    python3 bench/fallback_share.py build/skinmesh DIR_OR_FILE [...] [--probe P ...] [--jobs J]
                                    [--timeout S] [--mesh-arg=ARG ...] [--json FILE]

Meshes every molecule file (.pdb .ent .cif .mmcif .pqr .xyzr .xyzrn, optionally .gz) found in the folders given
(not recursively) or given by name, at every probe asked (default 1.4), J at a time, each on one thread:
`skinmesh mesh IN --probe P --threads 1 --timeout S -o TMP.ply --stats TMP.json -q` (the built-in check
included; the mesh is deleted at once). From each run's --stats it reads what the fallbacks did:

- the local patch (`patched_holes`): a region of the sweep re-meshed by restricted Delaunay, and why the sweep
  handed it over (`left_holes`: openings left for the seal, of which `folds`; `enlarged_holes` at the seal;
  `spent_vertices`: vertices that used up their departure budget);
- the whole-skin fallback (`static_fallback`): the skin meshed by the static baseline, with the sweep's error.

Prints one line per run that used a fallback or failed, then per probe the shares:
"N inputs: M meshed with every check passed; local patch in K (k %), whole-skin fallback in F (f %); E failed".
--json FILE writes every run's row and the summary, to watch the shares over time. Exit 0 unless an input
failed (exit code other than 0 from skinmesh, or a timeout).
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile
import time

EXTENSIONS = (".pdb", ".ent", ".cif", ".mmcif", ".pqr", ".xyzr", ".xyzrn")


def molecule_files(paths):
    files = []
    for p in paths:
        if os.path.isdir(p):
            for name in sorted(os.listdir(p)):
                base = name[:-3] if name.endswith(".gz") else name
                if base.lower().endswith(EXTENSIONS) and os.path.isfile(os.path.join(p, name)):
                    files.append(os.path.join(p, name))
        elif os.path.isfile(p):
            files.append(p)
        else:
            sys.exit(f"fallback_share.py: {p}: no such file or folder")
    return files


def run(binary, path, probe, timeout, extra):
    with tempfile.TemporaryDirectory(prefix="skinmesh_share_") as tmp:
        stats_path = os.path.join(tmp, "stats.json")
        cmd = [binary, "mesh", path, "--probe", str(probe), "--threads", "1", "-o", os.path.join(tmp, "m.ply"),
               "--stats", stats_path, "-q"] + list(extra)
        if timeout > 0:
            cmd += ["--timeout", str(timeout)]
        t0 = time.monotonic()
        # The mesher's own --timeout ends a run; the margin here only catches a process that ignores it.
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout + 60 if timeout > 0 else None)
            code, err = proc.returncode, proc.stderr.strip().splitlines()
        except subprocess.TimeoutExpired:
            code, err = "timeout", ["killed after %g s" % (timeout + 60)]
        seconds = time.monotonic() - t0
        row = {"input": path, "probe": probe, "exit": code, "seconds": round(seconds, 3),
               "error": err[-1] if code != 0 and err else ""}
        if os.path.exists(stats_path) and os.path.getsize(stats_path) > 0:
            with open(stats_path) as f:
                s = json.load(f)
            ops = s.get("operations", {})
            row.update({
                "atoms": s.get("atoms"),
                "triangles": s.get("triangles"),
                "checks_passed": s.get("checks_passed"),
                "patched_holes": ops.get("patched_holes", 0),
                "left_holes": ops.get("left_holes", 0),
                "folds": ops.get("folds", 0),
                "enlarged_holes": ops.get("enlarged_holes", 0),
                "reopened_holes": ops.get("reopened_holes", 0),
                "spent_vertices": ops.get("spent_vertices", 0),
                "static_fallback": s.get("static_fallback", ""),
            })
        return row


def reasons(row):
    parts = []
    if row.get("patched_holes"):
        why = ["%s %d" % (k, row[k]) for k in ("left_holes", "folds", "enlarged_holes", "spent_vertices") if row.get(k)]
        parts.append("local patch x%d (%s)" % (row["patched_holes"], ", ".join(why) or "at the seal"))
    elif row.get("left_holes") or row.get("spent_vertices"):
        parts.append("openings left for the seal %d, spent vertices %d, closed by the seal" %
                     (row.get("left_holes", 0), row.get("spent_vertices", 0)))
    if row.get("static_fallback"):
        parts.append("whole-skin fallback: " + row["static_fallback"])
    if row["exit"] != 0:
        parts.append("FAILED (exit %s): %s" % (row["exit"], row["error"]))
    return "; ".join(parts)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("binary")
    ap.add_argument("inputs", nargs="+", help="molecule files, or folders of them")
    ap.add_argument("--probe", type=float, action="append", help="probe radius in Å (repeatable; default 1.4)")
    ap.add_argument("--jobs", "-j", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--timeout", type=float, default=900, help="seconds per run (0: none; default 900)")
    ap.add_argument("--mesh-arg", action="append", default=[], help="an extra argument of skinmesh mesh")
    ap.add_argument("--json", help="write the rows and the summary here")
    a = ap.parse_args()
    files = molecule_files(a.inputs)
    if not files:
        sys.exit("fallback_share.py: no molecule files found")
    probes = a.probe or [1.4]
    binary = os.path.abspath(a.binary)
    jobs = [(f, p) for p in probes for f in files]
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        futures = [pool.submit(run, binary, f, p, a.timeout, a.mesh_arg) for f, p in jobs]
        for k, fut in enumerate(concurrent.futures.as_completed(futures), 1):
            row = fut.result()
            rows.append(row)
            why = reasons(row)
            if why:
                print("[%d/%d] %s probe %g: %s" % (k, len(jobs), row["input"], row["probe"], why), flush=True)
    summary = []
    for p in probes:
        rs = [r for r in rows if r["probe"] == p]
        n = len(rs)
        ok = sum(1 for r in rs if r["exit"] == 0 and r.get("checks_passed"))
        patched = sum(1 for r in rs if r.get("patched_holes"))
        whole = sum(1 for r in rs if r.get("static_fallback"))
        failed = sum(1 for r in rs if r["exit"] != 0)
        line = ("probe %g: %d inputs: %d meshed with every check passed; local patch in %d (%.1f %%), whole-skin "
                "fallback in %d (%.1f %%); %d failed" % (p, n, ok, patched, 100.0 * patched / n, whole,
                                                         100.0 * whole / n, failed))
        print(line)
        summary.append({"probe": p, "inputs": n, "passed": ok, "local_patch": patched, "whole_skin": whole,
                        "failed": failed})
    if a.json:
        rows.sort(key=lambda r: (r["probe"], r["input"]))
        with open(a.json, "w") as f:
            json.dump({"summary": summary, "runs": rows}, f, indent=1)
    return 1 if any(r["exit"] != 0 for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
