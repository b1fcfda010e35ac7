"""Tests of the Python module `skinmesh` (python/skinmesh_python.cpp), run by
`make test` (ctest `python`) with Debian's /usr/bin/python3 and pytest.
They check real properties: shapes and dtypes, a closed and outward mesh,
the vertices on the skin, agreement with the command line's meshes, and the
errors' one-line messages."""
import os
import subprocess

import numpy as np
import pytest

import skinmesh

DATA = os.environ.get("SKINMESH_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
CRAMBIN = os.path.join(DATA, "crambin_1crn.pdb")
LIGAND = os.path.join(DATA, "ligand_2zmm.pdb")


def edge_counts(triangles):
    """How many triangles use each undirected edge."""
    e = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    e.sort(axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return counts


def test_crambin_arrays_shapes_types_and_a_closed_outward_mesh():
    m = skinmesh.mesh(CRAMBIN)
    assert m.ok
    v, t = m.vertices, m.triangles
    assert v.dtype == np.float64 and v.ndim == 2 and v.shape[1] == 3
    assert t.dtype == np.int32 and t.ndim == 2 and t.shape[1] == 3
    assert m.normals.shape == v.shape
    assert m.atom.shape == (v.shape[0],) and m.atom.dtype == np.int32
    assert m.rho.shape == (v.shape[0],) and (m.rho > 0).all()
    assert t.min() >= 0 and t.max() < v.shape[0]
    # Closed: every edge in exactly two triangles; Euler characteristic 2 (one sphere).
    assert (edge_counts(t) == 2).all()
    n_edges = len(edge_counts(t))
    assert v.shape[0] - n_edges + t.shape[0] == 2
    # Outward: the enclosed volume is positive and matches the stats.
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
    assert volume > 0
    assert volume == pytest.approx(m.stats["surface"]["volume_A3"], rel=1e-9)
    # Unit normals, agreeing with the triangles' normals.
    assert np.allclose(np.linalg.norm(m.normals, axis=1), 1)
    face_n = np.cross(b - a, c - a)
    assert (np.einsum("ij,ij->i", face_n, m.normals[t[:, 0]]) > 0).all()
    # The atom indices point into crambin's 327 atoms.
    assert m.stats["atoms"] == 327
    assert m.atom.min() >= 0 and m.atom.max() < 327
    assert m.stats["triangles"] == t.shape[0]
    assert m.stats["min_angle_deg"] > 21.5
    assert m.stats["checks_passed"]


def test_atoms_array_single_atom_is_a_sphere_of_radius_r_plus_probe():
    m = skinmesh.mesh(np.array([[1.0, 2.0, 3.0, 1.6]]), probe=1.4)
    r = np.linalg.norm(m.vertices - [1, 2, 3], axis=1)
    assert np.allclose(r, 3.0, atol=1e-9)  # every vertex on the skin, a sphere of radius 3 Å
    assert (m.atom == 0).all()


def test_measures_of_the_exact_skin():
    # One atom: a sphere of radius r + probe, area and volume in closed form.
    one = skinmesh.measures(np.array([[1.0, 2.0, 3.0, 1.6]]), probe=1.4)
    assert one["area_A2"] == pytest.approx(4 * np.pi * 9, rel=1e-12)
    assert one["volume_A3"] == pytest.approx(4 / 3 * np.pi * 27, rel=1e-12)
    assert one["patch_cells"] == 1
    # A molecule: the mesh's values lie just inside the exact skin's (chords cut
    # the convex parts), within half a percent; mesh(analytic=True) gives the same.
    exact = skinmesh.measures(LIGAND)
    m = skinmesh.mesh(LIGAND, analytic=True)
    assert m.stats["surface"]["analytic"] == exact
    for key in ("area_A2", "volume_A3"):
        assert m.stats["surface"][key] == pytest.approx(exact[key], rel=5e-3)
    with pytest.raises(skinmesh.InputError, match="probe radius"):
        skinmesh.measures(LIGAND, probe=-1)


def test_same_mesh_as_the_command_line(tmp_path):
    exe = os.environ.get("SKINMESH_BINARY", os.path.join(os.path.dirname(skinmesh.__file__), "..", "skinmesh"))
    if not os.path.exists(exe):
        pytest.skip("skinmesh executable not found")
    out = tmp_path / "cli.ply"
    subprocess.run([exe, "mesh", LIGAND, "-o", str(out), "-q"], check=True)
    cli = skinmesh.read_mesh(out)
    py = skinmesh.mesh(LIGAND)
    assert np.array_equal(cli.vertices, py.vertices)
    assert np.array_equal(cli.triangles, py.triangles)


def test_write_and_check_round_trip(tmp_path):
    m = skinmesh.mesh(LIGAND, threads=1)
    for name in ["l.ply", "l.vtk"]:
        m.write(tmp_path / name)
        report = skinmesh.check(LIGAND, tmp_path / name)
        assert report["problems"] == []
    # STL keeps float32 corners: checked to that rounding, as the command line does.
    m.write(tmp_path / "l.stl")
    report = skinmesh.check(LIGAND, tmp_path / "l.stl")
    assert report["num_far_vertices"] == 0
    assert 0 < report["vertex_distance_tolerance"] < 1e-4
    report = skinmesh.check(LIGAND, m)
    assert report["problems"] == [] and report["ok"]
    assert report["mesh"]["num_triangles"] == m.triangles.shape[0]
    assert report["max_vertex_distance"] < 1e-9
    # A damaged mesh fails: one vertex pushed 0.1 Å off the skin.
    v = m.vertices
    v[0] += 0.1 * m.normals[0]
    damaged = tmp_path / "damaged.off"
    with open(damaged, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(v), len(m.triangles)))
        for p in v:
            f.write("%.17g %.17g %.17g\n" % tuple(p))
        for t in m.triangles:
            f.write("3 %d %d %d\n" % tuple(t))
    report = skinmesh.check(LIGAND, damaged)
    assert report["num_far_vertices"] == 1
    assert report["problems"]


def test_a_lossy_format_that_breaks_the_mesh_is_refused(tmp_path):
    # Crambin at probe 0 has a cavity of about 8e-4 Å² that MSMS's three
    # decimals collapse (zero-area, self-intersecting, inward triangles).
    m = skinmesh.mesh(CRAMBIN, probe=0, threads=2)
    assert m.ok
    with pytest.raises(skinmesh.InputError, match=r"c\.vert: stores positions as 3 decimals, which breaks the mesh"):
        m.write(tmp_path / "c.vert")
    assert not (tmp_path / "c.vert").exists() and not (tmp_path / "c.face").exists()
    m.write(tmp_path / "c.vert", msms_decimals=6)
    report = skinmesh.check(CRAMBIN, tmp_path / "c.vert", probe=0)
    assert report["problems"] == [] and report["num_L_violations"] is None
    assert skinmesh.check(CRAMBIN, tmp_path / "c.vert", probe=0, strict=True)["num_L_violations"] is not None
    with open(tmp_path / "c.vert") as f:
        counts = [f.readline() for _ in range(3)][2].split()
    assert int(counts[0]) == len(m.vertices) and float(counts[2]) > 0 and float(counts[3]) == 0.0
    m.write(tmp_path / "f.vert", force=True)
    assert (tmp_path / "f.vert").exists()
    with pytest.raises(ValueError):
        m.write(tmp_path / "bad.vert", msms_decimals=2)


def test_dynamic_algorithm():
    m = skinmesh.mesh(np.array([[0, 0, 0, 1.6], [3.0, 0, 0, 1.6]]), algorithm="dynamic")
    assert m.ok
    assert m.stats["algorithm"] == "dynamic"
    assert (edge_counts(m.triangles) == 2).all()


def test_errors_are_python_exceptions_with_one_line_messages(tmp_path):
    with pytest.raises(skinmesh.InputError, match="no_such_file.pdb"):
        skinmesh.mesh("no_such_file.pdb")
    with pytest.raises(ValueError):  # InputError is a ValueError
        skinmesh.mesh(np.zeros((3, 3)))
    with pytest.raises(skinmesh.InputError, match="radius"):
        skinmesh.mesh(np.array([[0, 0, 0, -1.0]]))
    with pytest.raises(skinmesh.InputError, match="algorithm"):
        skinmesh.mesh(LIGAND, algorithm="marching cubes")
    bad = tmp_path / "bad.pdb"
    bad.write_text("ATOM      1  CA  ALA A   1      11.104  xx.xxx  -1.000  1.00  0.00           C\n")
    with pytest.raises(skinmesh.InputError) as e:
        skinmesh.mesh(bad)
    assert "\n" not in str(e.value)
    assert "bad.pdb" in str(e.value)


def test_atom_areas_exact_and_of_the_mesh():
    # Per-atom areas: the exact skin's sum to its area, the mesh's to the
    # mesh's, and the two agree atom by atom within the mesh's resolution.
    crambin = os.path.join(DATA, "crambin_1crn.pdb")
    exact = skinmesh.atom_areas(crambin, threads=2)
    m = skinmesh.mesh(crambin, threads=2, check=False)
    mesh_areas = m.atom_areas()
    assert exact.shape == mesh_areas.shape == (327,)
    assert abs(exact.sum() / skinmesh.measures(crambin)["area_A2"] - 1) < 1e-9
    assert abs(mesh_areas.sum() / m.stats["surface"]["area_A2"] - 1) < 1e-12
    assert (exact >= 0).all() and (exact == 0).any()
    assert np.abs(mesh_areas - exact).sum() / exact.sum() < 0.03
    # A mesh read back knows no atom count: its areas run to the largest atom index.
    atoms = skinmesh.mesh(np.array([[0.0, 0, 0, 1.5], [2.0, 0, 0, 1.2]]), probe=0, threads=1)
    assert atoms.atom_areas().shape == (2,)
    assert atoms.atom_areas(atoms=5)[2:].tolist() == [0, 0, 0]


def test_arrays_are_views_edits_persist_and_are_written(tmp_path):
    m = skinmesh.mesh(LIGAND, threads=1)
    before = m.vertices[0].copy()
    m.vertices[0] += [0.5, 0, 0]  # in place, on the mesh itself
    assert m.vertices[0] == pytest.approx(before + [0.5, 0, 0])
    assert np.shares_memory(m.vertices, m.vertices)  # one buffer, not a fresh copy per access
    m.write(tmp_path / "edited.ply")
    back = skinmesh.read_mesh(tmp_path / "edited.ply")
    assert back.vertices[0] == pytest.approx(before + [0.5, 0, 0])
    # The verifier sees the edit: the moved vertex is off the skin.
    assert any("from the skin" in p for p in skinmesh.check(LIGAND, back)["problems"])
    # A view outlives the Python name of its mesh.
    t = skinmesh.mesh(LIGAND, threads=1).triangles
    assert t.shape[1] == 3 and t.min() >= 0


def test_unchecked_and_read_meshes_say_so(tmp_path):
    m = skinmesh.mesh(LIGAND, threads=1, check=False)
    assert m.ok is None and "not checked" in repr(m)
    checked = skinmesh.mesh(LIGAND, threads=1)
    assert checked.ok is True
    checked.write(tmp_path / "l.off")  # OFF holds positions and triangles only
    back = skinmesh.read_mesh(tmp_path / "l.off")
    assert back.ok is None
    assert back.atom.shape == (back.vertices.shape[0],) and (back.atom == -1).all()
    assert back.rho is None and back.normals is None
    full = skinmesh.read_mesh(checked_ply(checked, tmp_path))
    assert (full.atom >= 0).all() and full.rho is None and full.normals.shape == full.vertices.shape


def checked_ply(mesh, folder):
    path = folder / "l.ply"
    mesh.write(path)
    return path


def test_version_and_bytes_paths(tmp_path):
    exe = os.environ.get("SKINMESH_BINARY", os.path.join(os.path.dirname(skinmesh.__file__), "..", "skinmesh"))
    out = subprocess.run([exe, "--version"],
                         capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "skinmesh " + skinmesh.__version__
    assert skinmesh.__version__.count(".") == 2
    m = skinmesh.mesh(os.fsencode(LIGAND), threads=1)
    assert m.ok and m.stats["input"] == LIGAND
    target = os.fsencode(str(tmp_path / "b.ply"))
    m.write(target)
    back = skinmesh.read_mesh(target)
    assert back.vertices.shape == m.vertices.shape
    assert skinmesh.check(os.fsencode(LIGAND), target)["problems"] == []


READERS = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "readers")
NMR = os.path.join(READERS, "nmr_three_models.pdb")
DIMER_PDB = os.path.join(READERS, "assembly_dimer.pdb")
DIMER_CIF = os.path.join(READERS, "assembly_dimer.cif")


def test_models_assemblies_and_chains_select_atoms_as_the_command_line(tmp_path):
    # The three-model file's model 2 is model 1 moved by 0.5 Å along x (its
    # REMARK lines); its mesh is model 1's moved, and the same as
    # `skinmesh mesh --model 2`.
    assert skinmesh.model_numbers(NMR) == [1, 2, 3]
    m1, m2 = skinmesh.mesh(NMR), skinmesh.mesh(NMR, model=2)
    assert m1.ok and m2.ok
    assert m1.triangles.shape == m2.triangles.shape
    assert np.allclose(m2.vertices - m1.vertices, [0.5, 0, 0], atol=1e-9)
    assert skinmesh.check(NMR, m2, model=2)["problems"] == []
    assert skinmesh.check(NMR, m2)["problems"] != []  # model 1's atoms: the mesh is off their skin
    exe = os.environ.get("SKINMESH_BINARY", os.path.join(os.path.dirname(skinmesh.__file__), "..", "skinmesh"))
    if os.path.exists(exe):
        out = tmp_path / "m2.ply"
        subprocess.run([exe, "mesh", NMR, "--model", "2", "-o", str(out), "-q"], check=True)
        assert np.array_equal(skinmesh.read_mesh(out).vertices, m2.vertices)
    # Assembly 1 is two copies of the 35-atom model, apart: two bodies, each
    # of the single chain's area; each copy alone is a chain.
    for path in (DIMER_PDB, DIMER_CIF):
        assert skinmesh.chain_names(path) == ["A"]
        assert skinmesh.chain_names(path, assembly="1") == ["A", "A2"]
        single = skinmesh.measures(path)["area_A2"]
        dimer = skinmesh.mesh(path, assembly="1")
        assert dimer.ok and dimer.stats["atoms"] == 70
        assert abs(skinmesh.measures(path, assembly="1")["area_A2"] - 2 * single) < 1e-9 * single
        copy = skinmesh.mesh(path, assembly="1", chains=["A2"])
        assert copy.ok and copy.stats["atoms"] == 35
        assert skinmesh.atom_areas(path, assembly="1", chains="A2").sum() == pytest.approx(single, rel=1e-9)
    with pytest.raises(skinmesh.InputError, match="model 4"):
        skinmesh.mesh(NMR, model=4)
    for bad in (0, -1, True, 2**70, "2", 2.0):
        with pytest.raises(skinmesh.InputError, match="model number >= 1"):
            skinmesh.mesh(NMR, model=bad)
    with pytest.raises(skinmesh.InputError, match="none empty"):
        skinmesh.mesh(NMR, chains=5)
    with pytest.raises(skinmesh.InputError, match="none empty"):
        skinmesh.mesh(NMR, chains="A,,B")
    with pytest.raises(skinmesh.InputError, match="not from an array"):
        skinmesh.mesh(np.array([[0.0, 0.0, 0.0, 1.5]]), chains="A")
