#!/usr/bin/env bash
# tests/fuzz/run.sh BUILD_DIR SECONDS [TARGET...]: runs the libFuzzer targets of
# tests/fuzz (built in BUILD_DIR with -DSKINMESH_FUZZ=ON; `make fuzz` does both)
# for SECONDS each, every one on a scratch copy of its seed corpus
# (tests/fuzz/corpus/<format>/, never grown in place) with its dictionary
# (tests/fuzz/dict/<format>.dict). TARGETs default to all: pdb cif pqr xyzr xyzrn ply
# off obj stl vtk vtkxml msms molecule_invariants mesh_invariants; an invariant target gets the
# seeds and dictionaries of every format of its reader.
# Limits: -timeout=10 (seconds per input), -rss_limit_mb=2048 and
# -malloc_limit_mb=2048. Any crash, sanitizer report, uncaught exception, hang
# or allocation beyond the limits fails the run (exit 1); the input is kept as
# BUILD_DIR/fuzz-artifacts/<target>-<kind>-<sha1> with the log beside it
# (reproduce: BUILD_DIR/tests/fuzz/fuzz_<target> <that file>).
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR SECONDS [TARGET...]" >&2
  exit 2
fi
build=$1
seconds=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(pdb cif pqr xyzr xyzrn ply off obj stl vtk vtkxml msms molecule_invariants mesh_invariants)

# The formats whose seeds and dictionary a target uses.
formats_of() {
  case $1 in
    molecule_invariants) echo pdb cif pqr xyzr xyzrn ;;
    mesh_invariants) echo ply off obj stl vtk vtkxml msms ;;
    *) echo "$1" ;;
  esac
}

scratch_root=${TMPDIR:-/tmp}
if [ -d /dev/shm ] && [ -w /dev/shm ]; then scratch_root=/dev/shm; fi
scratch=$(mktemp -d "$scratch_root/skinmesh-fuzz.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
artifacts=$build/fuzz-artifacts
mkdir -p "$artifacts"
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

failed=()
summary=()
for t in "${targets[@]}"; do
  bin=$build/tests/fuzz/fuzz_$t
  if [ ! -x "$bin" ]; then
    echo "fuzz: $bin not built" >&2
    exit 2
  fi
  corpus=$scratch/corpus_$t
  dict=$scratch/$t.dict
  mkdir -p "$corpus"
  : >"$dict"
  for f in $(formats_of "$t"); do
    cp "$here/corpus/$f/"* "$corpus/"
    grep -v '^#' "$here/dict/$f.dict" >>"$dict"
  done
  sort -u -o "$dict" "$dict"
  seeds=$(find "$corpus" -type f | wc -l)
  log=$scratch/$t.log
  echo "fuzz_$t: ${seconds}s on $seeds seeds ($(formats_of "$t"))"
  start=$(date +%s)
  status=0
  "$bin" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -dict="$dict" -artifact_prefix="$artifacts/$t-" -print_final_stats=1 "$corpus" >"$log" 2>&1 || status=$?
  elapsed=$(( $(date +%s) - start ))
  runs=$(sed -n 's/^Done \([0-9]*\) runs in \([0-9]*\) second.*/\1 runs in \2 s/p' "$log" | tail -n 1)
  cov=$(grep -E '^#[0-9]+.*(DONE|pulse|NEW|REDUCE)' "$log" | tail -n 1 | sed -n 's/.* cov: \([0-9]*\) ft: \([0-9]*\) corp: \([0-9]*\).*/cov \1, ft \2, corpus \3/p')
  if [ "$status" -eq 0 ]; then
    summary+=("$(printf '%-26s ok      %-24s %s (wall %ss)' "fuzz_$t" "$runs" "$cov" "$elapsed")")
  else
    failed+=("fuzz_$t")
    cp "$log" "$artifacts/$t.log"
    summary+=("$(printf '%-26s FAILED  exit %s after %ss; log %s' "fuzz_$t" "$status" "$elapsed" "$artifacts/$t.log")")
    echo "---- fuzz_$t failed (exit $status); the end of its log:" >&2
    grep -v -E '^#[0-9]+' "$log" | tail -n 60 >&2
  fi
done

echo
echo "libFuzzer summary (${seconds}s per target):"
printf '  %s\n' "${summary[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: FAILED: ${failed[*]} (inputs in $artifacts)" >&2
  exit 1
fi
