#!/usr/bin/env python3
"""ctest fallback_share: bench/fallback_share.py tells the runs that used the local patch from those that did not.

    python3 tests/bench/fallback_share_test.py build/skinmesh

Meshes the amprenavir ligand and crambin at probe 1.4 twice through the script: as they are (no fallback) and with
every hole of the seal forced through the patch (--force-patch-every 1, a testing aid of skinmesh mesh). The JSON
must say 0 of 2 and then 2 of 2 with a local patch, every check passed both times, and the printed share must
agree.
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def share(binary, tmp, extra):
    out = os.path.join(tmp, "share.json")
    files = [os.path.join(ROOT, "data", f) for f in ("ligand_1hpv_amprenavir.pdb", "crambin_1crn.pdb")]
    proc = subprocess.run([sys.executable, os.path.join(ROOT, "bench", "fallback_share.py"), binary] + files +
                          ["--probe", "1.4", "--jobs", "2", "--json", out] + extra, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit("fallback_share.py failed (%d):\n%s%s" % (proc.returncode, proc.stdout, proc.stderr))
    with open(out) as f:
        return proc.stdout, json.load(f)


def main():
    binary = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory() as tmp:
        text, plain = share(binary, tmp, [])
        s = plain["summary"][0]
        assert (s["inputs"], s["passed"], s["local_patch"], s["whole_skin"], s["failed"]) == (2, 2, 0, 0, 0), s
        assert "local patch in 0 (0.0 %)" in text, text
        text, forced = share(binary, tmp, ["--mesh-arg=--force-patch-every", "--mesh-arg=1"])
        s = forced["summary"][0]
        assert (s["inputs"], s["passed"], s["local_patch"], s["whole_skin"], s["failed"]) == (2, 2, 2, 0, 0), s
        assert all(r["patched_holes"] > 0 for r in forced["runs"]), forced["runs"]
        assert "local patch in 2 (100.0 %)" in text and text.count("local patch x") == 2, text
    print("fallback_share: ok")


if __name__ == "__main__":
    main()
