"""The MDAnalysis example (python/examples/trajectory.py): a 10-frame
trajectory the test generates (a ligand turned 10 degrees a frame and jittered)
meshed frame by frame, the frames in parallel, through an in-memory Universe
and through a DCD file and the example's command line."""
import os
import sys

import numpy as np
import pytest

import skinmesh

mda = pytest.importorskip("MDAnalysis", reason="MDAnalysis is not installed (Debian python3-mdanalysis; .ci/install-deps)")
from MDAnalysis.coordinates.memory import MemoryReader  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "examples"))
import trajectory  # noqa: E402

DATA = os.environ.get("SKINMESH_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
LIGAND = os.path.join(DATA, "ligand_2zmm.pdb")


def ten_frames():
    """A Universe of the ligand with 10 frames: frame k turned 10k degrees about
    z through the centre and every atom moved by up to 0.1 Å (seeded)."""
    u = mda.Universe(LIGAND)
    base = u.atoms.positions.astype(np.float64)
    centre = base.mean(axis=0)
    rng = np.random.default_rng(7)
    frames = []
    for k in range(10):
        c, s = np.cos(np.radians(10 * k)), np.sin(np.radians(10 * k))
        turn = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        frames.append((base - centre) @ turn.T + centre + rng.uniform(-0.1, 0.1, base.shape))
    u.load_new(np.array(frames, dtype=np.float32), format=MemoryReader)
    return u


def test_every_frame_meshed_in_order_in_parallel_as_alone():
    u = ten_frames()
    atoms = u.select_atoms("all")
    radii = skinmesh.vdw_radii([str(e) for e in atoms.elements])
    assert radii.shape == (len(atoms),) and (radii > 1).all()
    meshes = list(trajectory.mesh_frames(atoms, probe=1.4, jobs=2))
    assert [f for f, _ in meshes] == list(range(10))
    for frame, mesh in meshes:
        assert mesh.ok, frame
        assert mesh.stats["min_angle_deg"] > 21.5
        # The frame's own atoms: the same mesh as meshing that frame alone.
        u.trajectory[frame]
        alone = skinmesh.mesh(trajectory.frame_atoms(atoms.positions, radii), probe=1.4, threads=1)
        assert np.array_equal(alone.vertices, mesh.vertices), frame
        assert np.array_equal(alone.triangles, mesh.triangles), frame
    # Frames differ: the molecule turned.
    first, last = meshes[0][1], meshes[9][1]
    assert len(first.vertices) != len(last.vertices) or not np.allclose(first.vertices, last.vertices)


def test_the_command_line_meshes_a_dcd_file(tmp_path):
    u = ten_frames()
    with mda.Writer(str(tmp_path / "t.dcd"), n_atoms=len(u.atoms)) as w:
        for _ in u.trajectory:
            w.write(u.atoms)
    code = trajectory.main([LIGAND, str(tmp_path / "t.dcd"), "--step", "3", "--jobs", "2", "-O",
                            str(tmp_path / "frames")])
    assert code == 0
    assert sorted(os.listdir(tmp_path / "frames")) == ["frame_%06d.ply" % k for k in (0, 3, 6, 9)]
    back = skinmesh.read_mesh(tmp_path / "frames" / "frame_000003.ply")
    assert len(back.triangles) > 1000
