"""The mesh files read by the tools people feed them to, through those tools'
own readers: Debian's python3-meshio (the reader behind many simulation and
learning pipelines) and TetGen 1.5 (volume meshes of the skin), both
installed by .ci/install-deps. Run by `make test` (ctest `python`).

What they check: each reader gets the same points (bit for bit where the
format stores doubles, the float32 values for STL), the same triangles and
the atom index; TetGen fills the plain OFF file, and the ASCII PLY and STL
files (`ascii=True`, `--ascii`: TetGen reads no binary PLY or STL), with
tetrahedra whose volume is the volume the mesh encloses; Debian's PyMOL loads
the OFF and MSMS files as surfaces at the mesh's extent; gmsh reads the ASCII
PLY files, of doubles and of floats."""
import importlib.util
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import meshio
import skinmesh

DATA = os.environ.get("SKINMESH_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
LIGAND = os.path.join(DATA, "ligand_2zmm.pdb")
CRAMBIN = os.path.join(DATA, "crambin_1crn.pdb")


def triangle_corners(points, triangles):
    """Each triangle as its three corners' coordinates, rows sorted: a
    comparison that does not depend on how a reader numbers the points."""
    corners = points[triangles].reshape(len(triangles), 9)
    return corners[np.lexsort(corners.T[::-1])]


def test_meshio_reads_ply_off_obj_stl_as_written(tmp_path):
    m = skinmesh.mesh(LIGAND, threads=1)
    assert m.ok
    for name in ["l.ply", "l.off", "l.obj", "l.stl"]:
        m.write(tmp_path / name)
        got = meshio.read(tmp_path / name)
        triangles = [c.data for c in got.cells if c.type == "triangle"]
        assert len(triangles) == 1 and len(got.cells) == 1, name
        if name == "l.stl":  # float32 corners, merged by meshio
            expected = triangle_corners(m.vertices.astype(np.float32).astype(np.float64), m.triangles)
            assert np.array_equal(triangle_corners(got.points.astype(np.float64), triangles[0]), expected)
        else:
            assert np.array_equal(got.points, m.vertices), name
            assert np.array_equal(triangles[0], m.triangles), name
    ply = meshio.read(tmp_path / "l.ply")
    assert np.array_equal(ply.point_data["atom"], m.atom)
    assert np.array_equal(np.column_stack([ply.point_data[k] for k in ("nx", "ny", "nz")]), m.normals)


def test_meshio_reads_ascii_ply_and_stl_exactly(tmp_path):
    m = skinmesh.mesh(LIGAND, threads=1)
    for name in ["a.ply", "a.stl"]:
        m.write(tmp_path / name, ascii=True)
        with open(tmp_path / name, "rb") as f:
            assert f.read(5) in (b"ply\nf", b"solid")
        got = meshio.read(tmp_path / name)
        triangles = [c.data for c in got.cells if c.type == "triangle"]
        assert len(triangles) == 1 and len(got.cells) == 1, name
        # Exact doubles in both: ASCII STL does not round to float32.
        expected = triangle_corners(m.vertices, m.triangles)
        assert np.array_equal(triangle_corners(got.points.astype(np.float64), triangles[0]), expected), name
    ply = meshio.read(tmp_path / "a.ply")
    assert np.array_equal(ply.points, m.vertices)
    assert np.array_equal(ply.point_data["atom"], m.atom)


def tetgen_volume(path):
    """The volume of TetGen's tetrahedra filling the surface mesh file `path`
    (`tetgen -pYQ`: a piecewise linear complex, its triangles kept, quiet),
    and their count. TetGen writes <stem>.1.node and <stem>.1.ele beside it."""
    subprocess.run(["tetgen", "-pYQ", str(path)], check=True, timeout=120)
    stem = str(path)[: str(path).rfind(".")]
    node = np.loadtxt(stem + ".1.node", comments="#", skiprows=1)
    ele = np.loadtxt(stem + ".1.ele", comments="#", skiprows=1, dtype=np.int64)
    points = node[:, 1:4]
    first = int(node[0, 0])  # TetGen numbers from 0 or 1, as its input did
    tets = points[ele[:, 1:5] - first]
    volume = np.abs(np.einsum("ij,ij->i", tets[:, 1] - tets[:, 0],
                              np.cross(tets[:, 2] - tets[:, 0], tets[:, 3] - tets[:, 0]))).sum() / 6
    return volume, len(ele)


@pytest.mark.parametrize("source,probe", [(LIGAND, 1.4), (CRAMBIN, 1.4), (CRAMBIN, 0.0)])
def test_tetgen_fills_the_off_and_ascii_ply_and_stl_files_with_the_enclosed_volume(tmp_path, source, probe):
    # One shell, which TetGen fills whole: crambin at probe 0 has ten cavities,
    # left out by cavities="remove" (or TetGen would fill them too).
    m = skinmesh.mesh(source, probe=probe, threads=2, cavities="remove")
    components = m.stats["surface"]["components"]
    assert len(components) == 1
    for name, ascii in [("l.off", False), ("a.ply", True), ("a.stl", True)]:
        m.write(tmp_path / name, ascii=ascii)
        volume, tetrahedra = tetgen_volume(tmp_path / name)
        assert tetrahedra > len(m.triangles) / 4, name
        assert abs(volume - components[0]["volume_A3"]) <= 1e-9 * components[0]["volume_A3"], name


def pymol_extent(path, folder):
    """The extent PyMOL 2.5 gives the object it loads from `path`, read with
    Debian's PyMOL in a subprocess (`python3 -m pymol -cq`, no window)."""
    script, out = folder / "extent.pml", folder / "extent.txt"
    script.write_text(
        "load %s, s\n"
        "python\n"
        "open(%r, 'w').write(repr((cmd.get_type('s'), cmd.get_extent('s'))))\n"
        "python end\n" % (path, str(out)))
    subprocess.run([sys.executable, "-m", "pymol", "-cq", str(script)], check=True, timeout=120,
                   capture_output=True)
    return eval(out.read_text())


@pytest.mark.skipif(importlib.util.find_spec("pymol") is None,
                    reason="PyMOL is not installed (Debian pymol; .ci/install-deps installs it)")
@pytest.mark.parametrize("probe", [1.4, 0.0])
def test_pymol_loads_the_off_and_msms_files_at_the_mesh_extent(tmp_path, probe):
    # PyMOL 2.5 reads plain OFF and MSMS .vert/.face as a CGO surface; its PLY
    # loader reads text PLY only and gives it a wrong extent, and it refuses STL
    # and VTK polydata (papers/geometry/io/mesh_io.md, "Consumers").
    m = skinmesh.mesh(CRAMBIN, probe=probe, threads=2)
    assert m.ok
    lo, hi = m.vertices.min(axis=0), m.vertices.max(axis=0)
    for name, options in [("c.off", {}), ("c.vert", {"msms_decimals": 6})]:
        m.write(tmp_path / name, **options)
        kind, extent = pymol_extent(tmp_path / name, tmp_path)
        assert kind == "object:cgo", name
        # float32 in PyMOL; six decimals in the MSMS file.
        assert np.allclose(extent[0], lo, atol=1e-4) and np.allclose(extent[1], hi, atol=1e-4), (name, extent)


def read_msh2(path):
    """Nodes (by tag) and triangles (node tags) of a gmsh MSH 2.2 text file."""
    lines = open(path).read().split("\n")
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    nodes = {}
    for line in lines[i + 2:i + 2 + n]:
        tag, x, y, z = line.split()
        nodes[int(tag)] = (float(x), float(y), float(z))
    j = lines.index("$Elements")
    triangles = []
    for line in lines[j + 2:j + 2 + int(lines[j + 1])]:
        f = [int(v) for v in line.split()]
        if f[1] == 2:  # a 3-node triangle: tag, type, number of tags, tags..., nodes
            triangles.append(f[3 + f[2]:])
    return nodes, triangles


SKINMESH = os.environ.get("SKINMESH_BINARY", os.path.join(os.path.dirname(skinmesh.__file__), "..", "skinmesh"))


@pytest.mark.skipif(shutil.which("gmsh") is None, reason="gmsh is not installed (Debian gmsh; .ci/install-deps)")
@pytest.mark.parametrize("probe", [1.4, 0.0])
def test_gmsh_reads_the_ascii_ply_of_floats_and_of_doubles(tmp_path, probe):
    # gmsh 4.8 reads text PLY; its binary PLY reader ("experimental") takes
    # vertices of x, y, z floats only, so our binary PLY (normals, atom) is
    # not for gmsh (papers/geometry/io/mesh_io.md, "Consumers").
    for name, flags in [("d.ply", ["--ascii"]), ("f.ply", ["--ascii", "--float"])]:
        subprocess.run([SKINMESH, "mesh", CRAMBIN, "--probe", str(probe), "-o", str(tmp_path / name), "-q"] + flags,
                       check=True, timeout=300)
        m = skinmesh.read_mesh(tmp_path / name)
        subprocess.run(["gmsh", str(tmp_path / name), "-save", "-format", "msh2", "-o", str(tmp_path / "g.msh")],
                       check=True, timeout=300, capture_output=True)
        nodes, triangles = read_msh2(tmp_path / "g.msh")
        assert len(nodes) == len(m.vertices) and len(triangles) == len(m.triangles), name
        tags = sorted(nodes)
        points = np.array([nodes[t] for t in tags])
        index = {t: k for k, t in enumerate(tags)}
        got = np.array([[index[t] for t in tri] for tri in triangles])
        # The same corners, as the file holds them (gmsh prints 16 digits).
        assert np.allclose(triangle_corners(points, got), triangle_corners(m.vertices, m.triangles), rtol=0,
                           atol=1e-12), name


@pytest.mark.parametrize("probe", [1.4, 0.0])
def test_meshio_reads_the_vtu_and_vtk_reads_the_vtp_and_vtu_with_every_array(tmp_path, probe):
    # meshio 7.0 reads .vtu (not .vtp); VTK's XML readers read both and load
    # every point array by default, the normals as the active normals.
    m = skinmesh.mesh(CRAMBIN, probe=probe, threads=2)
    assert m.ok
    for name in ["c.vtp", "c.vtu"]:
        m.write(tmp_path / name)
    got = meshio.read(tmp_path / "c.vtu")
    assert np.array_equal(got.points, m.vertices)
    assert [c.type for c in got.cells] == ["triangle"]
    assert np.array_equal(got.cells[0].data, m.triangles)
    assert np.array_equal(got.point_data["atom"], m.atom)
    assert np.array_equal(got.point_data["rho"], m.rho)
    assert np.array_equal(got.point_data["normals"], m.normals)
    assert np.all(got.cell_data["min_angle"][0] >= m.stats["min_angle_deg"] - 1e-9)
    if importlib.util.find_spec("vtk") is None:
        pytest.skip("VTK's Python module is not installed (Debian python3-vtk9; .ci/install-deps installs it)")
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    for name, reader in [("c.vtp", vtk.vtkXMLPolyDataReader()), ("c.vtu", vtk.vtkXMLUnstructuredGridReader())]:
        reader.SetFileName(str(tmp_path / name))
        reader.Update()
        out = reader.GetOutput()
        data = out.GetPointData()
        assert out.GetNumberOfCells() == len(m.triangles), name
        assert np.array_equal(vtk_to_numpy(out.GetPoints().GetData()), m.vertices), name
        names = {data.GetArrayName(i) for i in range(data.GetNumberOfArrays())}
        assert names == {"normals", "atom", "rho"}, name
        assert np.array_equal(vtk_to_numpy(data.GetNormals()), m.normals), name
        assert np.array_equal(vtk_to_numpy(data.GetArray("atom")), m.atom), name
        assert np.array_equal(vtk_to_numpy(data.GetArray("rho")), m.rho), name


def masif_read_msms(stem):
    """MaSIF's reading of MSMS output, re-implemented from its documented
    fields: the .vert after its 3 header lines, one vertex per line with 10
    fields (x y z nx ny nz component atom type name); the .face after its 3
    header lines, 1-based vertices in the first three fields; the .area after
    its 1 header line, the area (second field) keyed by the name (fourth)."""
    with open(stem + ".vert") as f:
        vert_lines = f.read().splitlines()
    with open(stem + ".face") as f:
        face_lines = f.read().splitlines()
    n_vertices, n_faces = int(vert_lines[2].split()[0]), int(face_lines[2].split()[0])
    assert len(vert_lines) == 3 + n_vertices and len(face_lines) == 3 + n_faces
    vertices, names = [], []
    for line in vert_lines[3:]:
        fields = line.split()
        assert len(fields) == 10
        vertices.append([float(x) for x in fields[:3]])
        names.append(fields[9])
    faces = [[int(x) - 1 for x in line.split()[:3]] for line in face_lines[3:]]
    areas = {}
    with open(stem + ".area") as f:
        next(f)
        for line in f:
            fields = line.split()
            areas[fields[3]] = float(fields[1])
    return np.array(vertices), np.array(faces), names, areas


@pytest.mark.parametrize("probe", [1.4, 0.0])
def test_masif_style_reading_of_msms_files_with_names_and_areas(tmp_path, probe):
    stem = str(tmp_path / "c")
    subprocess.run([SKINMESH, "mesh", CRAMBIN, "--probe", str(probe), "-o", stem + ".vert", "--msms-atom-names",
                    "--msms-decimals", "6", "--area-file", stem + ".area", "-q"], check=True, timeout=300)
    vertices, faces, names, areas = masif_read_msms(stem)
    m = skinmesh.read_mesh(stem + ".vert")
    assert np.allclose(vertices, m.vertices, atol=5e-7) and np.array_equal(faces, m.triangles)
    # Every vertex's name is an atom's (chain_resnum_icode_resname_atomname) and has an area.
    assert all(len(n.split("_")) == 5 for n in names)
    assert set(names) <= set(areas)
    assert all(areas[n] > 0 for n in set(names))
    exact = skinmesh.atom_areas(CRAMBIN, probe=probe)
    assert len(areas) <= len(exact)  # names of atoms may repeat across altlocs; crambin's do not
    assert abs(sum(areas.values()) - exact.sum()) <= 5e-7 * len(exact)
