"""Mesh the frames of a molecular dynamics trajectory with skinmesh, the frames
in parallel: an MDAnalysis Universe's atoms, frame by frame, as (n, 4) arrays
of x, y, z and radius for skinmesh.mesh() (which releases the GIL, so threads
mesh frames side by side).

    PYTHONPATH=build/python python3 python/examples/trajectory.py TOPOLOGY TRAJECTORY \\
        [--select "protein"] [--probe 1.4] [--step 10] [--jobs 2] -O frames/

writes frames/frame_000000.ply, ... and prints one line per frame. As a library:

    from trajectory import mesh_frames
    for frame, mesh in mesh_frames(universe.select_atoms("protein"), probe=1.4, jobs=2):
        ...

Notes: papers/python.md ("Trajectories"). Debian: python3-mdanalysis.
"""
import argparse
import concurrent.futures
import os
import sys

import numpy as np

import skinmesh


def frame_atoms(positions, radii):
    """The (n, 4) array skinmesh.mesh() takes: positions (Å) and radii (Å)."""
    return np.column_stack([np.asarray(positions, dtype=np.float64), radii])


def mesh_frames(atoms, probe=1.4, frames=None, jobs=None, radii=None, check=True):
    """Yields (frame index, skinmesh.Mesh) for the frames of `atoms` (an
    MDAnalysis AtomGroup) in frame order, meshing up to `jobs` frames at once
    (default: every core). `frames`: the frame indices (default: all);
    `radii`: one per atom in Å (default: skinmesh.vdw_radii of the atoms'
    elements, Bondi's, as the file readers give them). Each frame's positions
    are copied as the trajectory reaches it, so the trajectory is read once,
    in order."""
    universe = atoms.universe
    if radii is None:
        radii = skinmesh.vdw_radii([str(e) for e in atoms.elements])
    radii = np.asarray(radii, dtype=np.float64)
    indices = range(len(universe.trajectory)) if frames is None else list(frames)
    jobs = jobs or os.cpu_count() or 1
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        pending = []
        for i in indices:
            universe.trajectory[i]
            array = frame_atoms(atoms.positions, radii)
            pending.append((i, pool.submit(skinmesh.mesh, array, probe=probe, threads=1, check=check)))
            # Yield finished frames in order, keeping at most 2 * jobs frames in flight.
            while pending and (pending[0][1].done() or len(pending) > 2 * jobs):
                frame, future = pending.pop(0)
                yield frame, future.result()
        for frame, future in pending:
            yield frame, future.result()


def main(argv=None):
    import MDAnalysis as mda

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("topology")
    parser.add_argument("trajectory", nargs="*")
    parser.add_argument("--select", default="all", help="MDAnalysis selection (default: all)")
    parser.add_argument("--probe", type=float, default=1.4)
    parser.add_argument("--step", type=int, default=1, help="every STEP-th frame")
    parser.add_argument("--jobs", type=int, default=None, help="frames meshed at once (default: every core)")
    parser.add_argument("--format", default="ply")
    parser.add_argument("-O", "--output-dir", required=True)
    args = parser.parse_args(argv)
    universe = mda.Universe(args.topology, *args.trajectory)
    atoms = universe.select_atoms(args.select)
    os.makedirs(args.output_dir, exist_ok=True)
    failed = 0
    frames = range(0, len(universe.trajectory), args.step)
    for frame, mesh in mesh_frames(atoms, probe=args.probe, frames=frames, jobs=args.jobs):
        path = os.path.join(args.output_dir, "frame_%06d.%s" % (frame, args.format))
        if mesh.ok:
            mesh.write(path)
        failed += not mesh.ok
        print("frame %d: %d triangles, min angle %.2f, %s" % (frame, len(mesh.triangles),
              mesh.stats["min_angle_deg"], path if mesh.ok else "FAILED its check, not written"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
