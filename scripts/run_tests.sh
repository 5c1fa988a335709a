#!/usr/bin/env bash
# The test command behind `make test`: unit and verification tests (fpm test),
# command-line tests, and the reference-output diffs. Ends with the single
# line "N passed, N failed" and exits non-zero on any failure.
set -uo pipefail
cd "$(dirname "$0")/.."
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"   # the package python/visco2d/ (doc/python.md)
exe=${VISCO2D:-build/install/bin/visco2d}
log=build/test-logs
rm -rf "$log" && mkdir -p "$log"
passed=0
failed=0

stage_start=$SECONDS
stage() {  # end the running stage with its wall time, then print the next stage's title
  [ -n "${stage_open:-}" ] && echo "   ($((SECONDS - stage_start)) s)"
  stage_open=1
  stage_start=$SECONDS
  [ $# -gt 0 ] && echo "$1"
  return 0
}

count() {  # count PASS/FAIL lines of a log; echo the FAIL lines
  local file=$1
  local p f
  p=$(grep -c '^PASS ' "$file" || true)
  f=$(grep -c '^FAIL ' "$file" || true)
  passed=$((passed + p))
  failed=$((failed + f))
  grep '^FAIL ' "$file" || true
}

stage "== source floors (scripts/check_layers.py: no module uses one of a floor above it; the base modules' reach)"
python3 scripts/check_layers.py src > "$log/layers.log" 2>&1
count "$log/layers.log"
echo "   $(grep -c '^PASS layers ' "$log/layers.log") files checked, $(grep -c '^PASS reach ' "$log/layers.log") base modules within their reach"

stage "== documentation links (scripts/check_links.py: links, anchors, quoted paths, tables of README.md and doc/)"
python3 scripts/check_links.py > "$log/links.log" 2>&1
count "$log/links.log"
grep '^   ' "$log/links.log" || true
echo "   $(grep -c '^PASS ' "$log/links.log") pages checked"

stage "== walk-through (scripts/check_walkthrough.py: every line doc/walkthrough.md quotes is in the code, in order)"
python3 scripts/check_walkthrough.py doc/walkthrough.md > "$log/walkthrough.log" 2>&1
count "$log/walkthrough.log"
echo "   $(grep -c '^PASS ' "$log/walkthrough.log") quoted blocks match"

stage "== Python package (pytest python/tests: the readers, runner, Hertz formulas, sweeps, launchers of python/visco2d/)"
# One PASS/FAIL line per test; a collection error (no test ran) is one FAIL.
(cd python && python3 -m pytest -v -p no:cacheprovider tests) > "$log/pytest.log" 2>&1
pytest_status=$?
sed -n -E 's#^(tests/[^ ]+) PASSED.*#PASS pytest \1#p; s#^(tests/[^ ]+) (FAILED|ERROR).*#FAIL pytest \1: see '"$log"'/pytest.log#p' \
  "$log/pytest.log" > "$log/pytest.lines"
if [ "$pytest_status" != 0 ] && ! grep -q '^FAIL ' "$log/pytest.lines"; then
  echo "FAIL pytest: exit status $pytest_status and no failed test named: $(tail -3 "$log/pytest.log" | tr '\n' '|')" >> "$log/pytest.lines"
fi
count "$log/pytest.lines"
echo "   $(grep -c '^PASS ' "$log/pytest.lines") tests passed"

# fpm does not rebuild the test-side modules (visco2d_testing, ...) when a
# library module they use changes, and a stale .mod then breaks the build of
# the tests ("Mismatch in components of derived type"): after a change under
# src/, the tests' objects and modules are compiled again.
for stamp in build/gfortran_*/visco2d_testing.mod; do
  [ -e "$stamp" ] || continue
  if [ -n "$(find src -newer "$stamp" \( -name '*.f90' -o -name '*.F90' -o -name '*.c' \) -print -quit)" ]; then
    dir=$(dirname "$stamp")
    rm -f "$dir"/visco2d/test_* "$dir"/visco2d_testing.mod "$dir"/visco2d_test_decks.mod \
          "$dir"/visco2d_analytic.mod "$dir"/visco2d_spectrum.mod "$dir"/visco2d_mesh_measures.mod
  fi
done

stage "== unit and verification tests (fpm test; one line per test program as it finishes)"
fpm test --profile release 2>&1 | tee "$log/fpm-test.log" | grep --line-buffered -E '^[a-z_]+: [0-9]+ passed' \
  | { last=$SECONDS; while IFS= read -r line; do echo "   $line   [$((SECONDS - last)) s]"; last=$SECONDS; done; }
status=${PIPESTATUS[0]}
count "$log/fpm-test.log"
if [ $status -ne 0 ] && ! grep -q '^FAIL ' "$log/fpm-test.log"; then
  echo "FAIL fpm test exited with status $status without a failed check (a crash?); see $log/fpm-test.log"
  tail -20 "$log/fpm-test.log"
  failed=$((failed + 1))
fi

stage "== command-line tests"
bash scripts/test_cli.sh "$exe" > "$log/cli.log" 2>&1
count "$log/cli.log"
echo "   $(grep -c '^PASS ' "$log/cli.log") checks passed"

stage "== results.xmf in ParaView's readers (scripts/test_xdmf.sh: every field against results.h5, Warp By Vector)"
bash scripts/test_xdmf.sh "$exe" > "$log/xdmf.log" 2>&1
count "$log/xdmf.log"
grep '^SKIP ' "$log/xdmf.log" | sed 's/^/   /' || true
echo "   $(grep -c '^PASS ' "$log/xdmf.log") checks passed"

stage "== MPI task farm (2 ranks; built first: the batch stage runs --mpi through it)"
bash scripts/test_mpi.sh "$exe" > "$log/mpi.log" 2>&1
count "$log/mpi.log"
echo "   $(grep -c '^PASS ' "$log/mpi.log") checks passed; $(grep '^# ' "$log/mpi.log" | tr '\n' ' ')"

stage "== memory estimate (scripts/test_estimate.sh: estimate / measured peak of a spread of decks, refusal over the limit)"
bash scripts/test_estimate.sh "$exe" > "$log/estimate.log" 2>&1
count "$log/estimate.log"
echo "   $(grep -c '^PASS ' "$log/estimate.log") checks passed"

stage "== batch runs and sweeps (scripts/test_batch.sh: visco2d-batch sweeps, -j, shards, collect, threshold, MPI)"
bash scripts/test_batch.sh "$exe" > "$log/batch.log" 2>&1
count "$log/batch.log"
grep -E '^(NOTE|# )' "$log/batch.log" | sed 's/^/   /' || true
echo "   $(grep -c '^PASS ' "$log/batch.log") checks passed"

stage "== damage boundary (scripts/test_boundary.sh: visco2d-batch boundary against threshold, its table, chart, warnings)"
bash scripts/test_boundary.sh "$exe" > "$log/boundary.log" 2>&1
count "$log/boundary.log"
grep -E '^(NOTE|# )' "$log/boundary.log" | sed 's/^/   /' || true
echo "   $(grep -c '^PASS ' "$log/boundary.log") checks passed"

stage "== processes and hosts (scripts/test_hosts.sh: shared output roots, case locks; batch interrupt, resume, guards)"
bash scripts/test_hosts.sh "$exe" > "$log/hosts.log" 2>&1
count "$log/hosts.log"
grep -E '^(NOTE|# )' "$log/hosts.log" | sed 's/^/   /' || true
echo "   $(grep -c '^PASS ' "$log/hosts.log") checks passed"

stage "== study (make study-fast)"
bash scripts/test_study.sh "$exe" > "$log/study.log" 2>&1
count "$log/study.log"
echo "   $(grep -c '^PASS ' "$log/study.log") checks passed"

stage "== figures (make figures smoke check)"
bash scripts/test_figures.sh "$exe" > "$log/figures.log" 2>&1
count "$log/figures.log"
echo "   $(grep -c '^PASS ' "$log/figures.log") checks passed"

stage "== report (make report smoke check)"
bash scripts/test_report.sh "$exe" > "$log/report.log" 2>&1
count "$log/report.log"
echo "   $(grep -c '^PASS ' "$log/report.log") checks passed"

stage "== reference outputs (rtol 1e-6)"
rm -rf build/reference-check && mkdir -p build/reference-check
for deck in inputs/*.inp; do
  case_name=$(basename "$deck" .inp)
  if [ ! -d "reference_outputs/$case_name" ]; then
    echo "FAIL $case_name: no archived reference (make bless DECK=$deck, on purpose)" | tee -a "$log/reference.log"
    continue
  fi
  "$exe" -q -o build/reference-check "$deck" >> "$log/reference.log" 2>&1
  status=$?
  if [ $status -ne 0 ] && [ $status -ne 3 ]; then  # 3: it ran, and missed an EXPECT card (reported below)
    echo "FAIL $case_name: the deck did not run (exit $status); see $log/reference.log" | tee -a "$log/reference.log"
    continue
  fi
  missed=$(sed -n 's/^expect_\(.*\)_within_rtol = no$/\1/p' "build/reference-check/$case_name/summary.txt" | tr '\n' ' ')
  if [ -n "$missed" ]; then  # a deck's EXPECT cards are its analytic answers: a miss is a failure
    echo "FAIL $case_name: outside the RTOL of its EXPECT card(s): $missed" | tee -a "$log/reference.log"
  fi
  python3 -m visco2d.diff "reference_outputs/$case_name" "build/reference-check/$case_name" \
    > build/reference-check/compare.log 2>&1
  status=$?
  cat build/reference-check/compare.log >> "$log/reference.log"
  if [ $status -eq 1 ]; then  # the worst differences (the FAIL lines follow at the end of the stage)
    grep '^   ' build/reference-check/compare.log | head -5 | sed "s/^   /   $case_name: /"
  elif [ $status -ne 0 ]; then
    echo "FAIL $case_name: the diff could not compare (exit $status): $(cat build/reference-check/compare.log)" \
      | tee -a "$log/reference.log"
  fi
done
for folder in reference_outputs/*/; do
  [ -d "$folder" ] || continue
  case_name=$(basename "$folder")
  [ -f "inputs/$case_name.inp" ] || echo "FAIL $case_name: archived reference without a deck in inputs/" \
    | tee -a "$log/reference.log"
done
count "$log/reference.log"
echo "   $(grep -c '^PASS ' "$log/reference.log") files match"

stage "== diff and bless (scripts/test_diff.sh: compare_outputs.py and bless.py on scratch copies)"
bash scripts/test_diff.sh "$exe" > "$log/diff.log" 2>&1
count "$log/diff.log"
echo "   $(grep -c '^PASS ' "$log/diff.log") checks passed"

stage "== fuzz (python/visco2d/fuzz.py: mutated decks and the regression decks of test/fuzz/)"
bash scripts/test_fuzz.sh "$exe" > "$log/fuzz.log" 2>&1
count "$log/fuzz.log"
echo "   $(grep -c '^PASS ' "$log/fuzz.log") checks passed; $(grep '^# ' "$log/fuzz.log" | tr '\n' ' ')"

stage "== checked build (-fcheck=all, address and undefined-behaviour sanitizers)"
bash scripts/test_checked.sh > "$log/checked.log" 2>&1
count "$log/checked.log"
echo "   $(grep -c '^PASS ' "$log/checked.log") checks passed; $(grep '^# ' "$log/checked.log" | tr '\n' ' ')"

stage
echo "   (all stages: $((SECONDS / 60)) min $((SECONDS % 60)) s)"
echo "${passed} passed, ${failed} failed"
[ "$failed" -eq 0 ]
