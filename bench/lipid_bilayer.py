#!/usr/bin/env python3
"""An all-atom patch of a lipid bilayer, hydrogens included, with disordered tails (.xyzr on stdout).

    python3 bench/lipid_bilayer.py [--lipids N] [--seed S] > patch.xyzr

N x N lipids per leaflet (default 4: 32 lipids, about 4,300 atoms), 7.9 Å apart and jittered. Each lipid is
grown atom by atom like a phosphatidylcholine: a glycerol seed, a head group chain (C O P O C C N) with two
phosphate oxygens and three methyls on the nitrogen, and two tails of 16 or 18 carbons, every carbon with its
hydrogens (C-C 1.53 Å, C-H 1.09 Å, bond angles about 112°). Tail dihedrals are trans or gauche at random, the
growth prefers to head towards the bilayer's centre and avoids heavy atoms of other chains closer than 2.6 Å
(12 tries per atom, so some contacts remain, as in real patches). Radii (Å): C 1.7, H 1.1, N 1.55, O 1.52,
P 1.8. This is the test equivalent of the simulation-ready DOPC/DPPC patches of issue #25 (which failed at
probe 0 in the seal): the same chemistry at the resolution the skin sees, not a simulated membrane. Pure
Python, deterministic for a given seed.
"""
import argparse
import math
import random
import sys

RADIUS = {"C": 1.7, "H": 1.1, "N": 1.55, "O": 1.52, "P": 1.8}


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a, k):
    return (a[0] * k, a[1] * k, a[2] * k)


def norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def unit(a):
    return scale(a, 1 / norm(a))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def place(a, b, c, bond, angle, dihedral):
    """The atom d bonded to c with |cd| = bond, angle b-c-d and dihedral a-b-c-d (radians)."""
    bc = unit(sub(c, b))
    n = unit(cross(sub(b, a), bc))
    m = cross(n, bc)
    x, y, z = -bond * math.cos(angle), bond * math.sin(angle) * math.cos(dihedral), bond * math.sin(angle) * math.sin(
        dihedral)
    return add(c, add(scale(bc, x), add(scale(m, y), scale(n, z))))


class Patch:
    """The atoms so far, with a hash grid of 3 Å cells for the clash test."""

    def __init__(self, rng):
        self.rng = rng
        self.atoms = []
        self.cells = {}

    def key(self, p):
        return tuple(int(math.floor(x / 3.0)) for x in p)

    def add(self, p, element):
        self.atoms.append((p, element))
        self.cells.setdefault(self.key(p), []).append(len(self.atoms) - 1)
        return len(self.atoms) - 1

    def clashes(self, p, exclude):
        k = self.key(p)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for i in self.cells.get((k[0] + dx, k[1] + dy, k[2] + dz), ()):
                        if i not in exclude and self.atoms[i][1] != "H" and norm(sub(self.atoms[i][0], p)) < 2.6:
                            return True
        return False

    def hydrogens(self, i2, i1, i, count):
        """`count` hydrogens on atom i (bonded to i1, i1 bonded to i2), staggered."""
        a, b, c = self.atoms[i2][0], self.atoms[i1][0], self.atoms[i][0]
        base = self.rng.uniform(0, 2 * math.pi)
        for k in range(count):
            self.add(place(a, b, c, 1.09, math.radians(109.5), base + (k + 1) * 2 * math.pi / 3), "H")

    def chain(self, seed, elements, toward, hydrogens):
        """Grows len(elements) atoms from the three atoms `seed`, preferring to move along z sign `toward`."""
        idx = list(seed)
        for k, element in enumerate(elements):
            a, b, c = (self.atoms[j][0] for j in idx[-3:])
            best = None
            for _ in range(12):
                dihedral = self.rng.choice([math.pi, math.pi, math.pi, math.radians(60), math.radians(-60)])
                dihedral += self.rng.gauss(0, 0.25)
                p = place(a, b, c, 1.53, math.radians(self.rng.gauss(112, 2)), dihedral)
                score = (p[2] - c[2]) * toward - (10 if self.clashes(p, set(idx[-3:])) else 0)
                if best is None or score > best[0]:
                    best = (score, p)
            i = self.add(best[1], element)
            self.hydrogens(idx[-2], idx[-1], i, hydrogens(k))
            idx.append(i)
        return idx

    def methyl(self, centre):
        """A methyl carbon 1.49 Å from `centre` in a random direction, with its three hydrogens."""
        rng = self.rng
        d = unit((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)))
        c = self.add(add(centre, scale(d, 1.49)), "C")
        for _ in range(3):
            e = unit((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)))
            self.add(add(self.atoms[c][0], scale(unit(add(scale(d, 0.6), scale(e, 0.8))), 1.09)), "H")

    def lipid(self, x, y, z0, toward):
        rng = self.rng
        theta = rng.uniform(0, 2 * math.pi)
        c0 = (x, y, z0)
        i0 = self.add(c0, "C")
        i1 = self.add(add(c0, (1.2 * math.cos(theta), 1.2 * math.sin(theta), -0.9 * toward)), "C")
        i2 = self.add(add(c0, (0.0, 0.0, -1.53 * toward)), "O")
        head = self.chain([i2, i1, i0], ["C", "O", "P", "O", "C", "C", "N"], -toward, lambda k: [2, 0, 0, 0, 2, 2, 0][k])
        phosphorus = self.atoms[head[5]][0]
        for _ in range(2):
            self.add(add(phosphorus, (rng.uniform(-1, 1), rng.uniform(-1, 1), -0.3 * toward)), "O")
        for _ in range(3):
            self.methyl(self.atoms[head[-1]][0])
        length = rng.choice([16, 18])
        tail_h = lambda k: 2 if k < length - 1 else 3
        self.chain([i2, i0, i1], ["C"] * length, toward, tail_h)
        j = self.add(add(c0, (-1.2 * math.cos(theta), -1.2 * math.sin(theta), -0.9 * toward)), "C")
        self.chain([i1, i0, j], ["C"] * length, toward, tail_h)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lipids", type=int, default=4, help="lipids per side of each leaflet (N x N per leaflet)")
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    patch = Patch(rng)
    spacing = 7.9
    for leaflet, (z0, toward) in enumerate(((19.0, -1), (-19.0, 1))):
        for gx in range(a.lipids):
            for gy in range(a.lipids):
                x = gx * spacing + rng.uniform(-1, 1) + (spacing / 2 if leaflet else 0)
                y = gy * spacing + rng.uniform(-1, 1)
                patch.lipid(x, y, z0, toward)
    out = sys.stdout
    out.write("# lipid bilayer patch: python3 bench/lipid_bilayer.py --lipids %d --seed %d (%d atoms)\n" %
              (a.lipids, a.seed, len(patch.atoms)))
    for p, element in patch.atoms:
        out.write("%.3f %.3f %.3f %.2f\n" % (p[0], p[1], p[2], RADIUS[element]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
