#!/usr/bin/env bash
# Tests of visco2d-batch (python/visco2d/batch.py): sweeps, local cores, shards,
# collect, failed cases, duplicate names, the threshold search, the MPI farm.
#
#   bash scripts/test_batch.sh PATH/TO/visco2d
#
# Prints `PASS name` or `FAIL name: detail` per check (`# ` lines are notes,
# `NOTE` lines say what was skipped) and always exits 0: the caller counts.
# The deck: inputs/peach_drop.inp at mesh level 1 (88 elements, ~15 ms a run)
# with ${height}, ${radius} (and ${nu}) placeholders; everything happens in a
# temporary folder, removed at the end.

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

pass() { echo "PASS $1"; }
fail() { echo "FAIL $1: $2"; }
check() {  # check NAME DETAIL COMMAND...
  local name=$1 detail=$2
  shift 2
  if "$@"; then pass "$name"; else fail "$name" "$detail"; fi
}
check_rc() { if [ "$3" = "$2" ]; then pass "$1"; else fail "$1" "exit status $3, expected $2"; fi; }
# check_ok NAME STATUS LOG: exit status 0, else the log's last lines as the detail
check_ok() { if [ "$2" = 0 ]; then pass "$1"; else fail "$1" "exit status $2: $(tail -3 "$3" | tr '\n' '|')"; fi; }
# same_summary A B: two summary.txt equal line for line but for cpu_s and the deck's path
# that starts each warning (warning_N = PATH:LINE: ...: a case's deck lies in its own folder)
summary_lines() { grep -v '^cpu_s = ' "$1" | sed -E 's#^(warning_[0-9]+ = )[^:]*:#\1DECK:#'; }
same_summary() { diff <(summary_lines "$1") <(summary_lines "$2") > /dev/null 2>&1; }
# same_cases ROOT1 ROOT2 CASE...: every case's summary equal in both roots
same_cases() {
  local one=$1 two=$2 name
  shift 2
  for name in "$@"; do
    [ -f "$one/$name/summary.txt" ] && [ -f "$two/$name/summary.txt" ] || return 1
    same_summary "$one/$name/summary.txt" "$two/$name/summary.txt" || return 1
  done
}

if [ $# -ne 1 ] || [ ! -x "$1" ] || [ -d "$1" ]; then
  fail executable "usage: bash scripts/test_batch.sh PATH/TO/visco2d (got '${1:-}')"
  exit 0
fi
exe="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
batch() { "$tool" "$@" --exe "$exe"; }

work=$(mktemp -d "${TMPDIR:-/tmp}/visco2d_batch.XXXXXX") || { fail mktemp "cannot create a temporary folder"; exit 0; }
trap 'rm -rf "$work"' EXIT
cd "$work" || { fail cd "cannot enter $work"; exit 0; }
source "$root/scripts/batch_tool.sh"
tool=$(batch_tool "$exe" "$work")

check launcher_checkout "$tool does not import the package of this checkout ($root/python)" \
  grep -qF "$root/python" "$tool"

# The template: the peach of inputs/peach_drop.inp on the coarse mesh.
sed -e 's/^TITLE .*/TITLE Peach, R ${radius} m, dropped ${height} m (level 1)/' \
    -e 's/^MESH SPHERE R=0.03 LEVEL=3/MESH SPHERE R=${radius} LEVEL=1/' \
    -e 's/^DROP HEIGHT=0.2/DROP HEIGHT=${height}/' "$root/inputs/peach_drop.inp" > peach.inp
check template_made "the sed of inputs/peach_drop.inp found no MESH/DROP line to parameterize" \
  test "$(grep -o '\${[a-z]*}' peach.inp | wc -l)" = 4

heights="0.05 0.1 0.2"
radii="0.03 0.04"
cases=()
for h in $heights; do for r in $radii; do cases+=("peach__height=${h}__radius=${r}"); done; done

# 1. A 3 x 2 sweep (one process) against six decks written by hand (sed) under the same names.
batch run peach.inp --param height=0.05,0.1,0.2 --param radius=0.03:0.04:2 -j 1 -o serial > serial.log 2>&1
check_ok sweep_runs $? serial.log
count=$(ls -d serial/peach__* 2>/dev/null | wc -l)
check sweep_six_cases "expected 6 case folders, found $count" test "$count" = 6
mkdir hand
for h in $heights; do for r in $radii; do
  sed -e "s/\${height}/$h/g" -e "s/\${radius}/$r/g" peach.inp > "hand/peach__height=${h}__radius=${r}.inp"
done; done
"$exe" -q -o hand_out hand/*.inp > hand.log 2>&1
check sweep_equals_hand_written "a summary of serial/ differs from the hand-written deck's (cpu_s aside)" \
  same_cases serial hand_out "${cases[@]}"
check deck_beside_results "serial/<case>/<case>.inp is not the expanded deck" \
  bash -c 'for c in "$@"; do cmp -s "serial/$c/$c.inp" "hand/$c.inp" || exit 1; done' _ "${cases[@]}"
one=${cases[3]}
"$exe" -q -o rerun "serial/$one/$one.inp" > /dev/null 2>&1
check case_reruns_alone "visco2d -o rerun serial/$one/$one.inp: not the same summary, or another case name" \
  same_summary "serial/$one/summary.txt" "rerun/$one/summary.txt"
rows=$(tail -n +2 serial/table.csv 2>/dev/null | grep -c ',ok,')
check table_rows "serial/table.csv: expected 6 ok rows, found $rows" test "$rows" = 6
alpha=$(grep '^alpha_max_mm = ' "serial/$one/summary.txt" | cut -d' ' -f3)
check table_values "serial/table.csv: the row of $one lacks its parameters and alpha_max_mm = $alpha" \
  grep -q "^$one,ok,0.1,0.04,$alpha," serial/table.csv
check table_markdown "serial/table.md: no row for $one" grep -q "^| $one | ok | 0.1 | 0.04 |" serial/table.md

# 2. Two local processes: the same summaries.
batch run peach.inp --param height=0.05,0.1,0.2 --param radius=0.03:0.04:2 -j 2 -o parallel > parallel.log 2>&1
check_ok two_processes_run $? parallel.log
check two_processes_identical "-j 2 summaries differ from -j 1" same_cases serial parallel "${cases[@]}"
check two_processes_same_table "-j 2 table.csv differs from -j 1 beyond the cpu_s-free keys" \
  cmp -s serial/table.csv parallel/table.csv

# 3. Zipped axes, a CSV table and a TOML sweep give the same cases.
batch run peach.inp --param height=0.05,0.1 --param radius=0.03,0.04 --zip -q -o zipped > zipped.log 2>&1
count=$(ls -d zipped/peach__* 2>/dev/null | wc -l)
check zip_two_cases "expected 2 cases, found $count" test "$count" = 2
printf 'height,radius\n0.1,0.04\n0.2,0.03\n' > rows.csv
batch run peach.inp --table rows.csv -q -o tabled > tabled.log 2>&1
check csv_table_cases "--table rows.csv: not the sweep's summaries" \
  same_cases serial tabled "peach__height=0.1__radius=0.04" "peach__height=0.2__radius=0.03"
printf 'keys = ["alpha_max_mm"]\n[param]\nheight = [0.1]\nradius = "0.03:0.04:2"\n' > sweep.toml
batch run peach.inp --sweep sweep.toml -q -o tomled > tomled.log 2>&1
check toml_sweep_cases "--sweep sweep.toml: not the sweep's summaries" \
  same_cases serial tomled "peach__height=0.1__radius=0.03" "peach__height=0.1__radius=0.04"
check toml_keys "tomled/table.csv: header is not case,status,height,radius,alpha_max_mm,error" \
  test "$(head -1 tomled/table.csv | tr -d '\r')" = "case,status,height,radius,alpha_max_mm,error"

# 4. Shards and collect: two shards into one root, then the table of what is there.
batch expand peach.inp --param height=0.05,0.1,0.2 --param radius=0.03:0.04:2 -o sharded > /dev/null 2>&1
for k in 0 1; do
  batch run peach.inp --param height=0.05,0.1,0.2 --param radius=0.03:0.04:2 --shard $k/2 -j 1 -q \
    -o sharded > "shard$k.log" 2>&1
  [ $k = 0 ] && first_shard=$(ls -d sharded/peach__* 2>/dev/null | xargs -n 1 basename | tr '\n' ' ')
done
check shards_interleaved "shard 0/2 ran '$first_shard', not cases 1, 3, 5 of 6" \
  test "$first_shard" = "${cases[0]} ${cases[2]} ${cases[4]} "
check shards_identical "two shards: summaries differ from the serial run" same_cases serial sharded "${cases[@]}"
"$tool" collect sharded > collect.log 2>&1
check_ok collect_all_ok $? collect.log
check collect_same_table "collect sharded: table.csv differs from the serial run's" cmp -s serial/table.csv sharded/table.csv
rm -rf "sharded/${cases[5]}"
"$tool" collect sharded > collect.log 2>&1
check_rc collect_missing_status 1 $?
check collect_marks_missing "collect: ${cases[5]} not marked missing" grep -q "^${cases[5]},missing," sharded/table.csv
check shard_usage "--shard 2/2 accepted" bash -c '! "$0" run peach.inp --param height=0.1 --param radius=0.03 --shard 2/2 -o x 2>/dev/null' "$tool"

# 5. A failing case is marked with its located error; the others run.
sed 's/NU=0.35/NU=${nu}/' peach.inp > peach_nu.inp
batch run peach_nu.inp --param height=0.1 --param radius=0.03 --param nu=0.3,0.7,0.35 -j 2 -o failing > failing.log 2>&1
check_rc failing_status 1 $?
check failing_marked "failing/table.csv: the nu=0.7 case is not failed with MATERIAL's located error" \
  grep -q '^peach_nu__height=0.1__radius=0.03__nu=0.7,failed,.*decks/peach_nu__height=0.1__radius=0.03__nu=0.7.inp:12:[0-9]*: MATERIAL: NU must be' failing/table.csv
check failing_others_run "the nu=0.3 and nu=0.35 cases did not run" \
  test -f "failing/peach_nu__height=0.1__radius=0.03__nu=0.3/summary.txt" -a \
       -f "failing/peach_nu__height=0.1__radius=0.03__nu=0.35/summary.txt"
check failing_no_folder "the failed case left a folder" test ! -e "failing/peach_nu__height=0.1__radius=0.03__nu=0.7"

# 6. Usage errors: exit 2 before anything runs.
mkdir -p a b && cp peach.inp a/p.inp && cp peach.inp b/p.inp
sed -e 's/${height}/0.1/g' -e 's/${radius}/0.03/g' peach.inp > a/p.inp && cp a/p.inp b/p.inp
batch run a/p.inp b/p.inp -o duplicate > duplicate.log 2>&1
check_rc duplicate_names_status 2 $?
check duplicate_names_message "no message naming the case p and both decks: $(head -c 300 duplicate.log)" \
  grep -q 'case name "p" (a/p.inp and b/p.inp)' duplicate.log
check duplicate_names_nothing_run "duplicate/ was created" test ! -e duplicate
batch run peach.inp --param height=0.1 -o missing > missing.log 2>&1
check_rc missing_parameter_status 2 $?
check missing_parameter_line "no peach.inp:LINE:COLUMN: \${radius}: $(head -c 300 missing.log)" \
  grep -q 'error: peach.inp:[0-9]*:[0-9]*: ${radius}: no value for parameter "radius"' missing.log
batch run peach.inp --param height=0.1 --param radius=0.03 --param mass=2 -o unused > unused.log 2>&1
check_rc unused_parameter_status 2 $?
check unused_parameter_message "$(head -c 300 unused.log)" grep -q 'parameter "mass" is given but the template has no' unused.log
check usage_nothing_run "missing/ or unused/ was created" test ! -e missing -a ! -e unused

# 7. The threshold search against a fine sweep of the same template (radius 30 mm).
sed 's/${radius}/0.03/g' peach.inp > drop.inp
batch threshold drop.inp --param height=0.01:0.5 --when 'bruise_volume_cm3>0' --tol 0.005 -q -o search > search.log 2>&1
check_ok threshold_runs $? search.log
batch threshold drop.inp --param height=0.01:0.5 --when 'bruise_volume_cm3>0' --tol 0.005 -j 2 -q -o search2 > search2.log 2>&1
batch run drop.inp --param height=0.07:0.1:25 -q -o fine --keys bruise_volume_cm3 > fine.log 2>&1   # the onset: 0.083 m
python3 - search.log search2.log fine/table.csv > verdict.log 2>&1 <<'EOF'
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[3])))
points = sorted((float(r['height']), float(r['bruise_volume_cm3']) > 0) for r in rows)
states = [s for _, s in points]
switch = states.index(True)
assert not states[0] and all(states[switch:]), f'the fine sweep is not a single onset: {points}'
below, above = points[switch - 1][0], points[switch][0]
for log in sys.argv[1:3]:
    text = open(log).read()
    critical = float(re.search(r'height_critical = (\S+)', text).group(1))
    low, high = map(float, re.search(r'bracket = \[(\S+), (\S+)\]', text).group(1, 2))
    runs = int(re.search(r'runs = (\d+)', text).group(1))
    assert high - low <= 0.005 + 1e-12, f'{log}: bracket [{low}, {high}] wider than the tolerance'
    assert max(low, below) <= min(high, above), \
        f'{log}: bracket [{low}, {high}] misses the fine sweep onset in [{below}, {above}]'
    assert abs(critical - (below + above) / 2) <= 0.005, f'{log}: {critical} vs fine {below}..{above}'
    print(f'# {log}: height_critical = {critical} in [{low}, {high}] after {runs} runs; '
          f'fine sweep (25 runs, 1.25 mm apart): onset in [{below}, {above}]')
EOF
check threshold_agrees_with_fine_sweep "$(tr '\n' ' ' < verdict.log | head -c 600)" \
  bash -c '! grep -q Error verdict.log && grep -q "^# " verdict.log'
grep '^# ' verdict.log
runs=$(ls -d search/drop__height=* 2>/dev/null | wc -l)
check threshold_case_folders "search/: $runs case folders, threshold.txt says otherwise" \
  grep -q "^runs = $runs\$" search/threshold.txt
batch threshold drop.inp --param height=0.01:0.05 --when 'bruise_volume_cm3>0' --tol 0.005 -q -o nobracket > nobracket.log 2>&1
check_rc threshold_no_onset_status 1 $?
check threshold_no_onset_message "$(head -c 300 nobracket.log)" grep -q 'no onset in the bracket' nobracket.log

# 8. The MPI task farm on 2 ranks, when it is built.
farm="${VISCO2D_FARM:-$root/build/mpi/bin/visco2d-farm}"   # VISCO2D_FARM: another build of it
if [ -x "$farm" ] && command -v mpirun > /dev/null; then
  batch run peach.inp --param height=0.05,0.1,0.2 --param radius=0.03:0.04:2 --mpi 2 --farm "$farm" -q \
    -o mpi > mpi.log 2>&1
  check_ok mpi_runs $? mpi.log
  check mpi_identical "--mpi 2 summaries differ from -j 1" same_cases serial mpi "${cases[@]}"
  check mpi_same_table "--mpi 2 table.csv differs from -j 1" cmp -s serial/table.csv mpi/table.csv
else
  echo "NOTE --mpi 2 not tested: no $farm or no mpirun (make mpi builds it; its own test is in make test)"
fi
# The batch side of --mpi (the mpirun call, the failed case, the table) with a stand-in farm:
# rank 0 runs the decks through visco2d, the other ranks exit.
if command -v mpirun > /dev/null; then
  printf '#!/bin/bash\n[ "${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-0}}" = 0 ] || exit 0\nexec "%s" "$@"\n' "$exe" > stand_in_farm
  chmod +x stand_in_farm
  batch run peach_nu.inp --param height=0.1 --param radius=0.03 --param nu=0.3,0.7,0.35 --mpi 2 \
    --farm ./stand_in_farm -q -o stand_in > stand_in.log 2>&1
  check_rc mpi_stand_in_status 1 $?
  check mpi_stand_in_table "stand_in/table.csv differs from failing/table.csv (-j 2)" \
    cmp -s <(sed 's#stand_in/decks#failing/decks#' stand_in/table.csv) failing/table.csv
fi
"$tool" run peach.inp --param height=0.1 --param radius=0.03 --mpi 2 --farm "$work/none" \
  -o nofarm > nofarm.log 2>&1
check_rc mpi_no_farm_status 2 $?
check mpi_no_farm_message "$(head -c 300 nofarm.log)" grep -q 'none: not an executable' nofarm.log

# 9. The Slurm array script: its syntax, and its commands run by a stand-in sbatch that runs an
#    array's tasks one after the other (SLURM_ARRAY_TASK_ID = 0, 1, ...) and then the collect job.
check slurm_script_syntax "bash -n scripts/slurm_sweep.sh fails" bash -n "$root/scripts/slurm_sweep.sh"
if [ -x "$root/build/install/bin/visco2d-batch" ] && [ "$(dirname "$exe")" = "$root/build/install/bin" ]; then
  mkdir -p fakebin
  cat > fakebin/sbatch <<'SBATCH'
#!/bin/bash
array='' wrap=''
for arg in "$@"; do
  case $arg in --array=*) array=${arg#--array=};; --wrap=*) wrap=${arg#--wrap=};; esac
done
if [ -n "$array" ]; then
  for ((k = ${array%-*}; k <= ${array#*-}; k++)); do SLURM_ARRAY_TASK_ID=$k bash -c "$wrap" || true; done
else
  bash -c "$wrap" || true
fi
echo 4242
SBATCH
  chmod +x fakebin/sbatch
  PATH="$work/fakebin:$PATH" bash "$root/scripts/slurm_sweep.sh" 4 slurm peach.inp --param height=0.05,0.1,0.2 \
    --param radius=0.03:0.04:2 > slurm.log 2>&1
  check_ok slurm_stand_in $? slurm.log
  check slurm_stand_in_table "slurm/table.csv (4 shards, collected) differs from the serial run's" \
    cmp -s serial/table.csv slurm/table.csv
else
  echo "NOTE scripts/slurm_sweep.sh run not tested: it calls build/install/bin/visco2d-batch, not installed beside $exe"
fi

# 10. The example template of the README (the Table 3 apple) expands into a deck visco2d accepts.
batch expand "$root/inputs/examples/apple_drop.inp" --param height=0.5 -o example > example.log 2>&1
check_ok example_template_expands $? example.log
"$exe" check example/decks/apple_drop__height=0.5.inp > example_check.log 2>&1
check_ok example_deck_checks $? example_check.log
batch expand "$root/inputs/examples/apple_drop_on_pad.inp" --param height=0.2 --param pad_t=0.01 --param pad_e=2e6 \
  -o example_pad > example_pad.log 2>&1
check_ok example_pad_template_expands $? example_pad.log
"$exe" check "example_pad/decks/apple_drop_on_pad__height=0.2__pad_t=0.01__pad_e=2e6.inp" > example_pad_check.log 2>&1
check_ok example_pad_deck_checks $? example_pad_check.log

# 11. A case that misses its own EXPECT card (visco2d exit 3) runs and writes its results, and the
#     batch fails (exit 1) with the case `missed` in the table, its keys in the error cell.
sed -e 's/^EXPECT probe_pole_uz_m .*/EXPECT probe_pole_uz_m ${uz} RTOL=1e-6/' "$root/inputs/sphere_pressure.inp" \
  > pressure.inp
batch run pressure.inp --param uz=2.271585e-3,2.0e-3 -j 1 -o expects > expects.log 2>&1
check_rc expect_miss_fails_the_batch 1 $?
check expect_miss_row "expects/table.csv: no row 'pressure__uz=2.0e-3,missed,...probe_pole_uz_m'" \
  grep -q '^pressure__uz=2.0e-3,missed,.*outside the RTOL of its EXPECT card(s): probe_pole_uz_m' expects/table.csv
check expect_met_row "expects/table.csv: no row 'pressure__uz=2.271585e-3,ok'" \
  grep -q '^pressure__uz=2.271585e-3,ok,' expects/table.csv
check expect_miss_results_written "expects/pressure__uz=2.0e-3/summary.txt is missing" \
  test -f "expects/pressure__uz=2.0e-3/summary.txt"
check expect_miss_reported "expects.log: no 'MISSED pressure__uz=2.0e-3: ...: EXPECT: probe_pole_uz_m' line" \
  grep -q '^MISSED pressure__uz=2.0e-3: .*:23:[0-9]*: EXPECT: probe_pole_uz_m = ' expects.log

# 12. The decks of a sweep fed to one visco2d process a worker (python/visco2d/workers.py, visco2d
#     --decks-from -): a stand-in visco2d logs each process and each deck it is fed and passes them to
#     the real one; a 16-case sweep on -j 2 whose 6th case fails and whose 11th misses its EXPECT card
#     takes one process a worker, every deck fed once, every case keeps its own result, error or miss
#     and its result line, and the table is that of one process a case.
cat > logging_visco2d <<STANDIN
#!/bin/bash
echo "process \$*" >> "$work/processes.log"
while IFS= read -r deck; do echo "deck \$deck" >> "$work/processes.log"; echo "\$deck"; done | exec "$exe" "\$@"
STANDIN
chmod +x logging_visco2d
sed -e 's/NU=0.35/NU=${nu}/' -e 's/^END$/EXPECT alpha_max_mm ${alpha} RTOL=1e-3\nEND/' peach.inp > peach_mixed.inp
: > mixed_rows.csv
echo 'case,height,radius,nu,alpha' > mixed_rows.csv
for k in $(seq 1 16); do
  nu=0.35; alpha=$(grep '^alpha_max_mm = ' "serial/peach__height=0.1__radius=0.03/summary.txt" | cut -d' ' -f3)
  [ "$k" = 6 ] && nu=0.7
  [ "$k" = 11 ] && alpha=9.9
  echo "mixed_$k,0.1,0.03,$nu,$alpha" >> mixed_rows.csv
done
python3 "$tool" run peach_mixed.inp --table mixed_rows.csv -j 2 --exe "$work/logging_visco2d" -o mixed > mixed.log 2>&1
check_rc batched_status_1 1 $?
processes=$(grep -c '^process ' processes.log)
check batched_one_process_a_worker "$processes processes for 16 cases on -j 2: $(tr '\n' '|' < processes.log | head -c 300)" \
  test "$processes" -le 2 -a "$(grep -c '^process -o mixed/* --decks-from -$' processes.log)" = "$processes"
check batched_every_deck_fed_once "processes.log: $(grep -c '^deck ' processes.log) decks fed, $(grep '^deck ' processes.log | sort -u | wc -l) distinct, expected 16" \
  test "$(grep -c '^deck ' processes.log)" = 16 -a "$(grep '^deck ' processes.log | sort -u | wc -l)" = 16
check batched_failed_case "mixed/table.csv: mixed_6 is not failed with MATERIAL's located error: $(grep '^mixed_6,' mixed/table.csv)" \
  grep -q '^mixed_6,failed,.*decks/mixed_6.inp:12:[0-9]*: MATERIAL: NU must be' mixed/table.csv
check batched_missed_case "mixed/table.csv: mixed_11 is not missed: $(grep '^mixed_11,' mixed/table.csv)" \
  grep -q '^mixed_11,missed,.*outside the RTOL of its EXPECT card(s): alpha_max_mm' mixed/table.csv
check batched_missed_line "mixed.log: no 'MISSED mixed_11: ...: EXPECT: alpha_max_mm' line" \
  grep -q '^MISSED mixed_11: .*decks/mixed_11.inp:[0-9]*:[0-9]*: EXPECT: alpha_max_mm = ' mixed.log
check batched_failed_line "mixed.log: no 'FAILED mixed_6: ...: MATERIAL: ...' line" \
  grep -q '^FAILED mixed_6: .*decks/mixed_6.inp:12:[0-9]*: MATERIAL: NU must be' mixed.log
check batched_others_ok "mixed/table.csv: $(grep -c ',ok,' mixed/table.csv) ok rows, expected 14" \
  test "$(grep -c ',ok,' mixed/table.csv)" = 14
check batched_result_lines "mixed.log: $(grep -c '^mixed_[0-9]*: .* nodes' mixed.log) result lines of ok cases, expected 14" \
  test "$(grep -c '^mixed_[0-9]*: .* nodes' mixed.log)" = 14
check batched_decks_beside_results "a case folder of mixed/ lacks its deck" \
  bash -c 'for k in 1 2 3 4 5 7 8 9 10 11 12 13 14 15 16; do cmp -s "mixed/mixed_$k/mixed_$k.inp" "mixed/decks/mixed_$k.inp" || exit 1; done'
check batched_no_folder_of_failed "mixed/mixed_6 exists" test ! -e mixed/mixed_6
python3 - mixed/table.csv > /dev/null 2>&1 <<'PY' && summaries_equal=yes || summaries_equal=no
import csv, sys
rows = {row['case']: row for row in csv.DictReader(open(sys.argv[1]))}
reference = next(csv.DictReader(open('serial/table.csv')))
reference = next(row for row in csv.DictReader(open('serial/table.csv')) if row['case'] == 'peach__height=0.1__radius=0.03')
for k in (1, 16):
    assert rows[f'mixed_{k}']['alpha_max_mm'] == reference['alpha_max_mm'], (rows[f'mixed_{k}'], reference)
PY
check batched_same_results "mixed_1 or mixed_16: alpha_max_mm differs from the case run alone" test "$summaries_equal" = yes

# A process killed in a deck (the stand-in, fed as visco2d is with --decks-from -, kills itself at
# the 5th deck it reads, once): that deck fails with the signal, the decks written to it after that
# one go back on the queue and run in a new process, first in line; all others end.
cat > killing_visco2d <<STANDIN
#!/bin/bash
echo "process" >> "$work/killed_processes.log"
root=\$2; n=0
while IFS= read -r deck; do
  n=\$((n + 1)); echo "deck \$deck" >> "$work/killed_processes.log"
  [ \$n = 5 ] && mkdir "$work/killed.once" 2> /dev/null && kill -KILL \$\$
  "$exe" -o "\$root" "\$deck" 2>&1
done
STANDIN
chmod +x killing_visco2d
python3 "$tool" run peach.inp --param height=0.05:0.2:12 --param radius=0.03 -j 1 --exe "$work/killing_visco2d" -q \
  -o killed_batch > killed_batch.log 2>&1
check_rc killed_batch_status_1 1 $?
killed=$(grep ',failed,' killed_batch/table.csv | cut -d, -f1)
check killed_batch_one_failed "killed_batch/table.csv: failed: '$killed' (expected the 5th deck of the process, stopped by signal 9)" \
  bash -c 'test "$(grep -c ",failed,.*stopped by signal 9" killed_batch/table.csv)" = 1'
check killed_batch_others_ok "killed_batch/table.csv: $(grep -c ',ok,' killed_batch/table.csv) ok rows, expected 11" \
  test "$(grep -c ',ok,' killed_batch/table.csv)" = 11
check killed_batch_rest_rerun "killed_processes.log: the process after the killed one does not start with the deck after its 5th: $(tr '\n' '|' < killed_processes.log | head -c 400)" \
  python3 -c '
import os
processes = []
for line in open("killed_processes.log"):
    if line.strip() == "process":
        processes.append([])
    else:
        processes[-1].append(os.path.basename(line.split(" ", 1)[1].strip())[:-len(".inp")])
order = [line.split(",")[0] for line in open("killed_batch/table.csv")][1:]
first, second = processes[0], processes[1]
assert len(first) == 5 and first == order[:5], (first, order)
assert second[0] == order[5] and second == order[5:], (second, order)
