#!/usr/bin/env bash
# Smoke check of `make report` (python/visco2d/report.py): a small dropped sphere with a
# BRUISE card (level 2, to separation, well under a second) and the same sphere
# without the card get their report.png; a case folder with neither contact nor
# BRUISE is skipped; a folder that is not a case fails with a clear message and
# writes nothing.
# usage: scripts/test_report.sh [EXE]   (prints PASS/FAIL lines)
set -uo pipefail
cd "$(dirname "$0")/.."
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"   # the package python/visco2d/ (doc/python.md)
exe=${1:-${VISCO2D:-build/install/bin/visco2d}}
tmp=build/test-tmp/report
rm -rf "$tmp" && mkdir -p "$tmp"

pass() { echo "PASS $*"; }
fail() { echo "FAIL $*"; }
# a PNG starts with the 8-byte signature 89 50 4E 47 0D 0A 1A 0A; a drawn report (several panels) is > 50 kB
is_png() { [ -f "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] \
             && [ "$(stat -c %s "$1")" -gt 50000 ]; }

cp test/decks/bruise_drop.inp "$tmp/drop_bruise.inp"   # run from the repository root (cd above)
grep -v '^BRUISE' "$tmp/drop_bruise.inp" | sed 's/with a bruise criterion/without BRUISE/' > "$tmp/drop_plain.inp"
cat > "$tmp/flight.inp" <<'DECK'
TITLE report smoke test: free flight, no plate, no BRUISE
ANALYSIS DYNAMIC
GEOMETRY AXISYMMETRIC
MATERIAL apple ELASTIC E=6e6 NU=0.3 RHO=800
MESH SPHERE R=0.0381 LEVEL=1
INITIAL VZ=-2
TIME DT=1e-5 TEND=1e-4
END
DECK
if "$exe" -q -o "$tmp/out" "$tmp/drop_bruise.inp" "$tmp/drop_plain.inp" "$tmp/flight.inp" > "$tmp/run.txt" 2>&1; then
  pass "the three decks ran"
else
  fail "visco2d exited with status $? on the decks (see $tmp/run.txt)"
fi

# 1. The whole output root: the two impacts drawn, the free flight skipped.
if python3 -m visco2d.report --out "$tmp/out" > "$tmp/log.txt" 2>&1; then
  pass "report.py ran on the output root"
else
  fail "report.py exited with status $? (see $tmp/log.txt)"; tail -5 "$tmp/log.txt"
fi
for case_name in drop_bruise drop_plain; do
  png="$tmp/out/$case_name/report.png"
  is_png "$png" && grep -q "  $png\$" "$tmp/log.txt" && pass "$case_name/report.png written, a PNG, listed" \
    || fail "$case_name/report.png missing, not a PNG, too small, or not listed"
done
[ ! -e "$tmp/out/flight/report.png" ] && grep -q "flight: skipped" "$tmp/log.txt" \
  && pass "a run without contact or BRUISE is skipped, said so" || fail "free flight not skipped or not said"
ls "$tmp"/out/*/*.part.png > /dev/null 2>&1 && fail "a temporary .part.png was left" || pass "no temporary file left"

# 2. The envelope the report draws: its nodal averaging of the Gauss-point envelope is the file's
#    own max_shear_envelope_nodal (to round-off), the outline's level (envelope / threshold = 1)
#    lies between the smallest and largest nodal ratio, and the numbers panel quotes the summary.
python3 - "$tmp/out/drop_bruise" <<'EOF' || fail "the envelope checks did not run (python exit status $?)"
import sys
import numpy as np
from visco2d import report as R
case = R.load_case(sys.argv[1])
data = R.envelope_data(case)
b = case["bruise"]
mine = R.gauss_to_nodes(b["max_shear_envelope"], case["elements"], len(case["nodes"]))
error = np.abs(mine - b["max_shear_envelope_nodal"]).max() / b["max_shear_envelope_nodal"].max()
print(f"{'PASS' if error < 1e-12 else 'FAIL'} nodal envelope = /bruise/max_shear_envelope_nodal (rel. error {error:.1e})")
ok = data["ratio"].min() < 1.0 <= data["ratio"].max()
print(f"{'PASS' if ok else 'FAIL'} threshold contour inside the field: ratio {data['ratio'].min():.3g} .. {data['ratio'].max():.3g}")
peak = data["peak"][2] * 1e6
want = case["summary"]["envelope_max_shear_max_Pa"]
print(f"{'PASS' if abs(peak - want) <= 1e-9 * want else 'FAIL'} marked maximum {peak:.6g} Pa = summary {want:.6g} Pa")
text = R.numbers_text(case, data)
volume = f"{case['summary']['bruise_volume_cm3']:.4g} cm³"
print(f"{'PASS' if volume in text and 'α_m' in text else 'FAIL'} numbers panel quotes alpha_m and the bruise volume {volume}")
EOF

# 3. A case named on the command line (a name under --out) redraws only that one.
rm -f "$tmp/out/drop_bruise/report.png"
python3 -m visco2d.report --out "$tmp/out" drop_bruise > "$tmp/log2.txt" 2>&1 \
  && is_png "$tmp/out/drop_bruise/report.png" && grep -q "1 files written" "$tmp/log2.txt" \
  && pass "a case named under --out is drawn alone" || fail "a named case: $(cat "$tmp/log2.txt")"

# 4. Clear errors, nothing written: a folder that is not a case, a folder that does not exist,
#    an empty output root, a results.h5 that is not HDF5.
mkdir -p "$tmp/notacase"
echo "not a run" > "$tmp/notacase/readme.txt"
rm -f "$tmp/out/drop_plain/report.png"
out=$(python3 -m visco2d.report --out "$tmp/out" drop_plain "$tmp/notacase" 2>&1); status=$?
[ $status -eq 1 ] && echo "$out" | grep -q "^report: error: $tmp/notacase is not a visco2d case folder (no results.h5" \
  && pass "not a case: clear error, status 1" || fail "not a case: status $status, '$out'"
[ ! -e "$tmp/out/drop_plain/report.png" ] && pass "not a case: nothing drawn for the other folders" \
  || fail "not a case: drop_plain was drawn before the error"
out=$(python3 -m visco2d.report "$tmp/no-such-folder" 2>&1); status=$?
[ $status -eq 1 ] && echo "$out" | grep -q "^report: error: $tmp/no-such-folder is not a folder" \
  && pass "missing folder: clear error" || fail "missing folder: status $status, '$out'"
out=$(python3 -m visco2d.report --out "$tmp/notacase" 2>&1); status=$?
[ $status -eq 1 ] && echo "$out" | grep -q "^report: error: no case folder .* in $tmp/notacase" \
  && pass "output root without cases: clear error" || fail "output root without cases: status $status, '$out'"
mkdir -p "$tmp/broken" && echo "not HDF5" > "$tmp/broken/results.h5"
out=$(python3 -m visco2d.report "$tmp/broken" 2>&1); status=$?
[ $status -eq 1 ] && echo "$out" | grep -q "^report: error: $tmp/broken/results.h5 cannot be read as HDF5" \
  && [ ! -e "$tmp/broken/report.png" ] && pass "broken results.h5: clear error" \
  || fail "broken results.h5: status $status, '$out'"
