#!/usr/bin/env bash
# The fuzz stage of `make test` (seconds):
#
#   bash scripts/test_fuzz.sh [PATH/TO/visco2d]     (default build/install/bin/visco2d)
#
# 1. FUZZ_N (default 300) mutated decks of scripts/fuzz.py, seed FUZZ_SEED (default 1),
#    each bounded to FUZZ_BOUND seconds (default 8): one line per failure class,
#    `PASS fuzz_no_<class>` or `FAIL fuzz_no_<class>: count and examples` (the
#    classes: scripts/fuzz.py --help). Report in build/fuzz-test/random/.
# 2. Every regression deck in test/fuzz/ (test/fuzz/README.md), as it is:
#    `PASS fuzz_regression/<deck>` or `FAIL ...: reason`. Report in build/fuzz-test/regression/.
# Always exits 0: the caller counts the lines.
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
exe=${1:-$root/build/install/bin/visco2d}
out=$root/build/fuzz-test
rm -rf "$out" && mkdir -p "$out"
count=${FUZZ_N:-300}
seed=${FUZZ_SEED:-1}
bound=${FUZZ_BOUND:-8}

start=$(date +%s)
python3 "$root/scripts/fuzz.py" --exe "$exe" -n "$count" --seed "$seed" --bound "$bound" \
  --out "$out/random" -q > "$out/random.log" 2>&1
status=$?
if [ ! -f "$out/random/cases.csv" ]; then
  echo "FAIL fuzz_ran: scripts/fuzz.py (status $status) wrote no report: $(tail -3 "$out/random.log" | tr '\n' '|')"
else
  python3 - "$out/random" "$root/scripts" <<'PYTHON'
import csv, sys
sys.path.insert(0, sys.argv[2])
from fuzz import FAIL_CLASSES
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
  python3 "$root/scripts/fuzz.py" --exe "$exe" --bound "${FUZZ_REGRESSION_BOUND:-20}" --decks "${decks[@]}" \
    --out "$out/regression" -v -q --label fuzz_regression/ 2> "$out/regression.err" | grep -E '^(PASS|FAIL) '
  echo "# ${#decks[@]} regression decks in $(( $(date +%s) - start )) s"
fi
exit 0
