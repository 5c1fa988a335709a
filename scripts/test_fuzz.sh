#!/usr/bin/env bash
# The fuzz stage of `make test` (seconds):
#
#   bash scripts/test_fuzz.sh [PATH/TO/visco2d]     (default build/install/bin/visco2d)
#
# 0. The fuzzer's own checks: a stub executable misbehaving one way per deck
#    (`PASS fuzz_detects_<what>`): each misbehaviour lands in its class.
# 1. FUZZ_N (default 300) mutated decks of python/visco2d/fuzz.py, seed FUZZ_SEED (default 1),
#    each bounded to FUZZ_BOUND seconds (default 8): one line per failure class,
#    `PASS fuzz_no_<class>` or `FAIL fuzz_no_<class>: count and examples` (the
#    classes: python/visco2d/fuzz.py --help). Report in build/fuzz-test/random/.
# 2. Every regression deck in test/fuzz/ (test/fuzz/README.md), as it is:
#    `PASS fuzz_regression/<deck>` or `FAIL ...: reason`. Report in build/fuzz-test/regression/.
# Always exits 0: the caller counts the lines.
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export PYTHONPATH="$root/python${PYTHONPATH:+:$PYTHONPATH}"   # the package python/visco2d/ (doc/python.md)
exe=${1:-$root/build/install/bin/visco2d}
out=$root/build/fuzz-test
rm -rf "$out" && mkdir -p "$out"
count=${FUZZ_N:-300}
seed=${FUZZ_SEED:-1}
bound=${FUZZ_BOUND:-8}

# 0. The checks themselves: a stub executable that misbehaves on purpose, one way per
#    deck; each misbehaviour must be classified as its class (and a clean run must pass).
stub=$out/stub
mkdir -p "$stub/decks"
cat > "$stub/visco2d" <<'STUB'
#!/usr/bin/env bash
# usage like visco2d: -q -o OUT DECK
out=$3; deck=$4; case=$(basename "$deck" .inp)
what=$(head -1 "$deck")
write_outputs() {  # the summary's value, the HDF5 file's value
  mkdir -p "$out/$case"
  printf 'case = %s\ntitle = nan in a title is fine\nmax_displacement_m = %s\n' "$case" "$1" > "$out/$case/summary.txt"
  printf 't_s,uz_m\n0,0\n' > "$out/$case/history.csv"
  printf ' title: inf\n INPUT CARDS\n  1 TITLE NaN\n\n RESULTS\n  1.0E+00\n' > "$out/$case/listing.txt"
  python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'w'); f['x'] = [0.0, float(sys.argv[2])]" \
    "$out/$case/results.h5" "$2"
}
case $what in
  clean) write_outputs 1.0 1.0 ;;
  crash) kill -SEGV $$ ;;
  runtime) echo 'Fortran runtime error: Index 0 of dimension 1 of array' >&2; exit 2 ;;
  hang) sleep 30 ;;
  partial) mkdir -p "$out/.$case.partial.1"; echo "visco2d: error: $deck:1: STUB: partial" >&2; exit 1 ;;
  nonfinite) write_outputs 1.0 1.0; echo 'max_displacement_m = NaN' >> "$out/$case/summary.txt" ;;
  nonfinite_h5) write_outputs 1.0 inf ;;
  unreadable) write_outputs 1.0 1.0; echo 'q_max_MPa = 1.0000000-300' >> "$out/$case/summary.txt" ;;
  unlocated) echo "visco2d: error: $deck: the stub has no line" >&2; exit 1 ;;
  output_on_error) write_outputs 1.0 1.0; echo "visco2d: error: $deck:1:1: STUB: left its folder" >&2; exit 1 ;;
  silent_energy) write_outputs 1.0 1.0; echo 'balance_error_max_rel = 5.0' >> "$out/$case/summary.txt" ;;
  silent_exit) write_outputs 1.0 1.0 ;;
  missing_output) mkdir -p "$out/$case"; echo 'case = x' > "$out/$case/summary.txt" ;;
  expect_missed) write_outputs 1.0 1.0; echo 'expect_max_displacement_m_within_rtol = no' >> "$out/$case/summary.txt"
    echo "visco2d: error: $deck:1:5: EXPECT: max_displacement_m = 1.0 is not within RTOL" >&2; exit 3 ;;
  expect_exit_0) write_outputs 1.0 1.0; echo 'expect_max_displacement_m_within_rtol = no' >> "$out/$case/summary.txt" ;;
  expect_exit_3_met) write_outputs 1.0 1.0; exit 3 ;;
  expect_unlocated) write_outputs 1.0 1.0; echo 'expect_max_displacement_m_within_rtol = no' >> "$out/$case/summary.txt"
    exit 3 ;;
  exit_4) write_outputs 1.0 1.0; exit 4 ;;
esac
STUB
chmod +x "$stub/visco2d"
for what in clean crash runtime hang partial nonfinite nonfinite_h5 unreadable unlocated output_on_error \
            missing_output silent_energy silent_exit expect_missed expect_exit_0 expect_exit_3_met expect_unlocated \
            exit_4; do
  echo "$what" > "$stub/decks/$what.inp"
done
echo '# fuzz: exit 1' >> "$stub/decks/silent_exit.inp"   # must be refused, the stub runs it
python3 -m visco2d.fuzz --exe "$stub/visco2d" --bound 2 --decks "$stub"/decks/*.inp --out "$stub/report" \
  -q > "$stub/log" 2>&1
python3 - "$stub/report/cases.csv" <<'PYTHON'
import csv, sys
expected = {'clean': '', 'crash': 'CRASH', 'runtime': 'CRASH', 'hang': 'HANG', 'partial': 'PARTIAL',
            'nonfinite': 'NONFINITE', 'nonfinite_h5': 'NONFINITE', 'unreadable': 'UNREADABLE',
            'unlocated': 'UNLOCATED', 'output_on_error': 'OUTPUT_ON_ERROR', 'missing_output': 'MISSING_OUTPUT',
            'silent_energy': 'SILENT', 'silent_exit': 'SILENT', 'expect_missed': '', 'expect_exit_0': 'SILENT',
            'expect_exit_3_met': 'SILENT', 'expect_unlocated': 'UNLOCATED', 'exit_4': 'CRASH'}
try:
    rows = {r['id']: r['classes'].split() for r in csv.DictReader(open(sys.argv[1]))}
except OSError as error:
    rows = {}
for name, wanted in expected.items():
    got = rows.get(name)
    ok = got is not None and (got == [] if not wanted else wanted in got)
    print('%s fuzz_detects_%s%s' % ('PASS' if ok else 'FAIL', name,
                                    '' if ok else ': classified %s, expected %s' % (got, wanted or 'a pass')))
PYTHON

start=$(date +%s)
python3 -m visco2d.fuzz --exe "$exe" -n "$count" --seed "$seed" --bound "$bound" \
  --out "$out/random" -q > "$out/random.log" 2>&1
status=$?
if [ ! -f "$out/random/cases.csv" ]; then
  echo "FAIL fuzz_ran: python/visco2d/fuzz.py (status $status) wrote no report: $(tail -3 "$out/random.log" | tr '\n' '|')"
else
  python3 - "$out/random" <<'PYTHON' || echo "FAIL fuzz_classes: the class checks did not run (python exit status $?)"
import csv, sys
from visco2d.fuzz import FAIL_CLASSES
rows = list(csv.DictReader(open(sys.argv[1] + '/cases.csv')))
for name in FAIL_CLASSES:
    bad = [r for r in rows if name in r['classes'].split()]
    if not bad:
        print('PASS fuzz_no_%s (%d decks)' % (name.lower(), len(rows)))
        continue
    signatures = {}
    for r in bad:
        mine = [s for s in r['signatures'].split(' || ') if s.split(' ', 1)[0] == name]
        signatures.setdefault(mine[0] if mine else r['signature'], []).append(r['id'])
    examples = '; '.join('%d x %s (e.g. %s)' % (len(ids), s[:110], ids[0])
                         for s, ids in sorted(signatures.items(), key=lambda kv: -len(kv[1]))[:3])
    print('FAIL fuzz_no_%s: %d of %d decks: %s; decks in %s/failures/%s/' % (
        name.lower(), len(bad), len(rows), examples, sys.argv[1], name))
PYTHON
fi
echo "# $count mutated decks in $(( $(date +%s) - start )) s"

start=$(date +%s)
decks=("$root"/test/fuzz/*.inp)
if [ -e "${decks[0]}" ]; then
  python3 -m visco2d.fuzz --exe "$exe" --bound "${FUZZ_REGRESSION_BOUND:-20}" --decks "${decks[@]}" \
    --out "$out/regression" -v -q --label fuzz_regression/ 2> "$out/regression.err" | grep -E '^(PASS|FAIL) '
  echo "# ${#decks[@]} regression decks in $(( $(date +%s) - start )) s"
fi
exit 0
