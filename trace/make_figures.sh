#!/usr/bin/env bash
# Makes the figures of the notes (papers/front/figures, papers/morse/figures,
# papers/trace/figures) from traces recorded by `skinmesh trace` and rendered
# headlessly by the viewer (trace/viewer/render.mjs, Debian chromium).
# Needs: the build (make build), the viewer (make viewer) and chromium
# (bash .ci/install-deps --browser).
# Usage: bash trace/make_figures.sh [BUILD_DIR]   (default: build)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
bin=$build/skinmesh
render=$root/trace/viewer/render.mjs
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
front=$root/papers/front/figures
morse=$root/papers/morse/figures
tracefig=$root/papers/trace/figures
mkdir -p "$front" "$morse" "$tracefig"

# step_of PAGE OP [WHICH]: the step whose op is OP: WHICH = first (default),
# last, or before (the step before the first).
step_of() {
  node -e '
    const fs = require("fs");
    const html = fs.readFileSync(process.argv[1], "utf8");
    const m = /<script id="skinmesh-trace" type="application\/json">([\s\S]*?)<\/script>/.exec(html);
    const steps = JSON.parse(m[1].replace(/<\\\//g, "</")).steps;
    const idx = steps.map((s, i) => s.op === process.argv[2] ? i : -1).filter((i) => i >= 0);
    if (!idx.length) { console.error("no step with op " + process.argv[2]); process.exit(1); }
    const which = process.argv[3] || "first";
    console.log(which === "last" ? idx[idx.length - 1] : which === "before" ? idx[0] - 1 : idx[0]);
  ' "$@"
}
# fraction_step PAGE STAGE F: the step at fraction F of the stage's steps.
fraction_step() {
  node -e '
    const fs = require("fs");
    const html = fs.readFileSync(process.argv[1], "utf8");
    const m = /<script id="skinmesh-trace" type="application\/json">([\s\S]*?)<\/script>/.exec(html);
    const steps = JSON.parse(m[1].replace(/<\\\//g, "</")).steps;
    const idx = steps.map((s, i) => s.stage === process.argv[2] ? i : -1).filter((i) => i >= 0);
    console.log(idx[Math.min(idx.length - 1, Math.floor(Number(process.argv[3]) * idx.length))]);
  ' "$@"
}
fig() {  # fig PAGE OUT.png STEP LAYERS [extra render options]
  local page=$1 out=$2 step=$3 layers=$4
  shift 4
  node "$render" "$page" "$out" --step "$step" --layers "$layers" --size 800x600 "$@"
}

"$bin" trace "$root/tests/data/cube_corners.xyzr" --probe 0 -o "$tmp/cube.html"
"$bin" trace "$root/tests/data/two_atoms_neck.xyzr" -o "$tmp/neck.html"
"$bin" trace "$root/tests/data/two_atoms_neck.xyzr" --algorithm dynamic -o "$tmp/neck_dynamic.html"
"$bin" trace "$root/data/adna_3dna_fiber_30bp.pdb" -o "$tmp/adna.html"
"$bin" trace "$root/data/ligand_1hpv_amprenavir.pdb" -o "$tmp/amprenavir.html"

# The sweep's operations on Figure 4's configuration (eight weighted points at the corners of a cube).
fig "$tmp/cube.html" "$front/creation.png" "$(step_of "$tmp/cube.html" creation last)" skin,front,critical --view 30,-25,1
fig "$tmp/cube.html" "$front/creep.png" "$(fraction_step "$tmp/cube.html" sweep 0.3)" skin,front,critical,arcs
fig "$tmp/cube.html" "$front/wing.png" "$(step_of "$tmp/cube.html" wings)" skin,front,critical --view 30,-25,1
fig "$tmp/cube.html" "$front/sweep_late.png" "$(fraction_step "$tmp/cube.html" sweep 0.8)" skin,front,critical,spheres
fig "$tmp/cube.html" "$front/seal.png" "$(step_of "$tmp/cube.html" seal before)" skin,front,critical
fig "$tmp/neck.html" "$front/bridge_before.png" "$(step_of "$tmp/neck.html" bridge before)" skin,front,critical,spheres --view 20,-30,0.8
fig "$tmp/neck.html" "$front/bridge.png" "$(step_of "$tmp/neck.html" bridge)" skin,front,critical,spheres --view 20,-30,0.8
fig "$tmp/cube.html" "$front/refinement.png" -1 skin --quality min_angle
fig "$tmp/neck_dynamic.html" "$front/dynamic_growth.png" "$(fraction_step "$tmp/neck_dynamic.html" growth 0.5)" skin,front

# The Morse–Smale complex: Figure 4's configuration, the A-DNA torus, amprenavir (Figure 10a's stand-in).
fig "$tmp/cube.html" "$morse/ms_cube_corners.png" 0 critical,arcs,spheres
fig "$tmp/adna.html" "$morse/ms_adna.png" -1 skin,critical,arcs
fig "$tmp/amprenavir.html" "$morse/ms_amprenavir.png" -1 skin,critical,arcs
fig "$tmp/amprenavir.html" "$morse/ms_amprenavir_quality.png" -1 skin --quality min_angle

# README's picture: the sweep a third of the way up Figure 4's configuration.
cp "$front/creep.png" "$tracefig/readme_sweep.png"
ls -l "$front" "$morse" "$tracefig"
