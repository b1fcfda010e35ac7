#!/usr/bin/env python3
"""Large assemblies built from a bundled protein, for the every-core issue (#26): a capsid-like shell or tiles.

    python3 bench/assembly.py shell [--protein FILE] [--t T] [--join J] > shell.pdb
    python3 bench/assembly.py tiles [--protein FILE] [--copies K] [--gap G] > tiles.pdb

shell: 60·T copies of the protein's heavy atoms (default src kinase, 3,645 atoms; T = 5 gives 300 copies,
1,093,500 atoms) on a sphere with icosahedral symmetry. The T copies of one asymmetric unit sit at T directions
spread over the unit's spherical triangle (the 60 proper rotations of the icosahedron carry them over the whole
sphere), each turned so that its longest principal axis is tangent to the sphere. The shell radius is bisected to
the largest at which the copies' contact graph is connected, two copies being in contact when heavy atoms of
theirs are closer than J Å (default 3.0: van der Waals balls of radius 1.5 Å or more overlap, so the copies'
skins join at every probe): one skin component outside, the shell's interior one cavity or more. By symmetry
the contacts of the first asymmetric unit's T copies give every edge of the graph. tiles: K copies side by
side on a square grid with G Å between their boxes (each its own component).

Output: PDB on stdout (serial numbers modulo 100,000 and chains cycling over A-Z, a-z, 0-9: skinmesh uses neither),
and one line on stderr with the atom count, the copies and the shell radius. Pure Python; deterministic.
"""
import argparse
import math
import os
import sys

from lowres_dimer import read_atoms

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(os.path.dirname(HERE), "data")
CHAINS = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"


def heavy_atoms(path):
    """(record line, (x, y, z)) of the protein's heavy atoms, first model, waters dropped."""
    return [(line, (x, y, z)) for line, x, y, z in read_atoms(path)]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(m, p):
    return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] for i in range(3))


def icosahedral_rotations():
    """The 60 proper rotations of the icosahedron: closure of a 5-fold and a 3-fold generator."""
    g = (1 + math.sqrt(5)) / 2

    def axis_angle(axis, angle):
        n = math.sqrt(sum(c * c for c in axis))
        x, y, z = (c / n for c in axis)
        c, s = math.cos(angle), math.sin(angle)
        t = 1 - c
        return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
                [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
                [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]

    gens = [axis_angle((0, 1, g), 2 * math.pi / 5), axis_angle((1, 1, 1), 2 * math.pi / 3)]
    key = lambda m: tuple(round(v, 6) for row in m for v in row)
    group = {key(gens[0]): gens[0]}
    frontier = [gens[0]]
    identity = [[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]]
    group[key(identity)] = identity
    frontier.append(identity)
    while frontier:
        nxt = []
        for m in frontier:
            for h in gens:
                p = matmul(h, m)
                if key(p) not in group:
                    group[key(p)] = p
                    nxt.append(p)
        frontier = nxt
    rots = [group[k] for k in sorted(group)]
    if len(rots) != 60:
        sys.exit(f"assembly.py: the icosahedral group closed with {len(rots)} rotations")
    return rots


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def asymmetric_directions(t):
    """t unit vectors spread over a spherical triangle of the icosahedron's 60-fold tiling (a third of a face
    around one vertex): points of a small triangular lattice in barycentric coordinates of the corners
    (5-fold vertex, 3-fold face centre, 2-fold edge midpoint), the first t in a fixed order."""
    g = (1 + math.sqrt(5)) / 2
    v5 = unit((0, 1, g))
    face = unit(tuple(a + b + c for a, b, c in zip((0, 1, g), (0, -1, g), (g, 0, 1))))
    edge = unit(tuple(a + b for a, b in zip((0, 1, g), (0, -1, g))))
    n = 1
    while n * (n + 1) // 2 < t:
        n += 1
    pts = []
    for i in range(n):
        for j in range(n - i):
            k = n - 1 - i - j
            w = ((i + 1 / 3) / (n), (j + 1 / 3) / (n), (k + 1 / 3) / (n))
            pts.append(unit(tuple(w[0] * a + w[1] * b + w[2] * c for a, b, c in zip(v5, face, edge))))
    return pts[:t]


def principal_frame(coords):
    """Centroid and the rotation whose rows are the principal axes (largest spread first), by power iteration."""
    n = len(coords)
    c = tuple(sum(p[i] for p in coords) / n for i in range(3))
    cov = [[sum((p[i] - c[i]) * (p[j] - c[j]) for p in coords) / n for j in range(3)] for i in range(3)]
    axes = []
    for _ in range(2):
        v = (1.0, 0.7, 0.3)
        for _ in range(200):
            w = apply(cov, v)
            for a in axes:
                d = sum(x * y for x, y in zip(w, a))
                w = tuple(x - d * y for x, y in zip(w, a))
            v = unit(w)
        axes.append(v)
    a, b = axes
    axes.append((a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]))
    return c, axes


def place(local, direction, radius):
    """The copy whose principal frame is turned so that axis 0 is tangent and axis 2 radial, at `radius` along
    `direction`: local (centred, in principal coordinates) -> world."""
    r = unit(direction)
    helper = (0.0, 0.0, 1.0) if abs(r[2]) < 0.9 else (1.0, 0.0, 0.0)
    t1 = unit((helper[1] * r[2] - helper[2] * r[1], helper[2] * r[0] - helper[0] * r[2],
               helper[0] * r[1] - helper[1] * r[0]))
    t2 = (r[1] * t1[2] - r[2] * t1[1], r[2] * t1[0] - r[0] * t1[2], r[0] * t1[1] - r[1] * t1[0])
    return [tuple(radius * r[i] + p[0] * t1[i] + p[1] * t2[i] + p[2] * r[i] for i in range(3)) for p in local]


def contacts(base, others, cutoff):
    """For each copy of `others` (index -> points), whether some atom of it lies within `cutoff` of an atom of
    `base` (points); a hash grid of `base`."""
    grid = {}
    for p in base:
        grid.setdefault((math.floor(p[0] / cutoff), math.floor(p[1] / cutoff), math.floor(p[2] / cutoff)), []).append(p)
    c2 = cutoff * cutoff
    hits = set()
    for j, pts in others.items():
        for q in pts:
            kx, ky, kz = math.floor(q[0] / cutoff), math.floor(q[1] / cutoff), math.floor(q[2] / cutoff)
            if any((p[0] - q[0])**2 + (p[1] - q[1])**2 + (p[2] - q[2])**2 < c2
                   for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                   for p in grid.get((kx + dx, ky + dy, kz + dz), ())):
                hits.add(j)
                break
    return hits


def shell(args):
    atoms = heavy_atoms(args.protein)
    coords = [p for _, p in atoms]
    c, axes = principal_frame(coords)
    local = [tuple(sum((p[k] - c[k]) * axes[i][k] for k in range(3)) for i in range(3)) for p in coords]
    rots = icosahedral_rotations()
    key = lambda m: tuple(round(v, 6) for row in m for v in row)
    index = {key(m): i for i, m in enumerate(rots)}
    product = [[index[key(matmul(g, h))] for h in rots] for g in rots]  # product[g][h] = index of g·h
    base_dirs = asymmetric_directions(args.t)
    n = len(rots) * args.t  # copy (h, s) = index h * T + s, at direction rots[h] · base_dirs[s]
    dirs = [apply(rots[h], base_dirs[s]) for h in range(len(rots)) for s in range(args.t)]
    extent = max(math.sqrt(p[0]**2 + p[1]**2 + p[2]**2) for p in local)

    def copy(j, radius):
        """Copy j = (h, s): the first unit's copy s turned by rotation h, so that the assembly is symmetric
        (the contacts of the first unit's copies are the contacts of every unit's)."""
        h, s = divmod(j, args.t)
        return [apply(rots[h], p) for p in place(local, base_dirs[s], radius)]

    def components(radius):
        """Components of the graph of copies joined by a heavy-atom pair closer than --join; by symmetry the
        contacts of the T copies of the first asymmetric unit (h = identity) give every edge."""
        ident = index[key([[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]])]
        edges = []
        for s in range(args.t):
            i = ident * args.t + s
            near = {j: copy(j, radius) for j in range(n)
                    if j != i and radius * math.dist(dirs[i], dirs[j]) < 2 * extent + args.join}
            for j in contacts(copy(i, radius), near, args.join):
                edges.append((s, j))
        parent = list(range(n))

        def find(x):
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x

        for s, j in edges:
            hj, sj = divmod(j, args.t)
            for g in range(len(rots)):  # the edge's images: (g, s) - (g·hj, sj)
                a, b = find(g * args.t + s), find(product[g][hj] * args.t + sj)
                parent[a] = b
        return len({find(x) for x in range(n)})

    # Too small a radius makes the copies interpenetrate; too large leaves them apart. Bisect for the largest
    # radius at which the contact graph is connected (one skin component at every probe).
    lo = extent
    hi = extent * max(2.0, math.sqrt(n))
    if components(hi) == 1:
        sys.exit("assembly.py: the copies touch even at the largest radius tried")
    if components(lo) != 1:
        sys.exit("assembly.py: the copies do not form one component even when pressed together")
    while hi - lo > 0.05:
        mid = 0.5 * (lo + hi)
        if components(mid) == 1:
            lo = mid
        else:
            hi = mid
    copies = [copy(j, lo) for j in range(n)]
    write(atoms, copies)
    print(f"assembly.py shell: {n} copies (T = {args.t}) of {len(atoms)} atoms = {n * len(atoms)} atoms, shell "
          f"radius {lo:.2f} Å; the copies' contact graph (heavy atoms closer than {args.join} Å) is connected",
          file=sys.stderr)


def tiles(args):
    atoms = heavy_atoms(args.protein)
    coords = [p for _, p in atoms]
    lo = [min(p[i] for p in coords) for i in range(3)]
    hi = [max(p[i] for p in coords) for i in range(3)]
    nx = math.ceil(math.sqrt(args.copies))
    copies = []
    for k in range(args.copies):
        ox, oy = (k % nx) * (hi[0] - lo[0] + args.gap), (k // nx) * (hi[1] - lo[1] + args.gap)
        copies.append([(p[0] + ox, p[1] + oy, p[2]) for p in coords])
    write(atoms, copies)
    print(f"assembly.py tiles: {len(copies)} copies of {len(atoms)} atoms = {len(copies) * len(atoms)} atoms, "
          f"{args.gap} Å apart", file=sys.stderr)


def write(atoms, copies):
    out = sys.stdout
    serial = 0
    for k, pts in enumerate(copies):
        chain = CHAINS[k % len(CHAINS)]
        for (line, _), p in zip(atoms, pts):
            if max(abs(v) for v in p) >= 1e4:
                sys.exit("assembly.py: a coordinate does not fit the PDB field (|x| < 10,000 Å)")
            serial += 1
            out.write("%s%5d%s%s%s%8.3f%8.3f%8.3f%s\n" %
                      (line[:6], serial % 100000, line[11:21], chain, line[22:30], p[0], p[1], p[2], line[54:80]))
        out.write("TER\n")
    out.write("END\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="kind", required=True)
    s = sub.add_parser("shell", help="60·T copies with icosahedral symmetry, touching: one component")
    s.add_argument("--protein", default=os.path.join(DATA, "src_kinase_2src.pdb"))
    s.add_argument("--t", type=int, default=5, help="copies per asymmetric unit (the triangulation number T)")
    s.add_argument("--join", type=float, default=3.0,
                   help="copies closer than this (heavy atoms, Å) are joined; 3.0 joins them at every probe")
    t = sub.add_parser("tiles", help="copies side by side: one component each")
    t.add_argument("--protein", default=os.path.join(DATA, "src_kinase_2src.pdb"))
    t.add_argument("--copies", type=int, default=4)
    t.add_argument("--gap", type=float, default=10.0)
    args = ap.parse_args()
    if args.kind == "shell":
        if not 1 <= args.t <= 64 or not 1.0 <= args.join <= 6.0:
            sys.exit("assembly.py: --t must be in 1..64 and --join in [1, 6] Å")
        shell(args)
    else:
        if args.copies < 1 or args.gap < 0:
            sys.exit("assembly.py: --copies must be >= 1 and --gap >= 0")
        tiles(args)


if __name__ == "__main__":
    main()
