"""The Snakemake workflow (workflows/snakemake/Snakefile) run as a user runs it,
with Debian's snakemake (installed by .ci/install-deps): it meshes the bundled
molecules of data/ with -j 2 into checked meshes, per-atom area files and a
summary table, and a rerun does only what is missing."""
import csv
import os
import shutil
import subprocess

import pytest

import skinmesh

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
DATA = os.path.abspath(os.environ.get("SKINMESH_DATA", os.path.join(ROOT, "data")))
SNAKEFILE = os.path.join(ROOT, "workflows", "snakemake", "Snakefile")
SKINMESH = os.environ.get("SKINMESH_BINARY", os.path.join(os.path.dirname(skinmesh.__file__), "..", "skinmesh"))

pytestmark = pytest.mark.skipif(shutil.which("snakemake") is None,
                                reason="snakemake is not installed (Debian snakemake; .ci/install-deps installs it)")


def snakemake(tmp_path, *args):
    return subprocess.run(["snakemake", "-s", SNAKEFILE, "-j", "2", "--directory", str(tmp_path),
                           "--config", "inputs=" + DATA, "out=" + str(tmp_path / "out"),
                           "skinmesh=" + os.path.abspath(SKINMESH)] + list(args),
                          capture_output=True, text=True, timeout=900)


def test_snakemake_meshes_data_and_resumes(tmp_path):
    run = snakemake(tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    molecules = sorted(n for n in os.listdir(DATA) if n.endswith((".pdb", ".pqr")))
    with open(tmp_path / "out" / "summary.csv") as f:
        rows = list(csv.DictReader(f))
    assert sorted(os.path.basename(r["input"]) for r in rows) == molecules
    for r in rows:
        name = os.path.basename(r["input"])
        assert r["checks_passed"] == "True", name
        assert float(r["min_angle_deg"]) > 21.5, name
        # The per-atom areas sum to the exact skin's area (six decimals per atom).
        with open(tmp_path / "out" / (name + ".area")) as f:
            lines = f.read().splitlines()
        assert lines[0].startswith("#") and len(lines) == int(r["atoms"]) + 1, name
        total = sum(float(line.split()[1]) for line in lines[1:])
        assert abs(total - float(r["skin_area_A2"])) <= 5e-7 * int(r["atoms"]), name
        mesh = skinmesh.read_mesh(tmp_path / "out" / (name + ".ply"))
        assert len(mesh.triangles) == int(r["triangles"]), name
    # Resumable: nothing to do; one mesh removed, only it (and the table) made again.
    again = snakemake(tmp_path, "-n")
    assert again.returncode == 0 and "Nothing to be done" in again.stdout + again.stderr
    out = tmp_path / "out"
    before = {n: os.stat(out / n).st_mtime_ns for n in os.listdir(out) if n.endswith((".ply", ".json", ".area"))}
    os.remove(out / "ligand_2zmm.pdb.ply")
    redo = snakemake(tmp_path)
    assert redo.returncode == 0, redo.stderr[-2000:]
    changed = {n for n, t in before.items() if os.stat(out / n).st_mtime_ns != t}
    assert changed == {"ligand_2zmm.pdb.ply", "ligand_2zmm.pdb.json", "ligand_2zmm.pdb.area"}


def test_snakemake_meshes_one_structure_as_regions_over_jobs(tmp_path):
    # slabs=N: the cuts in one job, each region in a job of its own, the glue,
    # refinement and check in the last: the mesh of one process, byte for byte.
    inputs = tmp_path / "in"
    inputs.mkdir()
    shutil.copy(os.path.join(DATA, "crambin_1crn.pdb"), inputs)
    run = subprocess.run(["snakemake", "-s", SNAKEFILE, "-j", "2", "--directory", str(tmp_path),
                          "--config", "inputs=" + str(inputs), "out=" + str(tmp_path / "out"),
                          "skinmesh=" + os.path.abspath(SKINMESH), "slabs=4", "cut_detours=1"],
                         capture_output=True, text=True, timeout=900)
    assert run.returncode == 0, run.stderr[-2000:]
    regions = tmp_path / "out" / "regions" / "crambin_1crn.pdb"
    with open(regions / "regions.txt") as f:
        count = int(f.read())
    assert count == 4
    assert sorted(os.listdir(regions)) == sorted(["cuts.bin", "regions.txt"] + ["%d.region" % k for k in range(count)])
    one = tmp_path / "one.ply"
    subprocess.run([SKINMESH, "mesh", str(inputs / "crambin_1crn.pdb"), "--slabs", "4", "--cut-detours", "-q",
                    "-o", str(one)], check=True)
    with open(one, "rb") as a, open(tmp_path / "out" / "crambin_1crn.pdb.ply", "rb") as b:
        assert a.read() == b.read()
    with open(tmp_path / "out" / "summary.csv") as f:
        rows = list(csv.DictReader(f))
    assert [r["checks_passed"] for r in rows] == ["True"]
