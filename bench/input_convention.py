#!/usr/bin/env python3
"""bench/input_convention.py: which input convention did Cheng & Shi 2004 use for Table 1?

Measures, with the skinmesh command line at the paper's sizing (C = 0.08, Q = 1.65,
the defaults), the triangle count and minimum angle of the Table 1 stand-ins in
data/ (data/README.md) under several input conventions:

  * radii table and hydrogens:
      bondi      Bondi 1964 by element, heavy atoms only (what skinmesh does with these files)
      bondi+H    Bondi 1964 by element, hydrogens added (H 1.20)
      united     united-atom radii (the Connolly/MSMS values that MSMS's atmtypenumbers
                 uses): heavy atoms only, radius by element and number of attached H:
                 C 1.74 (no H), 1.86 (sp2 CH), 2.00 (sp3 CH, CH2, CH3); N 1.54 / 1.70 /
                 1.80 / 2.00 for 0 / 1 / 2 / 3 H; O 1.40 (no H), 1.60 (OH); S 1.80, SH 1.85;
                 P 1.80
      parse      PARSE (Sitkoff, Sharp & Honig 1994; the radii of data/crambin_1crn.pqr):
                 C 1.70 (no H) / 2.00 (with H), N 1.50, O 1.40, S 1.85, polar H 1.00,
                 H on carbon dropped (radius 0); P and Br, which PARSE lacks, get Bondi's
  * probe radius p (atom weight w = 2 (r + p)^2): 0 ... 1.4 Å.

It compares the counts with Table 1 (pdb7tmn 24,336 triangles, A-DNA 114,316, Gramicidin A
305,186) and prints the tables behind papers/bench/input_convention.md.

Hydrogens are placed by Open Babel (`obabel IN.pdb -O OUT.pdb -h`; the study used Open
Babel 3.1.1, Debian package `openbabel`). Open Babel is a measurement tool here, not a
dependency of the project: without `obabel` on PATH the script measures the `bondi`
convention only and says so. The hydrogens also give the H counts of the united-atom and
PARSE tables. Open Babel protonates the non-bridging phosphate oxygens of the DNA; those
60 H are removed (DNA is a polyanion in water).

Every variant is written as .xyzr (x y z r per line) into OUTDIR; nothing is written into
the repository. Runs are sequential, under `nice`.

Usage (a few minutes on one core):
    python3 bench/input_convention.py build/skinmesh OUTDIR > OUTDIR.md
Output: OUTDIR/results.json (every run) and the tables on stdout (Markdown).
Standard library only.
"""
import argparse
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(REPO, "data")

# Cheng & Shi 2004, Table 1: triangles, minimum angle (degrees).
PAPER = {
    "pdb7tmn": (24336, 27.02),
    "A-DNA": (114316, 24.12),
    "Gramicidin A": (305186, 24.37),
}

# (key, file, Table 1 molecule it stands in for)
MOLECULES = [
    ("amprenavir", "ligand_1hpv_amprenavir.pdb", "pdb7tmn"),
    ("xk263", "ligand_1hvr_xk263.pdb", "pdb7tmn"),
    ("2zmm", "ligand_2zmm.pdb", "pdb7tmn"),
    ("gramicidin", "gramicidinA_1grm_model1.pdb", "Gramicidin A"),
    ("adna30", "adna_3dna_fiber_30bp.pdb", "A-DNA"),
]
# Shorter A-DNA helices cut from the 30 bp fiber (strand A residues 1..n and their
# partners 61-n..60 of strand B) give the triangles per base pair.
ADNA_LENGTHS = (10, 20)

DIRECTIONS = ("1,0,0", "0,0,1", "0.3,0.5,0.8")  # besides the default (near +y)
PROBES = (0.0, 0.05, 0.1, 0.2, 0.25, 0.3, 0.4, 0.5, 0.75, 1.0, 1.4)
CONVENTIONS = ("bondi", "bondi+H", "united", "parse")

BONDI = {"H": 1.20, "C": 1.70, "N": 1.55, "O": 1.52, "P": 1.80, "S": 1.80, "BR": 1.85}
COVALENT = {"H": 0.31, "C": 0.76, "N": 0.71, "O": 0.66, "P": 1.07, "S": 1.05, "BR": 1.20}
WATERS = {"HOH", "WAT", "H2O", "DOD", "TIP", "TIP3", "SOL"}


# ----------------------------------------------------------------------------- reading

class Atom:
    __slots__ = ("x", "y", "z", "el", "name", "res", "chain", "resnum", "nh", "nheavy")

    def __init__(self, x, y, z, el, name, res, chain, resnum):
        self.x, self.y, self.z = x, y, z
        self.el, self.name, self.res, self.chain, self.resnum = el, name, res, chain, resnum
        self.nh = 0  # hydrogens attached
        self.nheavy = 0  # heavy atoms bonded


def read_pdb(path):
    """ATOM/HETATM records of the first model, waters dropped. Element from columns 77-78,
    else the first letter of the atom name (enough for the bundled files)."""
    atoms = []
    with open(path) as f:
        for line in f:
            rec = line[:6]
            if rec.startswith("ENDMDL"):
                break
            if rec not in ("ATOM  ", "HETATM"):
                continue
            res = line[17:20].strip()
            if res in WATERS:
                continue
            name = line[12:16].strip()
            el = line[76:78].strip().upper() if len(line) >= 78 else ""
            if not el or not el.isalpha():
                el = name.lstrip("0123456789")[0].upper()
            if el == "D":
                el = "H"
            if el not in BONDI:
                sys.exit(f"{path}: element {el!r} of atom {name!r} not in the radii tables")
            atoms.append(Atom(float(line[30:38]), float(line[38:46]), float(line[46:54]),
                              el, name, res, line[21], int(line[22:26])))
    return atoms


def dist2(a, b):
    return (a.x - b.x) ** 2 + (a.y - b.y) ** 2 + (a.z - b.z) ** 2


def bonds(atoms):
    """Covalent bonds by distance (sum of covalent radii + 0.45 Å), through a 2.5 Å grid."""
    cell = 2.5
    grid = {}
    for i, a in enumerate(atoms):
        grid.setdefault((int(a.x // cell), int(a.y // cell), int(a.z // cell)), []).append(i)
    out = []
    for i, a in enumerate(atoms):
        cx, cy, cz = int(a.x // cell), int(a.y // cell), int(a.z // cell)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get((cx + dx, cy + dy, cz + dz), ()):
                        if j <= i:
                            continue
                        b = atoms[j]
                        if a.el == "H" and b.el == "H":
                            continue
                        cut = COVALENT[a.el] + COVALENT[b.el] + 0.45
                        if dist2(a, b) < cut * cut:
                            out.append((i, j))
    return out


def annotate(atoms):
    """Heavy atoms with their H count and heavy-neighbour count; hydrogens attached to the
    nearest bonded heavy atom. Drops H on non-bridging phosphate oxygens (O bonded to P
    only). Returns (heavy, hydrogens as (atom, parent heavy atom))."""
    for a in atoms:
        a.nh = a.nheavy = 0
    nb = [[] for _ in atoms]
    for i, j in bonds(atoms):
        nb[i].append(j)
        nb[j].append(i)
    heavy = []
    for i, a in enumerate(atoms):
        if a.el != "H":
            heavy.append(a)
            a.nheavy = sum(1 for j in nb[i] if atoms[j].el != "H")
    hyd = []
    for i, a in enumerate(atoms):
        if a.el != "H":
            continue
        parents = [j for j in nb[i] if atoms[j].el != "H"]
        if not parents:
            sys.exit(f"hydrogen {a.name} {a.res} {a.resnum} has no heavy neighbour")
        p = min(parents, key=lambda j: dist2(a, atoms[j]))
        pa = atoms[p]
        if pa.el == "O" and [atoms[j].el for j in nb[p] if atoms[j].el != "H"] == ["P"]:
            continue  # phosphate OH -> O(-)
        pa.nh += 1
        hyd.append((a, pa))
    return heavy, hyd


# ----------------------------------------------------------------------------- radii tables

def united_radius(a):
    """Connolly/MSMS united-atom radius by element and attached H."""
    if a.el == "C":
        if a.nh == 0:
            return 1.74
        return 1.86 if a.nheavy + a.nh == 3 else 2.00  # sp2 CH vs sp3 CH/CH2/CH3
    if a.el == "N":
        return (1.54, 1.70, 1.80, 2.00)[min(a.nh, 3)]
    if a.el == "O":
        return 1.40 if a.nh == 0 else 1.60
    if a.el == "S":
        return 1.80 if a.nh == 0 else 1.85
    return BONDI[a.el]  # P 1.80; Br (not in the table) Bondi's


def parse_radius(a):
    if a.el == "C":
        return 1.70 if a.nh == 0 else 2.00
    return {"N": 1.50, "O": 1.40, "S": 1.85}.get(a.el, BONDI[a.el])


def variant(atoms_heavy, hyd, conv):
    """List of (x, y, z, r) for one convention."""
    if conv == "bondi":
        return [(a.x, a.y, a.z, BONDI[a.el]) for a in atoms_heavy]
    if conv == "bondi+H":
        return ([(a.x, a.y, a.z, BONDI[a.el]) for a in atoms_heavy]
                + [(h.x, h.y, h.z, BONDI["H"]) for h, _ in hyd])
    if conv == "united":
        return [(a.x, a.y, a.z, united_radius(a)) for a in atoms_heavy]
    if conv == "parse":
        return ([(a.x, a.y, a.z, parse_radius(a)) for a in atoms_heavy]
                + [(h.x, h.y, h.z, 1.00) for h, p in hyd if p.el != "C"])
    raise ValueError(conv)


def trp_fixed(heavy, hyd):
    """bondi+H spheres with each misplaced tryptophan H moved onto NE1."""
    res = {}
    for a in heavy:
        if a.res == "TRP":
            res.setdefault((a.chain, a.resnum), {})[a.name] = a
    drop, add = set(), []
    for d in res.values():
        n, c1, c2 = d["NE1"], d["CD1"], d["CE2"]
        bad = [d[k] for k in ("CD1", "CE3", "CZ2", "CZ3", "CH2") if d[k].nh == 2]
        if n.nh or not bad:
            continue
        drop.add(id(next(h for h, p in hyd if p is bad[0])))
        u1 = [n.x - c1.x, n.y - c1.y, n.z - c1.z]
        u2 = [n.x - c2.x, n.y - c2.y, n.z - c2.z]
        l1, l2 = math.hypot(*u1), math.hypot(*u2)
        v = [p / l1 + q / l2 for p, q in zip(u1, u2)]
        lv = math.hypot(*v)
        add.append((n.x + 1.01 * v[0] / lv, n.y + 1.01 * v[1] / lv, n.z + 1.01 * v[2] / lv))
    spheres = ([(a.x, a.y, a.z, BONDI[a.el]) for a in heavy]
               + [(h.x, h.y, h.z, BONDI["H"]) for h, _ in hyd if id(h) not in drop]
               + [(x, y, z, BONDI["H"]) for x, y, z in add])
    return spheres, len(add)


def write_xyzr(path, spheres):
    with open(path, "w") as f:
        for x, y, z, r in spheres:
            f.write(f"{x:.3f} {y:.3f} {z:.3f} {r:.2f}\n")


def adna_cut(atoms, n):
    keep_a = set(range(1, n + 1))
    keep_b = set(range(61 - n, 61))
    return [Atom(a.x, a.y, a.z, a.el, a.name, a.res, a.chain, a.resnum) for a in atoms
            if (a.chain == "A" and a.resnum in keep_a) or (a.chain == "B" and a.resnum in keep_b)]


# ----------------------------------------------------------------------------- meshing

def ply_area(path):
    """Area of a binary little-endian PLY triangle mesh (as skinmesh writes it)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    types = {"double": "d", "float": "f", "int": "i", "uint": "I", "uchar": "B", "char": "b",
             "short": "h", "ushort": "H"}
    nv = nf = 0
    vfmt = "<"
    section = None
    for line in header:
        w = line.split()
        if w[:2] == ["element", "vertex"]:
            nv, section = int(w[2]), "v"
        elif w[:2] == ["element", "face"]:
            nf, section = int(w[2]), "f"
        elif w[0] == "property" and section == "v":
            vfmt += types[w[1]]
        elif w[0] == "property" and section == "f":
            if w[1:4] != ["list", "uchar", "int"]:
                raise ValueError(f"{path}: unexpected face property {line}")
    vsize = struct.calcsize(vfmt)
    verts = [v[:3] for v in struct.iter_unpack(vfmt, data[end:end + nv * vsize])]
    fdata = data[end + nv * vsize:]
    if len(fdata) != 13 * nf:
        raise ValueError(f"{path}: faces are not all triangles")
    area = 0.0
    for k, i, j, l in struct.iter_unpack("<Biii", fdata):
        a, b, c = verts[i], verts[j], verts[l]
        ux, uy, uz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
        vx, vy, vz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
        cx, cy, cz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        area += math.sqrt(cx * cx + cy * cy + cz * cz)
    return 0.5 * area


def mesh(binary, inp, probe, outdir, direction=None):
    ply = os.path.join(outdir, "mesh.ply")
    stats = os.path.join(outdir, "stats.json")
    for p in (ply, stats):
        if os.path.exists(p):
            os.remove(p)
    cmd = ["nice", binary, "mesh", inp, "-o", ply, "--probe", f"{probe:g}", "--stats", stats, "-q"]
    if direction:
        cmd += ["--direction", direction]
    t = time.time()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t
    row = {"input": os.path.basename(inp), "probe": probe, "exit": proc.returncode,
           "wall_s": round(wall, 2)}
    if proc.returncode != 0 or not os.path.exists(stats):
        err = (proc.stderr.strip().splitlines() or ["(no message)"])[-1]
        row["error"] = err
        row["command"] = " ".join(cmd)
        print(f"  FAILED ({proc.returncode}): {' '.join(cmd)}\n    {err}", file=sys.stderr)
        return row
    with open(stats) as f:
        s = json.load(f)
    row.update(atoms=s["atoms"], triangles=s["triangles"], min_angle=round(s["min_angle_deg"], 2),
               euler=s["vertices"] - s["triangles"] // 2,
               checks_passed=s["checks_passed"], area=round(ply_area(ply), 1))
    return row


# ----------------------------------------------------------------------------- report

def fmt_int(n):
    return f"{n:,}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("skinmesh", help="path of the skinmesh binary")
    ap.add_argument("outdir", help="directory for the .xyzr variants, meshes and results.json")
    args = ap.parse_args()
    binary = os.path.abspath(args.skinmesh)
    out = os.path.abspath(args.outdir)
    if out == REPO or out.startswith(REPO + os.sep):
        sys.exit("OUTDIR must lie outside the repository")
    os.makedirs(out, exist_ok=True)

    obabel = shutil.which("obabel")
    convs = CONVENTIONS if obabel else ("bondi",)
    meta = {"skinmesh": binary, "probes": PROBES, "conventions": convs}
    if obabel:
        v = subprocess.run([obabel, "-V"], capture_output=True, text=True).stdout.strip()
        meta["obabel"] = v
        print(f"hydrogens: {v}", file=sys.stderr)
    else:
        print("obabel not found: measuring the 'bondi' convention only", file=sys.stderr)

    # Molecules (and A-DNA cuts) as lists of annotated atoms.
    mols = []
    for key, fname, paper in MOLECULES:
        src = os.path.join(DATA, fname)
        heavy_src = [a for a in read_pdb(src) if a.el != "H"]
        if obabel:
            hfile = os.path.join(out, key + "_H.pdb")
            subprocess.run(["nice", obabel, src, "-O", hfile, "-h"], check=True,
                           capture_output=True)
            atoms = read_pdb(hfile)
            heavy_ob = [a for a in atoms if a.el != "H"]
            if [(a.x, a.y, a.z) for a in heavy_ob] != [(a.x, a.y, a.z) for a in heavy_src]:
                sys.exit(f"{hfile}: heavy atoms differ from {src}")
        else:
            atoms = heavy_src
        mols.append((key, paper, atoms))
        if key == "adna30":
            for n in ADNA_LENGTHS:
                mols.append((f"adna{n}", paper, adna_cut(atoms, n)))

    rows = []
    for key, paper, atoms in mols:
        heavy, hyd = annotate(atoms)
        for conv in convs:
            spheres = variant(heavy, hyd, conv)
            path = os.path.join(out, f"{key}.{conv.replace('+', '')}.xyzr")
            write_xyzr(path, spheres)
            for p in PROBES:
                r = mesh(binary, path, p, out)
                r.update(molecule=key, stands_in_for=paper, convention=conv, spheres=len(spheres))
                rows.append(r)
                print(f"{key:11s} {conv:8s} p={p:<4g} {r.get('triangles', 'FAILED')!s:>8} "
                      f"{r.get('min_angle', '')}", file=sys.stderr)
    # Sanity check: the xyzr route agrees with skinmesh reading the PDB itself (Bondi).
    checks = []
    for key, fname, paper in MOLECULES:
        r = mesh(binary, os.path.join(DATA, fname), 0.0, out)
        x = next(q for q in rows if q["molecule"] == key and q["convention"] == "bondi"
                 and q["probe"] == 0.0)
        checks.append({"molecule": key, "pdb": r.get("triangles"), "xyzr": x.get("triangles")})
    meta["pdb_vs_xyzr_probe0"] = checks
    # Open Babel 3.1.1 puts the indole H of tryptophan on a ring carbon (CD1 or CE3, which
    # then carries 2 H) instead of NE1. Size of that error: gramicidin, bondi+H, p = 0,
    # with the H moved to NE1 (1.01 Å along the outer bisector of CD1-NE1-CE2).
    if obabel:
        key, paper, atoms = next(m for m in mols if m[0] == "gramicidin")
        heavy, hyd = annotate(atoms)
        spheres, moved = trp_fixed(heavy, hyd)
        path = os.path.join(out, "gramicidin.bondiH_trpfix.xyzr")
        write_xyzr(path, spheres)
        r = mesh(binary, path, 0.0, out)
        meta["gramicidin_bondiH_p0_trp_fixed"] = {"moved_H": moved, "triangles": r.get("triangles"),
                                                  "min_angle": r.get("min_angle")}
    # Measurement noise: the same input swept in other height directions.
    spread = []
    for key in ("amprenavir", "xk263", "2zmm", "gramicidin"):
        for conv in convs:
            path = os.path.join(out, f"{key}.{conv.replace('+', '')}.xyzr")
            if conv not in ("bondi", "bondi+H"):
                continue
            r0 = next(q for q in rows if q["molecule"] == key and q["convention"] == conv
                      and q["probe"] == 0.0)
            ts, angs = [r0.get("triangles")], [r0.get("min_angle")]
            for d in DIRECTIONS:
                r = mesh(binary, path, 0.0, out, d)
                ts.append(r.get("triangles"))
                angs.append(r.get("min_angle"))
            spread.append({"molecule": key, "convention": conv, "triangles": ts, "min_angle": angs})
    meta["direction_spread_p0"] = spread
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump({"meta": meta, "runs": rows}, f, indent=1)
    report(rows, convs, meta)


def get(rows, mol, conv, p, field="triangles"):
    for r in rows:
        if r["molecule"] == mol and r["convention"] == conv and r["probe"] == p:
            return r.get(field)
    return None


def report(rows, convs, meta):
    P = PROBES
    print("## Triangles (min angle) per molecule, convention and probe radius\n")
    for key, fname, paper in MOLECULES:
        n_paper, a_paper = PAPER[paper]
        print(f"### {key} (`data/{fname}`), stand-in for {paper}: "
              f"{fmt_int(n_paper)} triangles, {a_paper:.2f}°\n")
        print("| convention | spheres | " + " | ".join(f"p = {p:g}" for p in P) + " |")
        print("|---|---:|" + "---:|" * len(P))
        for conv in convs:
            cells = []
            for p in P:
                t = get(rows, key, conv, p)
                a = get(rows, key, conv, p, "min_angle")
                cells.append("failed" if t is None else f"{fmt_int(t)} ({a:.1f}°)")
            print(f"| {conv} | {get(rows, key, conv, P[0], 'spheres')} | " + " | ".join(cells) + " |")
        print()

    print("## Ratio measured / paper\n")
    print("| convention | molecule | " + " | ".join(f"p = {p:g}" for p in P) + " |")
    print("|---|---|" + "---:|" * len(P))
    for conv in convs:
        for key, paper in (("amprenavir", "pdb7tmn"), ("xk263", "pdb7tmn"), ("2zmm", "pdb7tmn"),
                           ("gramicidin", "Gramicidin A"), ("adna30", "A-DNA")):
            cells = []
            for p in P:
                t = get(rows, key, conv, p)
                cells.append("-" if t is None else f"{t / PAPER[paper][0]:.2f}")
            print(f"| {conv} | {key} | " + " | ".join(cells) + " |")
    print()

    print("## Fit: pdb7tmn = geometric mean of the three ligands' ratios; "
          "rms = root mean square of log(ratio) over pdb7tmn and Gramicidin A\n")
    print("| convention | p | pdb7tmn ratio | Gramicidin A ratio | rms log |")
    print("|---|---:|---:|---:|---:|")
    fits = [(conv, conv) for conv in convs]
    if "bondi+H" in convs:  # hydrogens as deposited: X-ray ligands none, Gramicidin A (NMR) all
        fits.append(("bondi, H as deposited", None))
    for label, conv in fits:
        for p in P:
            lig_conv, gra_conv = (conv, conv) if conv else ("bondi", "bondi+H")
            ts = [get(rows, k, lig_conv, p) for k in ("amprenavir", "xk263", "2zmm")]
            tg = get(rows, "gramicidin", gra_conv, p)
            if None in ts or tg is None:
                continue
            rl = math.exp(sum(math.log(t / PAPER["pdb7tmn"][0]) for t in ts) / 3)
            rg = tg / PAPER["Gramicidin A"][0]
            e = math.sqrt((math.log(rl) ** 2 + math.log(rg) ** 2) / 2)
            print(f"| {label} | {p:g} | {rl:.2f} | {rg:.2f} | {e:.2f} |")
    print()

    print("## Euler characteristic V - T/2 of the meshes (2 = one sphere)\n")
    print("| molecule | convention | " + " | ".join(f"p = {p:g}" for p in P) + " |")
    print("|---|---|" + "---:|" * len(P))
    for key in sorted({r["molecule"] for r in rows}, key=[r["molecule"] for r in rows].index):
        for conv in convs:
            print(f"| {key} | {conv} | "
                  + " | ".join(str(get(rows, key, conv, p, "euler")) for p in P) + " |")
    print()

    print("## A-DNA per base pair: triangles = a + b * bp fitted on 10, 20, 30 bp; "
          "length the paper's 114,316 triangles imply\n")
    print("| convention | p | 10 bp | 20 bp | 30 bp | b (per bp) | a | implied bp |"
          " area 30 bp (Å²) | triangles / Å² |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for conv in convs:
        for p in P:
            ts = [get(rows, f"adna{n}", conv, p) for n in (10, 20, 30)]
            if None in ts:
                continue
            xs = (10, 20, 30)
            mx, my = sum(xs) / 3, sum(ts) / 3
            b = sum((x - mx) * (y - my) for x, y in zip(xs, ts)) / sum((x - mx) ** 2 for x in xs)
            a = my - b * mx
            nbp = (PAPER["A-DNA"][0] - a) / b
            area = get(rows, "adna30", conv, p, "area")
            print(f"| {conv} | {p:g} | {fmt_int(ts[0])} | {fmt_int(ts[1])} | {fmt_int(ts[2])} | "
                  f"{b:,.0f} | {a:,.0f} | {nbp:.1f} | {area:,.0f} | {ts[2] / area:.1f} |")
    print()

    print("## Area and triangle density (triangles per Å² of mesh)\n")
    print("| molecule | convention | " + " | ".join(f"p = {p:g}" for p in P) + " |")
    print("|---|---|" + "---:|" * len(P))
    for key, fname, paper in MOLECULES:
        for conv in convs:
            cells = []
            for p in P:
                t, a = get(rows, key, conv, p), get(rows, key, conv, p, "area")
                cells.append("-" if t is None else f"{a:,.0f} / {t / a:.1f}")
            print(f"| {key} | {conv} | " + " | ".join(cells) + " |")
    print()
    print("## Sweep direction (p = 0): default, (1,0,0), (0,0,1), (0.3,0.5,0.8)\n")
    print("| molecule | convention | triangles | spread | min angles |")
    print("|---|---|---|---:|---|")
    for sp in meta.get("direction_spread_p0", []):
        ts = [t for t in sp["triangles"] if t is not None]
        rel = (max(ts) - min(ts)) / min(ts) if ts else float("nan")
        print(f"| {sp['molecule']} | {sp['convention']} | {', '.join(fmt_int(t) for t in ts)} | "
              f"{100 * rel:.1f}% | {', '.join(f'{a:.1f}°' for a in sp['min_angle'] if a)} |")
    print()
    failed = [r for r in rows if "error" in r]
    ok = [r for r in rows if "triangles" in r]
    print(f"checks_passed false: {sum(1 for r in ok if not r['checks_passed'])}; smallest minimum "
          f"angle over all runs: {min(r['min_angle'] for r in ok):.2f}°")
    print(f"runs: {len(rows)}, failed: {len(failed)}; "
          f"PDB vs xyzr (bondi, p = 0): {meta['pdb_vs_xyzr_probe0']}")
    if "gramicidin_bondiH_p0_trp_fixed" in meta:
        print(f"gramicidin bondi+H p = 0 with the tryptophan H on NE1: "
              f"{meta['gramicidin_bondiH_p0_trp_fixed']}")
    for r in failed:
        print(f"- FAILED: `{r['command']}`: {r['error']}")


if __name__ == "__main__":
    main()
