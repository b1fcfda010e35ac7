#!/usr/bin/env bash
# The trace viewer in a real browser: records traces with `skinmesh trace`
# (Figure 4's cube corners with the sweep, the two-atom neck with the dynamic
# baseline, gramicidin A) and drives the pages in headless Chromium with
# trace/viewer/test/browser_test.mjs (playwright-core). Exit 77 (ctest:
# skipped), with a line that says why, when chromium, node, the viewer's npm
# packages or the built viewer are missing.
# Usage: browser_test.sh SKINMESH_BINARY BUILD_DIR
set -euo pipefail
bin=$1
build=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
chromium=${CHROMIUM:-/usr/bin/chromium}
skip() { echo "SKIP: $*" | tee "$build/browser_test.log"; exit 77; }
[ -x "$chromium" ] || skip "chromium not found at $chromium (bash .ci/install-deps --browser installs it)"
command -v node >/dev/null 2>&1 || skip "node not found (bash .ci/install-deps --browser installs it)"
[ -f "$build/trace_viewer.html" ] || skip "the viewer is not built: $build/trace_viewer.html (make viewer)"
[ -d "$root/trace/viewer/node_modules/playwright-core" ] || skip "the viewer's npm packages are not installed (make viewer)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin" trace "$root/tests/data/cube_corners.xyzr" --probe 0 -o "$tmp/cube_corners_sweep.html" -q
"$bin" trace "$root/tests/data/two_atoms_neck.xyzr" --probe 0 --algorithm dynamic -o "$tmp/two_atoms_neck_dynamic.html" -q
"$bin" trace "$root/data/gramicidinA_1grm_model1.pdb" -o "$tmp/gramicidin_sweep.html" -q
ls -l "$tmp"/*.html
# The log is kept beside the build (make test prints it: ctest shows the
# output of failed tests only).
CHROMIUM=$chromium node "$root/trace/viewer/test/browser_test.mjs" "$tmp"/*.html 2>&1 | tee "$build/browser_test.log"
