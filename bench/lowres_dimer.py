#!/usr/bin/env python3
"""A dense, low-resolution-like homodimer built from a bundled protein (PDB on stdout).

    python3 bench/lowres_dimer.py [IN.pdb] [--contacts F] [--noise S] [--decimals D] [--seed N] > dimer.pdb

The test equivalent of the 4.2 Å crystal structure of issue #25 (an 11,484-atom dimer whose sweep at probe 0
once ran for more than 15 minutes): two copies of the input's protein atoms (default data/src_kinase_2src.pdb,
3,915 atoms, so 7,830 in the dimer), the second the image of the first under a two-fold axis, pushed into the
first until a fraction F of the second copy's atoms (default 0.06) lies within 3.5 Å of the first copy, far
more interface than a refined structure packs and with clashes kept, as in a model built into weak density.
Every coordinate is then perturbed by Gaussian noise of S Å (default 0.3, about a low-resolution model's
coordinate error) and rounded to D decimals (default 3, as PDB files hold them; 1 makes exact coordinate ties,
and some of them make the skin singular, which skinmesh refuses by name). Chains are
A and B; element columns are copied, hydrogens and waters dropped. The axis comes from the seed; the result is
deterministic for a given input, options and seed. Pure Python.
"""
import argparse
import math
import os
import random
import sys


def read_atoms(path):
    """The ATOM/HETATM records of the first model, without waters and hydrogens: (line, x, y, z)."""
    atoms = []
    with open(path) as f:
        for line in f:
            if line.startswith("ENDMDL"):
                break
            if not line.startswith(("ATOM  ", "HETATM")):
                continue
            if line[17:20] in ("HOH", "WAT"):
                continue
            element = line[76:78].strip() if len(line) >= 78 else ""
            name = line[12:16]
            if element == "H" or (not element and name.strip().startswith("H")):
                continue
            atoms.append((line.rstrip("\n").ljust(80), float(line[30:38]), float(line[38:46]), float(line[46:54])))
    if not atoms:
        sys.exit(f"{path}: no protein atoms found")
    return atoms


def rotate_half_turn(p, point, axis):
    """p turned by 180° about the line through `point` along the unit vector `axis`."""
    d = [p[i] - point[i] for i in range(3)]
    along = sum(d[i] * axis[i] for i in range(3))
    return [point[i] + 2 * along * axis[i] - d[i] for i in range(3)]


def interface_fraction(a, b, cutoff):
    """The fraction of the points b within `cutoff` of some point of a (hash grid of `cutoff` cells)."""
    grid = {}
    for p in a:
        grid.setdefault(tuple(int(math.floor(c / cutoff)) for c in p), []).append(p)
    c2 = cutoff * cutoff
    near = 0
    for q in b:
        key = [int(math.floor(c / cutoff)) for c in q]
        hit = False
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for p in grid.get((key[0] + dx, key[1] + dy, key[2] + dz), ()):
                        if (p[0] - q[0])**2 + (p[1] - q[1])**2 + (p[2] - q[2])**2 < c2:
                            hit = True
                            break
                    if hit:
                        break
                if hit:
                    break
            if hit:
                break
        near += hit
    return near / len(b)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("input", nargs="?", default=os.path.join(here, "..", "data", "src_kinase_2src.pdb"))
    ap.add_argument("--contacts", type=float, default=0.06, help="fraction of copy B within 3.5 Å of copy A")
    ap.add_argument("--noise", type=float, default=0.3, help="Gaussian coordinate noise, Å")
    ap.add_argument("--decimals", type=int, default=3, help="decimals of the written coordinates (1-3)")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    if not 0 < args.contacts < 1 or args.noise < 0 or not 1 <= args.decimals <= 3:
        sys.exit("lowres_dimer.py: --contacts must be in (0, 1), --noise >= 0, --decimals in 1..3")

    atoms = read_atoms(args.input)
    rng = random.Random(args.seed)
    a = [[x, y, z] for _, x, y, z in atoms]
    centre = [sum(p[i] for p in a) / len(a) for i in range(3)]
    # A random direction u from the centre towards the partner, and a two-fold axis perpendicular to it.
    z = rng.uniform(-1, 1)
    phi = rng.uniform(0, 2 * math.pi)
    s = math.sqrt(1 - z * z)
    u = [s * math.cos(phi), s * math.sin(phi), z]
    t = [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0]
    w = [u[1] * t[2] - u[2] * t[1], u[2] * t[0] - u[0] * t[2], u[0] * t[1] - u[1] * t[0]]
    wn = math.sqrt(sum(c * c for c in w))
    w = [c / wn for c in w]

    def partner(offset):
        point = [centre[i] + offset * u[i] for i in range(3)]
        return [rotate_half_turn(p, point, w) for p in a]

    # The axis at `offset` from the centre puts the copies' centres 2·offset apart: bisect the offset for
    # the requested interface (the fraction falls as the copies separate).
    lo, hi = 0.0, max(math.dist(p, centre) for p in a) + 4
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if interface_fraction(a, partner(mid), 3.5) > args.contacts:
            lo = mid
        else:
            hi = mid
    b = partner(hi)

    out = sys.stdout
    out.write("REMARK   1 LOW-RESOLUTION-LIKE DIMER FROM %s\n" % os.path.basename(args.input))
    out.write("REMARK   1 CONTACTS %.3f NOISE %.2f DECIMALS %d SEED %d INTERFACE %.3f\n" %
              (args.contacts, args.noise, args.decimals, args.seed, interface_fraction(a, b, 3.5)))
    serial = 0
    for chain, coords in (("A", a), ("B", b)):
        for (line, _, _, _), p in zip(atoms, coords):
            serial += 1
            q = [round(c + rng.gauss(0, args.noise), args.decimals) for c in p]
            out.write("%s%5d%s%s%s%8.3f%8.3f%8.3f%s\n" %
                      (line[:6], serial % 100000, line[11:21], chain, line[22:30], q[0], q[1], q[2], line[54:80]))
        out.write("TER\n")
    out.write("END\n")


if __name__ == "__main__":
    main()
