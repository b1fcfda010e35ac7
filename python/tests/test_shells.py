"""Shell selection from Python: mesh(..., cavities=, min_cavity_volume=),
check() with the same arguments, and Mesh.write() of a selected mesh to a
format that rounds (its stored check expects the kept shells)."""
import os

import pytest

import skinmesh

DATA = os.environ.get("SKINMESH_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
CRAMBIN = os.path.join(DATA, "crambin_1crn.pdb")


def kinds(m):
    return [c["kind"] for c in m.stats["surface"]["components"]]


def test_cavities_remove_keeps_the_body_only_and_checks(tmp_path):
    # Crambin at probe 0: one body and ten cavities.
    m = skinmesh.mesh(CRAMBIN, probe=0, threads=2, cavities="remove")
    assert m.ok
    assert kinds(m) == ["body"]
    shells = m.stats["surface"]["shells"]
    assert shells["kept_bodies"] == 1 and shells["removed_cavities"] == 10
    assert skinmesh.check(CRAMBIN, m, probe=0, cavities="remove")["problems"] == []
    assert skinmesh.check(CRAMBIN, m, probe=0)["topology_matches"] is False
    # Three decimals break one of the removed cavities, not the body.
    m.write(tmp_path / "c.vert")
    assert skinmesh.check(CRAMBIN, tmp_path / "c.vert", probe=0, cavities="remove")["problems"] == []


def test_cavities_only_and_min_volume():
    only = skinmesh.mesh(CRAMBIN, probe=0, threads=2, cavities="only", min_cavity_volume=0.5)
    assert only.ok
    assert set(kinds(only)) == {"cavity"}
    assert all(-c["volume_A3"] >= 0.5 for c in only.stats["surface"]["components"])
    assert 0 < len(kinds(only)) < 10
    assert skinmesh.check(CRAMBIN, only, probe=0, cavities="only", min_cavity_volume=0.5)["problems"] == []
    with pytest.raises(skinmesh.InputError):
        skinmesh.mesh(CRAMBIN, probe=0, cavities="none")
    with pytest.raises(skinmesh.InputError):
        skinmesh.mesh(CRAMBIN, probe=0, min_cavity_volume=-1)
