#!/usr/bin/env python3
"""bench/size_ladder.py: how skinmesh's time and memory grow with the input.

Runs `skinmesh mesh` (whole process, the built-in check included) on a ladder of
inputs from a ligand to a >= 10^5-atom assembly:

    ligand_1hpv_amprenavir (35 atoms) -> crambin_1crn (327) -> hivprotease_xk263_1hvr
    (1,890) -> src_kinase_2src (3,646) -> maltoporin_1af6 (10,123) -> k copies of
    maltoporin side by side (default k = 3 and 10: 30,369 and 101,230 atoms)
    [-> with --shell T, a shell of 60*T maltoporin copies placed by icosahedral
    symmetry, built by bench/assembly.py: one skin body; T = 2 gives 1,214,760 atoms]

The copies are translated along a grid with a 10 Å gap between their bounding boxes,
so each copy is its own skin component (the skin body of an atom is the ball of
radius r + probe, at most 1.85 + 1.4 Å); they are written as PDB files (serial
numbers modulo 100,000; skinmesh does not use them) into OUTDIR, never into the
repository.

For every input it records the stage times of `--stats` ("seconds"), the triangles,
the skin's bodies and cavities (the mesh's components by the sign of their volume),
the wall time and the peak resident memory of the process (`/usr/bin/time -f "%e %M"`);
the wall time leaves out what `--stats` alone adds, the exact area and volume of the
skin ("seconds.analytic", minutes on the shell),
and prints a Markdown table; results.csv and results.json go to OUTDIR. With
gnuplot on PATH (Debian `gnuplot-nox`) it also draws OUTDIR/size_ladder.png: seconds
against triangles, log-log, per stage and for the whole process, with a line of
slope 1 (linear scaling) for reference.

Usage:
    python3 bench/size_ladder.py build/skinmesh OUTDIR [--probe 1.4] [--copies 3,10]
                                 [--shell T] [--repeat 1] [--extra ARGS]
Standard library only; runs are sequential.
"""
import argparse
import csv
import json
import math
import os
import shutil
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(os.path.dirname(HERE), "data")

LADDER = [
    "ligand_1hpv_amprenavir.pdb",
    "crambin_1crn.pdb",
    "hivprotease_xk263_1hvr.pdb",
    "src_kinase_2src.pdb",
    "maltoporin_1af6.pdb",
]
STAGES = ["skin", "morse", "sweep", "refine", "angles", "output", "check", "normals"]


def atom_lines(path):
    """The ATOM/HETATM records of a PDB file (first model only)."""
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("ENDMDL"):
                break
            if line.startswith(("ATOM  ", "HETATM")):
                out.append(line.rstrip("\n"))
    return out


def tiled_copies(lines, k, gap=10.0):
    """k copies of the atoms on a near-square grid in the xy plane, `gap` Å apart."""
    xs = [float(l[30:38]) for l in lines]
    ys = [float(l[38:46]) for l in lines]
    dx = max(xs) - min(xs) + gap
    dy = max(ys) - min(ys) + gap
    nx = math.ceil(math.sqrt(k))
    out = []
    serial = 0
    for c in range(k):
        ox, oy = (c % nx) * dx, (c // nx) * dy
        for l in lines:
            serial += 1
            x, y = float(l[30:38]) + ox, float(l[38:46]) + oy
            if abs(x) >= 1e4 or abs(y) >= 1e4:
                sys.exit("size_ladder: a copy would not fit the PDB coordinate field")
            out.append(l[:6] + f"{serial % 100000:5d}" + l[11:30] + f"{x:8.3f}{y:8.3f}" + l[46:])
        out.append("TER")
    out.append("END")
    return out


def run_one(skinmesh, path, outdir, probe, extra):
    name = os.path.splitext(os.path.basename(path))[0]
    stats = os.path.join(outdir, name + ".json")
    mesh = os.path.join(outdir, name + ".ply")
    cmd = ["/usr/bin/time", "-f", "%e %M", skinmesh, "mesh", path, "-o", mesh, "--probe", str(probe), "-q",
           "--stats", stats] + extra
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return {"input": name, "status": f"exit {p.returncode}: {p.stderr.strip().splitlines()[-2:]}"}
    wall, kb = p.stderr.strip().splitlines()[-1].split()
    with open(stats) as f:
        s = json.load(f)
    os.remove(mesh)
    parts = s.get("surface", {}).get("components", [])
    row = {"input": name, "status": "ok" if s.get("checks_passed") else "CHECK FAILED", "atoms": s.get("atoms"),
           "triangles": s["triangles"], "min_angle_deg": s["min_angle_deg"],
           "bodies": sum(1 for c in parts if c.get("kind") == "body"),
           "cavities": sum(1 for c in parts if c.get("kind") == "cavity"),
           "wall_s": float(wall) - s["seconds"].get("analytic", 0.0), "peak_mb": int(kb) / 1024.0}
    for st in STAGES:
        row[st + "_s"] = s["seconds"].get(st, 0.0)
    row["meshing_s"] = sum(row[st + "_s"] for st in STAGES if st != "check")
    return row


def median_row(rows):
    if any(r["status"] != "ok" for r in rows):
        return next(r for r in rows if r["status"] != "ok")
    out = dict(rows[0])
    for k, v in rows[0].items():
        if isinstance(v, float):
            out[k] = statistics.median(r[k] for r in rows)
    return out


def plot(rows, outdir):
    if not shutil.which("gnuplot"):
        print("size_ladder: gnuplot not on PATH (Debian gnuplot-nox), no plot drawn", file=sys.stderr)
        return
    dat = os.path.join(outdir, "size_ladder.dat")
    with open(dat, "w") as f:
        f.write("# triangles wall " + " ".join(STAGES) + "\n")
        for r in rows:
            if r["status"] == "ok":
                f.write(f"{r['triangles']} {r['wall_s']} " + " ".join(f"{max(r[s + '_s'], 1e-4)}" for s in STAGES) +
                        "\n")
    png = os.path.join(outdir, "size_ladder.png")
    cols = " ,\\\n  ".join(f"'{dat}' using 1:{i + 3} with linespoints title '{s}'" for i, s in enumerate(STAGES))
    first = next(r for r in rows if r["status"] == "ok")
    script = f"""set terminal png size 900,600
set output '{png}'
set logscale xy
set xlabel 'triangles'
set ylabel 'seconds'
set key left top
set grid
set title 'skinmesh mesh: time against output size (whole process and per stage)'
plot '{dat}' using 1:2 with linespoints lw 2 lc rgb 'red' title 'whole process', \\
  {cols}, \\
  {first['wall_s']} * x / {first['triangles']} with lines dashtype 2 lc rgb 'black' title 'slope 1 (linear)'
"""
    gp = os.path.join(outdir, "size_ladder.gp")
    with open(gp, "w") as f:
        f.write(script)
    subprocess.run(["gnuplot", gp], check=True)
    print(f"size_ladder: wrote {png}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("skinmesh")
    ap.add_argument("outdir")
    ap.add_argument("--probe", type=float, default=1.4)
    ap.add_argument("--copies", default="3,10", help="maltoporin copies of the largest rungs (comma list)")
    ap.add_argument("--shell", type=int, default=0,
                    help="add a rung: a shell of 60*T maltoporin copies (bench/assembly.py shell --t T; "
                         "T = 2: 1,214,760 atoms, one body, about 11.5 GB and 10 minutes on 2 cores); 0: none")
    ap.add_argument("--repeat", type=int, default=1, help="runs per input; the table shows medians")
    ap.add_argument("--extra", default="", help="more skinmesh mesh options, one string")
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    inputs = [os.path.join(DATA, f) for f in LADDER]
    malt = atom_lines(os.path.join(DATA, "maltoporin_1af6.pdb"))
    for k in [int(c) for c in a.copies.split(",") if c.strip()]:
        p = os.path.join(a.outdir, f"maltoporin_x{k}.pdb")
        with open(p, "w") as f:
            f.write("\n".join(tiled_copies(malt, k)) + "\n")
        inputs.append(p)
    if a.shell > 0:
        p = os.path.join(a.outdir, f"maltoporin_shell_t{a.shell}.pdb")
        with open(p, "w") as f:
            subprocess.run([sys.executable, os.path.join(HERE, "assembly.py"), "shell", "--protein",
                            os.path.join(DATA, "maltoporin_1af6.pdb"), "--t", str(a.shell)], stdout=f, check=True)
        inputs.append(p)
    rows = []
    for path in inputs:
        runs = [run_one(a.skinmesh, path, a.outdir, a.probe, a.extra.split()) for _ in range(a.repeat)]
        r = median_row(runs)
        rows.append(r)
        print(f"size_ladder: {r['input']}: {r['status']}", file=sys.stderr)
    with open(os.path.join(a.outdir, "results.json"), "w") as f:
        json.dump(rows, f, indent=1)
    keys = ["input", "status", "atoms", "triangles", "bodies", "cavities", "min_angle_deg", "wall_s", "peak_mb"] + \
        [s + "_s" for s in STAGES] + ["meshing_s"]
    with open(os.path.join(a.outdir, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, restval="", extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    print(f"| input | atoms | triangles | bodies + cavities | min angle | skin | Morse | sweep | refine | angles | "
          f"output | check | meshing s | triangles/s | whole process s | peak MB | bytes/triangle | status |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in rows:
        if r["status"] != "ok" and "triangles" not in r:
            print(f"| {r['input']} | | | | | | | | | | | | | | | | | {r['status']} |")
            continue
        st = " | ".join(f"{r[s + '_s']:.3g}" for s in STAGES)
        print(f"| {r['input']} | {r['atoms']:,} | {r['triangles']:,} | {r['bodies']} + {r['cavities']} | "
              f"{r['min_angle_deg']:.1f}° | {st} | "
              f"{r['meshing_s']:.3g} | {r['triangles'] / r['meshing_s']:,.0f} | {r['wall_s']:.2f} | "
              f"{r['peak_mb']:.0f} | {r['peak_mb'] * 1048576 / r['triangles']:.0f} | {r['status']} |")
    plot(rows, a.outdir)


if __name__ == "__main__":
    main()
