#!/usr/bin/env bash
# The checked build (`make checked`, a stage of `make test`):
#
#   bash scripts/test_checked.sh [N]      (N mutated decks too, default 0)
#
# Builds visco2d with run-time checks and the address and undefined-behaviour
# sanitizers into its own fpm build folder, installed as build/checked/bin/visco2d
# (the release build, build/install/, is not touched):
#   fpm install --profile debug --flag "$CHECKED_FLAGS" --link-flag "-fsanitize=address,undefined"
# and runs under it every deck in inputs/ (each must exit 0) and every regression
# deck in test/fuzz/ (exit 0, 1 or 2, or what its '# fuzz: exit' line says), then N
# mutated decks of python/visco2d/fuzz.py (seed 7). Clean means: the expected exit status,
# and no runtime-error, sanitizer or leak report in stderr (python/visco2d/fuzz.py's CRASH
# class), no non-finite output, no partial folder, a located error on exit 1.
# Any sanitizer report is an error: halt_on_error=1 and exitcode 86 (ASan, LSan) /
# 87 (UBSan); an allocation above 4 GB is one too (max_allocation_size_mb=4096, as the
# release runs of python/visco2d/fuzz.py get a 4 GB address-space limit); leaks are checked
# at exit (detect_leaks=1), with no suppressions.
# -fcheck=all minus array-temps (a performance note, not a defect; the debug
# profile's own -fcheck=array-temps comes after our flags, so its run-time
# warnings may appear in stderr: they are not counted).
# Prints one line per deck, `PASS checked_...` or `FAIL checked_...: reason`.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export PYTHONPATH="$root/python${PYTHONPATH:+:$PYTHONPATH}"   # the package python/visco2d/ (doc/python.md)
cd "$root" || exit 1
count=${1:-0}
flags=${CHECKED_FLAGS:-"-fcheck=all,no-array-temps -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g -O1"}
prefix=build/checked
log=build/checked-logs
rm -rf "$log" && mkdir -p "$log"

start=$(date +%s)
if fpm install --profile debug --flag "$flags" --link-flag "-fsanitize=address,undefined" --prefix "$prefix" \
     > "$log/build.log" 2>&1; then
  echo "PASS checked_build ($(( $(date +%s) - start )) s)"
else
  echo "FAIL checked_build: fpm install --profile debug --flag \"$flags\" failed; see $log/build.log: $(tail -3 "$log/build.log" | tr '\n' '|')"
  exit 0
fi
exe=$prefix/bin/visco2d

export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:exitcode=86:max_allocation_size_mb=4096}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1:exitcode=87}
bound=${CHECKED_BOUND:-150}   # a hang bound, in wall seconds: the slowest deck takes ~21 s of CPU under the sanitizers, 50-70 s wall on a loaded machine

python3 -m visco2d.fuzz --exe "$exe" --bound "$bound" --decks inputs/*.inp --expect-exit 0 \
  --out "$log/inputs" -v -q --label checked_inputs/ | grep -E '^(PASS|FAIL) '
regression=(test/fuzz/*.inp)
if [ -e "${regression[0]}" ]; then
  python3 -m visco2d.fuzz --exe "$exe" --bound "$bound" --decks "${regression[@]}" \
    --out "$log/regression" -v -q --label checked_test/fuzz/ | grep -E '^(PASS|FAIL) '
fi
if [ "$count" -gt 0 ]; then
  python3 -m visco2d.fuzz --exe "$exe" --bound "${CHECKED_FUZZ_BOUND:-30}" -n "$count" --seed 7 \
    --out "$log/fuzz" -q > "$log/fuzz.log" 2>&1
  python3 - "$log/fuzz" <<'PYTHON'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + '/cases.csv')))
bad = [r for r in rows if r['classes']]
if bad:
    for r in bad[:20]:
        print('FAIL checked_fuzz_%s: %s (%s)' % (r['id'], r['classes'], r['signature'][:200]))
    if len(bad) > 20:
        print('FAIL checked_fuzz: %d more failing decks; see %s' % (len(bad) - 20, sys.argv[1]))
else:
    print('PASS checked_fuzz (%d mutated decks)' % len(rows))
PYTHON
fi
echo "# checked build: $(( $(date +%s) - start )) s; logs in $log/"
