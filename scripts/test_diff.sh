#!/usr/bin/env bash
# Tests of the reference diff (python/visco2d/diff.py, installed as visco2d-diff) and of
# blessing (python/visco2d/bless.py, behind `make bless`), on scratch copies in a temporary folder:
# reference_outputs/ is never written.
#
# usage: bash scripts/test_diff.sh [PATH/TO/visco2d]
# Prints one line per check, `PASS name` or `FAIL name: detail`.
set -uo pipefail
cd "$(dirname "$0")/.."
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"   # the package python/visco2d/ (doc/python.md)
exe=${1:-build/install/bin/visco2d}
diff_tool="python3 -m visco2d.diff"
bless_tool="python3 -m visco2d.bless"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

pass() { echo "PASS $1"; }
fail() { echo "FAIL $1: $2"; }
# check_rc NAME EXPECTED ACTUAL
check_rc() {
  if [ "$3" = "$2" ]; then pass "$1"; else fail "$1" "exit status $3, expected $2"; fi
}
# check_grep NAME PATTERN FILE: PASS if FILE has a line matching PATTERN
check_grep() {
  if grep -qE -- "$2" "$3"; then pass "$1"; else fail "$1" "no line matching '$2' in: $(head -c 600 "$3" | tr '\n' '|')"; fi
}
# first_difference FILE: the first difference line the diff printed (indented by 3 spaces)
first_difference() { grep -m1 '^   ' "$1"; }
# set_key FILE KEY VALUE: set a summary.txt value
set_key() { sed -i "s/^$2 = .*/$2 = $3/" "$1"; }
# scale_h5 FILE DATASET INDEX FACTOR: multiply one element of an HDF5 dataset (INDEX: Python, e.g. 10,1)
scale_h5() {
  python3 -c "import h5py, numpy
with h5py.File('$1', 'r+') as f:
    d = f['$2']; x = numpy.array(d[()]); x[$3] *= $4; d[...] = x"
}
tree_sums() { (cd "$1" && find . -type f | LC_ALL=C sort | xargs sha1sum); }

if [ ! -x "$exe" ]; then
  fail executable "usage: bash scripts/test_diff.sh PATH/TO/visco2d (got '$exe')"
  exit 1
fi
"$exe" -q -o "$tmp/run" inputs/table1_elastic.inp inputs/block_cards.inp inputs/free_flight.inp > "$tmp/run.log" 2>&1 \
  || fail "runs" "the decks did not run: $(cat "$tmp/run.log")"

# --- the diff ------------------------------------------------------------------------------
$diff_tool reference_outputs/table1_elastic "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: the archived reference of table1_elastic matches a fresh run (exit 0)" 0 $?

# one summary key changed by 1e-3 relative: exit 1, that key named first, with both values
cp -r reference_outputs/table1_elastic "$tmp/ref_key"
alpha=$(sed -n 's/^alpha_max_mm = //p' "$tmp/ref_key/summary.txt")
set_key "$tmp/ref_key/summary.txt" alpha_max_mm "$(python3 -c "print(repr($alpha * 1.001))")"
$diff_tool "$tmp/ref_key" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: alpha_max_mm changed by 1e-3 relative fails (exit 1)" 1 $?
check_grep "diff: alpha_max_mm is named first, with both values and its relative error" \
  "^   alpha_max_mm: [-0-9.e]+ vs reference [-0-9.e]+ \(rel 9\.99e-04" <(first_difference "$tmp/out")
check_grep "diff: the FAIL line of the perturbed file counts one difference" \
  "^FAIL ref_key/summary.txt: 1 difference beyond" "$tmp/out"
check_grep "diff: the unperturbed history passes" "^PASS ref_key/history.csv" "$tmp/out"

# round-off in zero-valued stresses (block_cards: a hydrostatic state in r and theta, the issue's
# -8.7e-11 Pa vs -1.2e-10 Pa): passes; a 1 Pa change of the same key fails (the floor is 1e-6 Pa)
cp -r reference_outputs/block_cards "$tmp/ref_roundoff"
set_key "$tmp/ref_roundoff/summary.txt" sigma_r_min_Pa -1.2e-10
set_key "$tmp/ref_roundoff/summary.txt" sigma_theta_min_Pa -1.2e-10
set_key "$tmp/ref_roundoff/summary.txt" tau_rz_max_abs_Pa 1.1e-10
python3 - "$tmp/ref_roundoff/history.csv" <<'EOF'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
columns = [rows[0].index("top_outside_" + name + "_Pa") for name in ("sr", "st", "trz")]
for row in rows[1:]:
    for j in columns:
        row[j] = repr(float(row[j]) * 1.5 + 3e-11)  # values of ~1e-11 Pa: round-off
csv.writer(open(sys.argv[1], "w", newline=""), lineterminator="\n").writerows(rows)
EOF
$diff_tool "$tmp/ref_roundoff" "$tmp/run/block_cards" > "$tmp/out" 2>&1
check_rc "diff: round-off changes of zero-valued stresses (summary and history) pass (exit 0)" 0 $?
set_key "$tmp/ref_roundoff/summary.txt" sigma_r_min_Pa -1.0
$diff_tool "$tmp/ref_roundoff" "$tmp/run/block_cards" > "$tmp/out" 2>&1
check_rc "diff: a 1 Pa change of that zero stress fails (exit 1)" 1 $?
check_grep "diff: ... and names it" "^   sigma_r_min_Pa: " <(first_difference "$tmp/out")

# free_flight's stresses are round-off (~1e-9 Pa, gravity-free flight): they differ by up to 100 %
# between machines (BLAS, compiler); only the unit's floor (1e-6 Pa) makes the reference portable
$diff_tool reference_outputs/free_flight "$tmp/run/free_flight" > "$tmp/out" 2>&1
check_rc "diff: free_flight's round-off stresses of ~1e-9 Pa pass against the archived reference (exit 0)" 0 $?

# HDF5 fields: one stress perturbed by 1e-3 relative fails and is named with its index;
# round-off (1e-10 Pa) added to every stress passes
cp -r "$tmp/run/table1_elastic" "$tmp/run_h5"
last_step=$(python3 -c "import h5py
with h5py.File('$tmp/run_h5/results.h5', 'r') as f: print(sorted(f['fields'])[-1])")   # the final snapshot
scale_h5 "$tmp/run_h5/results.h5" "fields/$last_step/stress" "10, 1" 1.001
$diff_tool "$tmp/run/table1_elastic" "$tmp/run_h5" > "$tmp/out" 2>&1
check_rc "diff: an HDF5 field value changed by 1e-3 relative fails (exit 1)" 1 $?
check_grep "diff: the HDF5 dataset and element are named" \
  "^   /fields/$last_step/stress\[10,1\]: .*\(rel 1\.00e-03" <(first_difference "$tmp/out")
check_grep "diff: summary, history and pressure of the same run pass" "^PASS table1_elastic/pressure.csv" "$tmp/out"
cp -r "$tmp/run/table1_elastic" "$tmp/run_h5_roundoff"
python3 -c "import h5py
with h5py.File('$tmp/run_h5_roundoff/results.h5', 'r+') as f:
    d = f['fields/step_000000/stress']; d[...] = d[()] + 1e-10"
$diff_tool "$tmp/run/table1_elastic" "$tmp/run_h5_roundoff" > "$tmp/out" 2>&1
check_rc "diff: HDF5 stresses changed by 1e-10 Pa pass (exit 0)" 0 $?
cp -r "$tmp/run/table1_elastic" "$tmp/run_h5_summary"
scale_h5 "$tmp/run_h5_summary/results.h5" summary/force_max_N "()" 1.0001
$diff_tool "$tmp/run/table1_elastic" "$tmp/run_h5_summary" > "$tmp/out" 2>&1
check_grep "diff: the HDF5 /summary group is compared" "^   /summary/force_max_N: " <(first_difference "$tmp/out")

# worst first, and how many are shown: every force_N changed by 1e-4, one row by 1e-2
cp -r reference_outputs/table1_elastic "$tmp/ref_many"
python3 - "$tmp/ref_many/history.csv" <<'EOF'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
j, step = rows[0].index("force_N"), rows[0].index("step")
for row in rows[1:]:
    row[j] = repr(float(row[j]) * (1.01 if float(row[step]) == 100 else 1.0001))
csv.writer(open(sys.argv[1], "w", newline=""), lineterminator="\n").writerows(rows)
EOF
$diff_tool "$tmp/ref_many" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: force_N changed in every row fails (exit 1)" 1 $?
check_grep "diff: the worst row (1e-2) comes first, named by line, step, time and column" \
  "^   line 102 step 100 t 0.001 s force_N: " <(first_difference "$tmp/out")
shown=$(grep -c '^   line ' "$tmp/out")
if [ "$shown" -eq 20 ] && grep -qE '^   \.\.\. and [0-9]+ more' "$tmp/out"; then
  pass "diff: the worst 20 are shown, then a count of the others"
else
  fail "diff: the worst 20 are shown, then a count of the others" "$shown shown"
fi
$diff_tool "$tmp/ref_many" "$tmp/run/table1_elastic" --all > "$tmp/out" 2>&1
total=$(sed -n 's/^FAIL ref_many\/history.csv: \([0-9]*\) differences.*/\1/p' "$tmp/out")
shown=$(grep -c '^   line ' "$tmp/out")
if [ -n "$total" ] && [ "$total" -gt 20 ] && [ "$shown" -eq "$total" ]; then
  pass "diff --all lists all $total differences"
else
  fail "diff --all lists all differences" "$shown shown of '$total'"
fi

# tolerances.txt of the reference case
printf '# table1_elastic: alpha_max_mm known to 2e-3 (test)\nalpha_max_mm = 2e-3\n' > "$tmp/ref_key/tolerances.txt"
$diff_tool "$tmp/ref_key" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: tolerances.txt 'alpha_max_mm = 2e-3' accepts the 1e-3 change (exit 0)" 0 $?
printf 'default = 1e-2\n' > "$tmp/ref_key/tolerances.txt"
$diff_tool "$tmp/ref_key" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: tolerances.txt 'default = 1e-2' accepts it too (exit 0)" 0 $?
printf 'alpha_max_mm = 1e-9 1e-12\n' > "$tmp/ref_key/tolerances.txt"
$diff_tool "$tmp/ref_key" "$tmp/run/table1_elastic" --rtol 1e-2 > "$tmp/out" 2>&1
check_rc "diff: a tolerances.txt entry wins over --rtol (exit 1)" 1 $?
printf 'alpha_max_mm = loose\n' > "$tmp/ref_key/tolerances.txt"
$diff_tool "$tmp/ref_key" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: a malformed tolerances.txt is unusable input (exit 2)" 2 $?
check_grep "diff: ... with its file and line" "tolerances.txt:1: expected" "$tmp/out"

# folders of case folders; a case or a file on one side only is a difference
mkdir -p "$tmp/refs" && cp -r reference_outputs/table1_elastic reference_outputs/block_cards reference_outputs/free_flight "$tmp/refs/"
$diff_tool "$tmp/refs" "$tmp/run" > "$tmp/out" 2>&1
check_rc "diff: two folders of case folders that match (exit 0)" 0 $?
check_grep "diff: ... with one line of totals" "^# 3 of 3 cases match" "$tmp/out"
cp -r reference_outputs/sphere_pressure "$tmp/refs/"
$diff_tool "$tmp/refs" "$tmp/run" > "$tmp/out" 2>&1
check_rc "diff: a case in the reference only is a difference (exit 1)" 1 $?
check_grep "diff: ... named" "^FAIL sphere_pressure: in the reference, not in the run" "$tmp/out"
cp -r "$tmp/run/table1_elastic" "$tmp/run_nohistory" && rm "$tmp/run_nohistory/history.csv"
$diff_tool reference_outputs/table1_elastic "$tmp/run_nohistory" > "$tmp/out" 2>&1
check_rc "diff: a file missing from the run is a difference (exit 1)" 1 $?

# unusable input: exit 2
$diff_tool reference_outputs/table1_elastic "$tmp/no_such_folder" > "$tmp/out" 2>&1
check_rc "diff: a missing folder is unusable input (exit 2)" 2 $?
cp -r "$tmp/run/table1_elastic" "$tmp/run_corrupt_csv"
echo "1,2,three" >> "$tmp/run_corrupt_csv/history.csv"
$diff_tool reference_outputs/table1_elastic "$tmp/run_corrupt_csv" > "$tmp/out" 2>&1
check_rc "diff: a corrupt history.csv is unusable input (exit 2)" 2 $?
check_grep "diff: ... named with its line" "history.csv:[0-9]+: expected [0-9]+ numbers" "$tmp/out"
cp -r "$tmp/run/table1_elastic" "$tmp/run_corrupt_h5"
head -c 4096 "$tmp/run/table1_elastic/results.h5" > "$tmp/run_corrupt_h5/results.h5"
$diff_tool "$tmp/run/table1_elastic" "$tmp/run_corrupt_h5" > "$tmp/out" 2>&1
check_rc "diff: a truncated results.h5 is unusable input (exit 2)" 2 $?
$diff_tool reference_outputs/table1_elastic > "$tmp/out" 2>&1
check_rc "diff: a missing argument is a usage error (exit 2)" 2 $?

# --- a reference that has lost or damaged a file: unusable input (exit 2), the file named ----
cp -r reference_outputs/table1_elastic "$tmp/ref_nosummary" && rm "$tmp/ref_nosummary/summary.txt"
$diff_tool "$tmp/ref_nosummary" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: a reference case without its summary.txt is unusable input (exit 2)" 2 $?
check_grep "diff: ... naming the missing file" "ref_nosummary/summary.txt: missing from the reference" "$tmp/out"
mkdir -p "$tmp/refs_lost/table1_elastic" && cp reference_outputs/table1_elastic/history.csv "$tmp/refs_lost/table1_elastic/"
cp -r reference_outputs/block_cards "$tmp/refs_lost/"
mkdir -p "$tmp/run_two" && cp -r "$tmp/run/table1_elastic" "$tmp/run/block_cards" "$tmp/run_two/"
$diff_tool "$tmp/refs_lost" "$tmp/run_two" > "$tmp/out" 2>&1
check_rc "diff: ... also in a folder of cases (exit 2)" 2 $?
mkdir -p "$tmp/refs_empty/table1_elastic"
$diff_tool "$tmp/refs_empty" "$tmp/run_two" > "$tmp/out" 2>&1
check_rc "diff: a reference case folder left empty is unusable input, not an extra run case (exit 2)" 2 $?
cp -r reference_outputs/table1_elastic "$tmp/ref_nohistory" && rm "$tmp/ref_nohistory/history.csv"
$diff_tool "$tmp/ref_nohistory" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: a reference case without its history.csv is unusable input (exit 2)" 2 $?
check_grep "diff: ... naming it" "ref_nohistory/history.csv: missing from the reference" "$tmp/out"
cp -r reference_outputs/table1_elastic "$tmp/ref_truncated"
size=$(stat -c %s reference_outputs/table1_elastic/summary.txt)
head -c $((size * 2 / 3)) reference_outputs/table1_elastic/summary.txt > "$tmp/ref_truncated/summary.txt"
$diff_tool "$tmp/ref_truncated" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: a truncated reference summary.txt (cut mid-line) is unusable input (exit 2)" 2 $?
check_grep "diff: ... named, as truncated" "ref_truncated/summary.txt: truncated" "$tmp/out"
cp -r reference_outputs/table1_elastic "$tmp/ref_truncated_csv"
size=$(stat -c %s reference_outputs/table1_elastic/history.csv)
head -c $((size - 3)) reference_outputs/table1_elastic/history.csv > "$tmp/ref_truncated_csv/history.csv"
$diff_tool "$tmp/ref_truncated_csv" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: a reference history.csv cut inside its last number is unusable input (exit 2)" 2 $?
check_grep "diff: ... named, as truncated" "ref_truncated_csv/history.csv: truncated" "$tmp/out"
cp -r reference_outputs/table1_elastic "$tmp/ref_nan"
set_key "$tmp/ref_nan/summary.txt" alpha_max_mm NaN
$diff_tool "$tmp/ref_nan" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: a NaN in the reference summary.txt is unusable input (exit 2)" 2 $?
check_grep "diff: ... with its file, line and key" "ref_nan/summary.txt:[0-9]+: alpha_max_mm = NaN is not a finite number" "$tmp/out"
cp -r reference_outputs/table1_elastic "$tmp/ref_nan_csv"
sed -i '5s/^\([^,]*\),[^,]*,/\1,inf,/' "$tmp/ref_nan_csv/history.csv"
$diff_tool "$tmp/ref_nan_csv" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: an Inf in the reference history.csv is unusable input (exit 2)" 2 $?
check_grep "diff: ... with its file, line and column" "ref_nan_csv/history.csv:5: t_s = inf is not a finite number" "$tmp/out"
cp -r reference_outputs/table1_elastic "$tmp/ref_garbled" && echo "alpha_max_mm 1.0" >> "$tmp/ref_garbled/summary.txt"
$diff_tool "$tmp/ref_garbled" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_rc "diff: an unparseable line in the reference summary.txt is unusable input (exit 2)" 2 $?
cp -r "$tmp/run/table1_elastic" "$tmp/run_nan" && set_key "$tmp/run_nan/summary.txt" alpha_max_mm NaN
$diff_tool reference_outputs/table1_elastic "$tmp/run_nan" > "$tmp/out" 2>&1
check_rc "diff: a NaN in the run (the output under test) is a difference (exit 1)" 1 $?

# --- paths in messages: the same deck run from two roots (a laptop's relative out/, a cluster's
# absolute /scratch/...) quotes two deck paths in its warning; the case folders must match
mkdir -p "$tmp/local/decks" "$tmp/cluster/scratch/sweep/decks"
cp inputs/apple_center_accel.inp "$tmp/local/decks/" && cp inputs/apple_center_accel.inp "$tmp/cluster/scratch/sweep/decks/"
exe_absolute="$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")"
(cd "$tmp/local" && "$exe_absolute" -q -o out decks/apple_center_accel.inp) > "$tmp/run.log" 2>&1 \
  || fail "runs" "apple_center_accel did not run from $tmp/local: $(cat "$tmp/run.log")"
"$exe" -q -o "$tmp/cluster/scratch/sweep" "$tmp/cluster/scratch/sweep/decks/apple_center_accel.inp" > "$tmp/run.log" 2>&1 \
  || fail "runs" "apple_center_accel did not run from $tmp/cluster: $(cat "$tmp/run.log")"
grep -q "^warning_1 = decks/apple_center_accel.inp:64: PROBE" "$tmp/local/out/apple_center_accel/summary.txt" \
  && grep -q "^warning_1 = $tmp/cluster/scratch/sweep/decks/apple_center_accel.inp:64: PROBE" \
       "$tmp/cluster/scratch/sweep/apple_center_accel/summary.txt" \
  && pass "diff: the two runs' warnings quote two different deck paths" \
  || fail "diff: the two runs' warnings quote two different deck paths" "$(grep warning_1 "$tmp"/*/out/*/summary.txt)"
$diff_tool "$tmp/local/out/apple_center_accel" "$tmp/cluster/scratch/sweep/apple_center_accel" > "$tmp/out" 2>&1
check_rc "diff: the same deck run under two output roots matches, results.h5 included (exit 0)" 0 $?
$diff_tool reference_outputs/apple_center_accel "$tmp/cluster/scratch/sweep/apple_center_accel" > "$tmp/out" 2>&1
check_rc "diff: the archived reference (deck in inputs/) matches the run under /scratch (exit 0)" 0 $?
cp -r reference_outputs/apple_center_accel "$tmp/ref_warning"
sed -i 's/^\(warning_1 = .*\)RADIUS=0.005 m/\1RADIUS=0.006 m/' "$tmp/ref_warning/summary.txt"
$diff_tool "$tmp/ref_warning" "$tmp/local/out/apple_center_accel" > "$tmp/out" 2>&1
check_rc "diff: a warning whose text differs still fails (exit 1)" 1 $?
cp -r reference_outputs/apple_center_accel "$tmp/ref_warning_line"
sed -i 's/^\(warning_1 = .*\.inp\):64:/\1:65:/' "$tmp/ref_warning_line/summary.txt"
$diff_tool "$tmp/ref_warning_line" "$tmp/local/out/apple_center_accel" > "$tmp/out" 2>&1
check_rc "diff: ... and so does one whose deck line differs (exit 1)" 1 $?
cp -r reference_outputs/apple_center_accel "$tmp/ref_warning_deck"
sed -i 's/^\(warning_1 = .*\)apple_center_accel\.inp:64:/\1other_deck.inp:64:/' "$tmp/ref_warning_deck/summary.txt"
$diff_tool "$tmp/ref_warning_deck" "$tmp/local/out/apple_center_accel" > "$tmp/out" 2>&1
check_rc "diff: ... and one quoting another deck's file name (exit 1)" 1 $?

# --- worst first: time-of-event keys apart, in time steps ------------------------------------
# table2_viscoelastic with its moduli (K, G) raised by 0.1 %: the time of peak surface pressure
# jumps 20 steps (between two near-equal maxima); the real changes must come first
mkdir -p "$tmp/modulus"
python3 - inputs/table2_viscoelastic.inp "$tmp/modulus/table2_viscoelastic.inp" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
text, n = re.subn(r'^(MATERIAL .* K=|PRONY G=)([0-9.e+]+)', lambda m: f"{m.group(1)}{float(m.group(2)) * 1.001!r}",
                  text, flags=re.M)
assert n == 2, n
open(sys.argv[2], 'w').write(text)
EOF
"$exe" -q -o "$tmp/modulus/out" "$tmp/modulus/table2_viscoelastic.inp" > "$tmp/run.log" 2>&1 \
  || fail "runs" "the modified table2_viscoelastic did not run: $(cat "$tmp/run.log")"
$diff_tool reference_outputs/table2_viscoelastic "$tmp/modulus/out/table2_viscoelastic" --all > "$tmp/out" 2>&1
check_rc "diff: a 0.1 % modulus change fails (exit 1)" 1 $?
sed -n '/^FAIL table2_viscoelastic\/summary.txt/,/^[A-Z#]/p' "$tmp/out" > "$tmp/summary_part"
if first_difference "$tmp/summary_part" | grep -qE '^   (t_|time_)'; then
  fail "diff: ... a time-of-event key is not the worst summary difference" "$(first_difference "$tmp/summary_part")"
else
  pass "diff: ... a time-of-event key is not the worst summary difference"
fi
check_grep "diff: ... the event times are listed apart, in steps of the summary's DT" \
  "^   time-of-event keys \(in steps of DT = 1e-05 s\): [0-9]+ differ" "$tmp/summary_part"
check_grep "diff: ... t_q_surface_max_ms reads as 20 steps earlier" \
  "^   t_q_surface_max_ms: 1\.36 vs reference 1\.56 ms: 20 steps earlier" "$tmp/summary_part"
rank=$(grep '^   ' "$tmp/summary_part" | grep -n '^   q_max_MPa:' | cut -d: -f1)
event_rank=$(grep '^   ' "$tmp/summary_part" | grep -n '^   time-of-event' | cut -d: -f1)
if [ -n "$rank" ] && [ -n "$event_rank" ] && [ "$rank" -lt "$event_rank" ]; then
  pass "diff: ... q_max_MPa (rank $rank) is listed before every event time"
else
  fail "diff: ... q_max_MPa is listed before every event time" "rank '$rank', events at '$event_rank'"
fi
# a one-step shift against a real 1e-3 change: the change first, the shift read as "one step"
cp -r reference_outputs/table1_elastic "$tmp/ref_step"
alpha=$(sed -n 's/^alpha_max_mm = //p' "$tmp/ref_step/summary.txt")
set_key "$tmp/ref_step/summary.txt" alpha_max_mm "$(python3 -c "print(repr($alpha * 1.001))")"
set_key "$tmp/ref_step/summary.txt" t_force_max_ms 1.430000000E+000   # the run's is 1.44 ms, DT = 0.01 ms
$diff_tool "$tmp/ref_step" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_grep "diff: a 1e-3 change of alpha_max_mm is named before a one-step shift of t_force_max_ms" \
  "^   alpha_max_mm: " <(first_difference "$tmp/out")
check_grep "diff: ... which reads as one step later" \
  "^   t_force_max_ms: 1\.44 vs reference 1\.43 ms: one step later" "$tmp/out"
check_grep "diff: ... and both count as differences" "^FAIL ref_step/summary.txt: 2 differences beyond" "$tmp/out"

# a change at a zero crossing ranks by its size against the quantity's largest value: vz_cm_m_s of
# table1_elastic crosses zero at maximum deformation (0.0136 m/s of an impact at 0.998 m/s); moved by
# 1e-5 m/s it is 7e-4 relative (734x the tolerance) but 1e-5 of the column's largest (10x there),
# so q_max_MPa changed by 1e-4 relative (100x) comes first; in history.csv the same with the row of
# smallest |vz_cm_m_s| moved by 1e-6 m/s against alpha_mm at its largest changed by 1e-4
cp -r reference_outputs/table1_elastic "$tmp/ref_crossing"
vz=$(sed -n 's/^vz_cm_m_s = //p' "$tmp/ref_crossing/summary.txt")
q=$(sed -n 's/^q_max_MPa = //p' "$tmp/ref_crossing/summary.txt")
set_key "$tmp/ref_crossing/summary.txt" vz_cm_m_s "$(python3 -c "print(repr($vz + 1e-5))")"
set_key "$tmp/ref_crossing/summary.txt" q_max_MPa "$(python3 -c "print(repr($q * 1.0001))")"
python3 - "$tmp/ref_crossing/history.csv" <<'EOF'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
v, a = rows[0].index("vz_cm_m_s"), rows[0].index("alpha_mm")
body = rows[1:]
crossing = min((r for r in body if float(r[v]) != 0), key=lambda r: abs(float(r[v])))
crossing[v] = repr(float(crossing[v]) + 1e-6)
peak = max(body, key=lambda r: abs(float(r[a])))
peak[a] = repr(float(peak[a]) * 1.0001)
csv.writer(open(sys.argv[1], "w", newline=""), lineterminator="\n").writerows(rows)
EOF
$diff_tool "$tmp/ref_crossing" "$tmp/run/table1_elastic" > "$tmp/out" 2>&1
check_grep "diff: q_max_MPa changed by 1e-4 ranks before vz_cm_m_s moved by 1e-5 m/s at its zero crossing" \
  "^   q_max_MPa: " <(first_difference "$tmp/out")
check_grep "diff: ... which is shown against the largest |vz_cm_m_s| of the history" \
  "^   vz_cm_m_s: .*; 10(\.[0-9]+)?x at the quantity's largest, 0\.998" "$tmp/out"
sed -n '/^FAIL ref_crossing\/history.csv/,$p' "$tmp/out" > "$tmp/history_part"
check_grep "diff: alpha_mm changed by 1e-4 at its largest ranks before the zero crossing of vz_cm_m_s" \
  "^   line [0-9]+ step [0-9]+ t [0-9.e-]+ s alpha_mm: " <(first_difference "$tmp/history_part")

# --- extra case folders in the run: listed apart, not failures --------------------------------
mkdir -p "$tmp/refs_two" && cp -r reference_outputs/table1_elastic reference_outputs/block_cards "$tmp/refs_two/"
cp -r "$tmp/run/table1_elastic" "$tmp/run_two/table1_elastic_copy"
$diff_tool "$tmp/refs_two" "$tmp/run_two" > "$tmp/out" 2>&1
check_rc "diff: a case folder only the run has is not a failure (exit 0)" 0 $?
check_grep "diff: ... it is listed as extra" "^EXTRA table1_elastic_copy: in the run, not in the reference \(not compared\)" "$tmp/out"
check_grep "diff: ... and counted apart in the totals" "^# 2 of 2 cases match .*; 1 extra case in the run, not compared" "$tmp/out"
rm -r "$tmp/refs_two/block_cards"
$diff_tool "$tmp/refs_two" "$tmp/run_two" > "$tmp/out" 2>&1
check_rc "diff: ... two extras, everything else matching (exit 0)" 0 $?
cp -r reference_outputs/sphere_pressure "$tmp/refs_two/"
$diff_tool "$tmp/refs_two" "$tmp/run_two" > "$tmp/out" 2>&1
check_rc "diff: ... while a case only the reference has still fails (exit 1)" 1 $?
installed="$(dirname "$exe")/visco2d-diff"
if [ -x "$installed" ] && "$installed" reference_outputs/table1_elastic "$tmp/run" > "$tmp/out" 2>&1; then
  pass "visco2d-diff is installed beside visco2d and runs"
else
  fail "visco2d-diff is installed beside visco2d and runs" "$installed: $(head -c 300 "$tmp/out" 2>/dev/null)"
fi

# --- blessing, on a scratch copy of inputs/ and reference_outputs/ ---------------------------
repo="$tmp/repo"
mkdir -p "$repo" && cp -r inputs reference_outputs "$repo/"
exe_path="$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")"
bless() { (cd "$repo" && $bless_tool --exe "$exe_path" --work "$tmp/bless-work" "$@"); }
# the issue's case: a reference blessed on a machine whose round-off gave another hydrostatic zero
set_key "$repo/reference_outputs/block_cards/summary.txt" sigma_r_min_Pa -8.7e-11
tree_sums "$repo/reference_outputs" > "$tmp/sums_before"
bless --all > "$tmp/out" 2>&1
check_rc "bless --all on an unchanged tree runs (exit 0)" 0 $?
tree_sums "$repo/reference_outputs" > "$tmp/sums_after"
if cmp -s "$tmp/sums_before" "$tmp/sums_after" && grep -q '^bless: 0 files of 0 cases rewritten' "$tmp/out"; then
  pass "bless --all on an unchanged tree (round-off zeros included) rewrites nothing"
else
  fail "bless --all on an unchanged tree rewrites nothing" "$(cat "$tmp/out")"
fi

cp "$repo/inputs/sphere_pressure.inp" "$repo/inputs/new_deck.inp"
bless inputs/new_deck.inp > "$tmp/out" 2>&1
check_rc "bless one new deck (exit 0)" 0 $?
tree_sums "$repo/reference_outputs" | grep -v '\./new_deck/' > "$tmp/sums_after"
if cmp -s "$tmp/sums_before" "$tmp/sums_after"; then
  pass "blessing one new deck leaves every other reference file byte-identical"
else
  fail "blessing one new deck leaves every other reference file byte-identical" "$(diff "$tmp/sums_before" "$tmp/sums_after" | head -5)"
fi
if [ -f "$repo/reference_outputs/new_deck/summary.txt" ] && [ -f "$repo/reference_outputs/new_deck/history.csv" ] \
   && ! grep -q '^cpu_s = ' "$repo/reference_outputs/new_deck/summary.txt" \
   && python3 -m visco2d.diff "$repo/reference_outputs/new_deck" "$tmp/bless-work/new_deck" > /dev/null; then
  pass "the new deck's reference: summary.txt without cpu_s and history.csv, matching its run"
else
  fail "the new deck's reference" "$(ls "$repo/reference_outputs/new_deck" 2>&1)"
fi

tree_sums "$repo/reference_outputs" > "$tmp/sums_before"
alpha=$(sed -n 's/^alpha_max_mm = //p' "$repo/reference_outputs/table1_elastic/summary.txt")
set_key "$repo/reference_outputs/table1_elastic/summary.txt" alpha_max_mm "$(python3 -c "print(repr($alpha * 1.001))")"
bless --all > "$tmp/out" 2>&1
check_rc "bless --all with one reference off by 1e-3 (exit 0)" 0 $?
check_grep "bless --all says which file changed and why" "^blessed table1_elastic/summary.txt: alpha_max_mm: " "$tmp/out"
tree_sums "$repo/reference_outputs" | grep -v '\./table1_elastic/summary.txt' > "$tmp/sums_after"
grep -v '\./table1_elastic/summary.txt' "$tmp/sums_before" > "$tmp/sums_others"
if cmp -s "$tmp/sums_others" "$tmp/sums_after" && grep -q '^bless: 1 file of 1 case rewritten (table1_elastic)' "$tmp/out" \
   && python3 -m visco2d.diff "$repo/reference_outputs/table1_elastic" "$tmp/bless-work/table1_elastic" > /dev/null; then
  pass "bless --all rewrote only that file, back to the code's value"
else
  fail "bless --all rewrote only that file" "$(diff "$tmp/sums_others" "$tmp/sums_after" | head -3; tail -1 "$tmp/out")"
fi

tree_sums "$repo/reference_outputs" > "$tmp/sums_before"
bless inputs/table1_elastic.inp > "$tmp/out" 2>&1
tree_sums "$repo/reference_outputs" > "$tmp/sums_after"
if cmp -s "$tmp/sums_before" "$tmp/sums_after" && grep -q '^bless: 0 files' "$tmp/out"; then
  pass "bless DECK within tolerance rewrites nothing"
else
  fail "bless DECK within tolerance rewrites nothing" "$(tail -1 "$tmp/out")"
fi
bless --force inputs/table1_elastic.inp > "$tmp/out" 2>&1
check_grep "bless --force DECK rewrites it" "^bless: 2 files of 1 case rewritten \(table1_elastic\)" "$tmp/out"

tree_sums "$repo/reference_outputs" > "$tmp/sums_before"
printf 'TITLE a deck that does not run\nNO SUCH CARD\n' > "$repo/inputs/broken.inp"
bless --all > "$tmp/out" 2>&1
check_rc "bless refuses a deck that fails to run (exit 1)" 1 $?
tree_sums "$repo/reference_outputs" > "$tmp/sums_after"
if cmp -s "$tmp/sums_before" "$tmp/sums_after" && grep -q 'refused: inputs/broken.inp failed to run' "$tmp/out"; then
  pass "... names it and writes nothing"
else
  fail "... names it and writes nothing" "$(tail -2 "$tmp/out")"
fi

# A deck that runs but misses one of its own EXPECT cards: its reference would archive a failed check.
rm -f "$repo/inputs/broken.inp"
sed -e 's/^EXPECT probe_pole_uz_m .*/EXPECT probe_pole_uz_m 2.0e-3 RTOL=1e-6/' "$repo/inputs/sphere_pressure.inp" \
  > "$repo/inputs/missed_expect.inp"
bless inputs/missed_expect.inp > "$tmp/out" 2>&1
check_rc "bless refuses a deck outside its EXPECT RTOL (exit 1)" 1 $?
tree_sums "$repo/reference_outputs" > "$tmp/sums_after"
if cmp -s "$tmp/sums_before" "$tmp/sums_after" \
   && grep -q 'refused: an EXPECT card is outside its RTOL in missed_expect (probe_pole_uz_m)' "$tmp/out"; then
  pass "... names the deck and the key and writes nothing"
else
  fail "... names the deck and the key and writes nothing" "$(tail -2 "$tmp/out")"
fi
