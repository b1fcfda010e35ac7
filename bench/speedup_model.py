#!/usr/bin/env python3
"""bench/speedup_model.py: the speed-up of `skinmesh mesh` on 1-64 cores, predicted from measured costs.

This machine has two cores; issue #26 asks what the decomposed sweep would give on 4, 16 or 64. The script
measures, and then simulates:

1. It runs `skinmesh mesh IN --slabs N --stats S.json` with --threads 1 and --threads 2 (each --repeat times,
   runs alternated, medians taken) and reads the stage seconds and the decomposed sweep's parts
   ("seconds" / "sweep_parts": each slab's sweep, the bands, the glue; "decomposition" / "slab_triangles").
2. It predicts the whole process's seconds on P cores under two models:
   - "today": the code as it is. The slabs are list-scheduled in slab order on P workers, exactly as
     core/parallel.h's parallel_for hands them out (the next slab to the first free worker), so the sweep's
     critical path is its slowest chain of slabs; the bands are shared over min(P, cuts) workers; the glue
     and the rest of the sweep stage stay serial. The other stages run with the parallelism they have today,
     mostly two tasks side by side, so for P >= 2 they are held at their measured 2-thread seconds (a
     lower bound of today's speed-up beyond two cores).
   - "per region": the design of papers/decompose/README.md carried through every stage (skin, Morse-Smale
     complex, refinement, angles, check per region, increment 6). Each of those stages' 1-thread seconds is
     split over the slabs in proportion to their triangles and list-scheduled with the slabs' sweeps;
     reading, the output conversion, writing, the bands and the glue stay serial. Where that is slower than
     "today" (few slabs), today's schedule is taken.
   - "balanced": as "per region", but with the regions' work cut into 4 P equal slabs, the decomposition the
     cut choice would need to find (today it finds fewer, unequal ones): the ceiling the serial parts set. The
     seams are the measured ones, so for an input the cut choice left whole (no seams) it is an underestimate.
   The speed-up is the model's 1-core seconds over its P-core seconds (the 1-core prediction is the sum of the
   measured stages; the measured whole process is printed beside it). At P = 2 the "today" prediction of the
   sweep is checked against the measured 2-thread sweep (printed).
3. It prints a Markdown table, writes OUTDIR/speedup.json and, with gnuplot on PATH (Debian gnuplot-nox),
   OUTDIR/speedup.png: speed-up against cores, log-log, with the ideal line.

Usage:
    python3 bench/speedup_model.py build/skinmesh OUTDIR [--input data/maltoporin_1af6.pdb] [--probe 1.4]
                                   [--slabs 64] [--repeat 1] [--cores 1,2,4,8,16,32,64] [--extra ARGS]
                                   [--reuse]
`--input` may be given several times (each gets a line per model). Standard library only; runs are sequential.
"""
import argparse
import heapq
import json
import os
import shutil
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
# The stages that would run per region in the "per region" model; the others stay serial.
REGION_STAGES = ["skin", "morse", "refine", "angles", "check"]
SERIAL_STAGES = ["read", "output", "write"]
MODELS = ["today", "regions", "balanced"]
MODEL_TITLES = {"today": "today", "regions": "per region", "balanced": "balanced regions"}


def run(skinmesh, path, outdir, probe, slabs, threads, extra, reuse=False):
    """The --stats summary of one run (the mesh is written to OUTDIR and removed); with `reuse`, the summary an
    earlier run left in OUTDIR if there is one."""
    name = os.path.splitext(os.path.basename(path))[0]
    stats = os.path.join(outdir, f"{name}.t{threads}.json")
    mesh = os.path.join(outdir, f"{name}.t{threads}.ply")
    if reuse and os.path.exists(stats):
        with open(stats) as f:
            return json.load(f)
    cmd = [skinmesh, "mesh", path, "-o", mesh, "--probe", str(probe), "--slabs", str(slabs), "--threads",
           str(threads), "-q", "--stats", stats] + extra
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"speedup_model: {' '.join(cmd)} failed (exit {p.returncode}): {p.stderr.strip()[-400:]}")
    with open(stats) as f:
        s = json.load(f)
    if os.path.exists(mesh):
        os.remove(mesh)
    if not s.get("checks_passed"):
        sys.exit(f"speedup_model: {path}: the mesh failed its checks; no model of a failing run")
    return s


def median_stats(runs):
    """Per stage and per slab, the median over the runs (the slabs are the same: the cuts depend on the input)."""
    out = {"seconds": {}, "slabs": [], "triangles": runs[0]["triangles"], "atoms": runs[0]["atoms"]}
    for stage in runs[0]["seconds"]:
        if stage == "sweep_parts":
            continue
        out["seconds"][stage] = statistics.median(r["seconds"][stage] for r in runs)
    parts = [r["seconds"].get("sweep_parts") for r in runs]
    if parts[0]:
        n = len(parts[0]["slabs"])
        out["slabs"] = [statistics.median(p["slabs"][k] for p in parts) for k in range(n)]
        for key in ("bands", "glue", "retried"):
            out[key] = statistics.median(p[key] for p in parts)
        out["slab_triangles"] = runs[0]["decomposition"]["slab_triangles"]
    else:  # one sweep: one slab, no seams
        out["slabs"] = [out["seconds"]["sweep"]]
        out["bands"] = out["glue"] = out["retried"] = 0.0
        out["slab_triangles"] = [runs[0]["triangles"]]
    return out


def makespan(tasks, workers):
    """Seconds for `tasks` (seconds each) handed out in order, each to the first free of `workers` workers."""
    free = [0.0] * max(1, workers)
    for t in tasks:
        heapq.heapreplace(free, free[0] + t)
    return max(free)


def stage(m, name):
    return m["seconds"].get(name, 0.0)


def sweep_rest(m):
    """The sweep stage's seconds outside the slabs, the bands and the glue (cut bookkeeping, the retried slabs)."""
    return max(0.0, stage(m, "sweep") - sum(m["slabs"]) - m["bands"] - m["glue"])


def predict_today(one, two, p):
    """Whole-process seconds on p cores with today's code (see the module's comment)."""
    cuts = max(1, len(one["slabs"]) - 1)
    sweep = makespan(one["slabs"], p) + one["bands"] / min(p, cuts) + one["glue"] + sweep_rest(one)
    ref = one if p == 1 else two
    others = sum(stage(ref, s) for s in ("skin", "morse", "refine", "angles", "check") + tuple(SERIAL_STAGES))
    return others + sweep


def predict_regions(one, two, p):
    """Whole-process seconds on p cores with every region stage per slab (see the module's comment), or today's
    schedule where it is faster (few slabs: the stages' own threads beat one region per core)."""
    return min(predict_today(one, two, p), regions_only(one, p))


def regions_only(one, p):
    """predict_regions() without today's schedule."""
    tris = one["slab_triangles"]
    total_tris = float(sum(tris)) or 1.0
    per_region = sum(stage(one, s) for s in REGION_STAGES)
    tasks = [sweep + per_region * t / total_tris for sweep, t in zip(one["slabs"], tris)]
    cuts = max(1, len(tasks) - 1)
    serial = serial_seconds(one)
    return makespan(tasks, p) + one["bands"] / min(p, cuts) + serial


def serial_seconds(one):
    """The seconds no model splits: reading, the output conversion, writing, the glue, the sweep's rest."""
    return sum(stage(one, s) for s in SERIAL_STAGES) + one["glue"] + sweep_rest(one)


def predict_balanced(one, p):
    """As predict_regions(), the regions' work cut into 4 p equal slabs."""
    work = sum(one["slabs"]) + sum(stage(one, s) for s in REGION_STAGES)
    if p == 1:
        return work + one["bands"] + serial_seconds(one)
    return work / p + one["bands"] / p + serial_seconds(one)


def plot(results, cores, outdir):
    if not shutil.which("gnuplot"):
        print("speedup_model: gnuplot not on PATH (Debian gnuplot-nox), no plot drawn", file=sys.stderr)
        return
    dat = os.path.join(outdir, "speedup.dat")
    with open(dat, "w") as f:
        f.write("# cores " + " ".join(f"{r['name']}:{m}" for r in results for m in MODELS) + "\n")
        for i, p in enumerate(cores):
            f.write(f"{p} " + " ".join(f"{r[m][i]['speedup']}" for r in results for m in MODELS) + "\n")
    png = os.path.join(outdir, "speedup.png")
    lines = ["x with lines lc rgb 'gray' dt 2 title 'ideal'"]
    for k, r in enumerate(results):
        label = f"{r['name']} ({len(r['one']['slabs'])} slabs)"
        for j, (m, dt) in enumerate(zip(MODELS, (1, 3, 2))):
            col = 2 + len(MODELS) * k + j
            lines.append(f"'{dat}' using 1:{col} with linespoints lw 2 dt {dt} title '{label}, {MODEL_TITLES[m]}'")
    script = f"""set terminal pngcairo size 900,600 noenhanced
set output '{png}'
set logscale xy 2
set xrange [1:{max(cores)}]
set yrange [1:{max(cores)}]
set xlabel 'cores'
set ylabel 'speed-up of the whole process (predicted 1-core / P-core seconds)'
set key left top
set grid
set title 'skinmesh mesh: predicted speed-up from measured per-slab costs (bench/speedup_model.py)'
plot {", ".join(lines)}
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    print(f"speedup_model: wrote {png}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("skinmesh")
    ap.add_argument("outdir")
    ap.add_argument("--input", action="append", help="molecule file (repeatable; default maltoporin)")
    ap.add_argument("--probe", type=float, default=1.4)
    ap.add_argument("--slabs", type=int, default=64, help="slabs asked for (fewer are found where no cut is "
                    "admissible)")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--cores", default="1,2,4,8,16,32,64")
    ap.add_argument("--extra", default="", help="more arguments for skinmesh mesh, space-separated")
    ap.add_argument("--reuse", action="store_true", help="model the summaries an earlier run left in OUTDIR "
                    "(with --repeat 1) instead of running again")
    a = ap.parse_args()
    if a.reuse and a.repeat != 1:
        sys.exit("speedup_model: --reuse models one run per thread count: use it with --repeat 1")
    inputs = a.input or [os.path.join(ROOT, "data", "maltoporin_1af6.pdb")]
    cores = [int(c) for c in a.cores.split(",")]
    if not cores or min(cores) < 1:
        sys.exit("speedup_model: --cores takes positive counts, e.g. 1,2,4")
    os.makedirs(a.outdir, exist_ok=True)
    extra = a.extra.split()
    results = []
    for path in inputs:
        runs = {1: [], 2: []}
        for _ in range(a.repeat):
            for t in (1, 2):  # alternated, so a slow spell of the machine hits both
                runs[t].append(run(a.skinmesh, path, a.outdir, a.probe, a.slabs, t, extra, a.reuse))
        one, two = median_stats(runs[1]), median_stats(runs[2])
        name = os.path.splitext(os.path.basename(path))[0]
        t1 = stage(one, "total")
        r = {"name": name, "atoms": one["atoms"], "triangles": one["triangles"], "one": one, "two": two,
             "measured_total_1": t1, "measured_total_2": stage(two, "total"), "today": [], "regions": [],
             "balanced": [], "serial": serial_seconds(one)}
        for model, f in (("today", lambda q: predict_today(one, two, q)), ("regions", lambda q: predict_regions(
                one, two, q)), ("balanced", lambda q: predict_balanced(one, q))):
            base = f(1)
            r[model + "_1"] = base
            for p in cores:
                s = f(p)
                r[model].append({"cores": p, "seconds": s, "speedup": base / s})
        cuts = max(1, len(one["slabs"]) - 1)
        r["sweep_2_predicted"] = makespan(one["slabs"], 2) + one["bands"] / min(2, cuts) + one["glue"] + sweep_rest(
            one)
        r["sweep_2_measured"] = stage(two, "sweep")
        r["critical_path_today"] = predict_today(one, two, 10 ** 9)
        r["critical_path_regions"] = predict_regions(one, two, 10 ** 9)
        results.append(r)

    with open(os.path.join(a.outdir, "speedup.json"), "w") as f:
        json.dump(results, f, indent=1)
    for r in results:
        one = r["one"]
        print(f"\n{r['name']}: {r['atoms']} atoms, {r['triangles']} triangles, {len(one['slabs'])} slabs "
              f"(--slabs {a.slabs}); measured whole process {r['measured_total_1']:.2f} s on 1 thread, "
              f"{r['measured_total_2']:.2f} s on 2")
        print(f"slabs' sweeps (1 thread): " + ", ".join(f"{s:.3f}" for s in one["slabs"]) +
              f" s; bands {one['bands']:.3f} s, glue {one['glue']:.3f} s, retried {one['retried']:.3f} s")
        print(f"model on 1 core: {r['today_1']:.2f} s (the stages' sum)")
        print(f"sweep on 2 threads: predicted {r['sweep_2_predicted']:.3f} s, measured {r['sweep_2_measured']:.3f} s")
        print(f"critical path (unbounded cores): today {r['critical_path_today']:.2f} s, per region "
              f"{r['critical_path_regions']:.2f} s; serial in every model (read, output, write, glue, the "
              f"sweep's rest) {r['serial']:.2f} s\n")
        print("| cores | " + " | ".join(f"{MODEL_TITLES[m]}: seconds | speed-up" for m in MODELS) + " |")
        print("|---:|" + "---:|---:|" * len(MODELS))
        for i, p in enumerate(cores):
            print(f"| {p} | " + " | ".join(f"{r[m][i]['seconds']:.2f} | {r[m][i]['speedup']:.2f}" for m in MODELS) +
                  " |")
    plot(results, cores, a.outdir)


if __name__ == "__main__":
    main()
