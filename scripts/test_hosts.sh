#!/usr/bin/env bash
# Nothing lost across processes and hosts (the make test stage "processes
# and hosts"): runs that share an output root (an MPI farm, a cluster job
# array, two shells) never remove or overwrite each other's work, and
# visco2d-batch stops, resumes and refuses as doc/batch.md says.
#
#   bash scripts/test_hosts.sh PATH/TO/visco2d
#
# Prints `PASS name` or `FAIL name: detail` per check (`# ` lines are notes,
# `NOTE` lines say what was skipped) and always exits 0: the caller counts.
# The decks: inputs/peach_drop.inp at mesh levels 1 (~15 ms a run) and 3
# (~0.6 s: long enough to be caught running); everything in a temporary folder.

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

pass() { echo "PASS $1"; }
fail() { echo "FAIL $1: $2"; }
check() {  # check NAME DETAIL COMMAND...
  local name=$1 detail=$2
  shift 2
  if "$@"; then pass "$name"; else fail "$name" "$detail"; fi
}
check_rc() { if [ "$3" = "$2" ]; then pass "$1"; else fail "$1" "exit status $3, expected $2"; fi; }
first_lines() { head -c 400 "$1" 2>/dev/null | tr '\n' '|'; }
# wait_for PATH: until PATH exists (at most 10 s)
wait_for() { local i; for i in $(seq 1 2000); do [ -e "$1" ] && return 0; sleep 0.005; done; return 1; }

if [ $# -ne 1 ] || [ ! -x "$1" ] || [ -d "$1" ]; then
  fail executable "usage: bash scripts/test_hosts.sh PATH/TO/visco2d (got '${1:-}')"
  exit 0
fi
exe="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
batch() { "$tool" "$@" --exe "$exe"; }

work=$(mktemp -d "${TMPDIR:-/tmp}/visco2d_hosts.XXXXXX") || { fail mktemp "cannot create a temporary folder"; exit 0; }
holders=()
trap 'for p in "${holders[@]}"; do kill "$p" 2> /dev/null; done; rm -rf "$work"' EXIT
cd "$work" || { fail cd "cannot enter $work"; exit 0; }
source "$root/scripts/batch_tool.sh"
tool=$(batch_tool "$exe" "$work")

sed -e 's/^MESH SPHERE R=0.03 LEVEL=3/MESH SPHERE R=0.03 LEVEL=1/' "$root/inputs/peach_drop.inp" > small.inp
cp "$root/inputs/peach_drop.inp" slow.inp
check decks_made "the sed of inputs/peach_drop.inp found no LEVEL=3 MESH line" grep -q 'LEVEL=1' small.inp
sh -c 'exit 0' & dead=$!
wait "$dead"

# ------------------------------------------------------------- another host's folders
# A run on another host (or in another PID namespace) sharing the root: its
# pid means nothing here. Its temporary folders are left alone (a note says
# so), and a folder whose case lock is held by a live process is kept even
# when its pid looks dead. Before the case locks both were removed.
mkdir -p shared/.far.partial.node17.cluster.$dead shared/.far.old.node17.cluster.$dead \
  shared/.near.partial.$dead shared/.gone.partial.$dead
echo half > shared/.far.partial.node17.cluster.$dead/summary.txt
( exec 9> shared/.near.lock && flock 9 && exec sleep 30 ) & holders+=($!)   # a live run elsewhere
wait_for shared/.near.lock
sleep 0.1
"$exe" -q -o shared small.inp > shared.out 2> shared.err
check_rc foreign_run_exit_0 0 $?
check foreign_partial_kept "shared holds: $(ls -A shared | tr '\n' ' ')" \
  test -f shared/.far.partial.node17.cluster.$dead/summary.txt -a -d shared/.far.old.node17.cluster.$dead
check foreign_partial_note "stderr: $(first_lines shared.err)" \
  grep -q "^visco2d: note: left shared/.far.partial.node17.cluster.$dead alone: written by process $dead on host node17.cluster, another host" shared.err
check locked_partial_kept "shared holds: $(ls -A shared | tr '\n' ' ')" test -d shared/.near.partial.$dead
check unlocked_dead_partial_removed "shared holds: $(ls -A shared | tr '\n' ' ')" test ! -e shared/.gone.partial.$dead
kill "${holders[-1]}" 2> /dev/null
wait "${holders[-1]}" 2> /dev/null
"$exe" -q -o shared small.inp > shared2.out 2> shared2.err
check released_partial_removed "shared holds: $(ls -A shared | tr '\n' ' ')" test ! -e shared/.near.partial.$dead
check stale_lock_file_removed "shared holds: $(ls -A shared | tr '\n' ' ')" test ! -e shared/.near.lock
# A lock file that names another host stays (that host's run may hold it there).
echo "process $dead on host node17.cluster" > shared/.far.lock
"$exe" -q -o shared small.inp > /dev/null 2>&1
check foreign_lock_file_kept "shared holds: $(ls -A shared | tr '\n' ' ')" test -f shared/.far.lock
rm -f shared/.far.lock

# ------------------------------------------------------------- one case, two runs
# Two processes running one case into one root: the second fails at once,
# naming the first (exit 1); the first's result is whole; no lock file left.
"$exe" -q -o twice slow.inp > first.out 2> first.err & first=$!
wait_for twice/.slow.lock
"$exe" -q -o twice slow.inp > second.out 2> second.err
check_rc same_case_second_exit_1 1 $?
wait "$first"
check_rc same_case_first_exit_0 0 $?
check same_case_second_message "stderr: $(first_lines second.err)" \
  grep -q "^visco2d: error: slow.inp: the case slow is being run into twice by another run (process $first on host [^ ]*, which holds twice/.slow.lock)" second.err
check same_case_first_result "twice holds: $(ls -A twice 2>/dev/null | tr '\n' ' ')" \
  test "$(ls -A twice 2>/dev/null)" = slow -a -s twice/slow/summary.txt
# A deck that fails leaves no root made for its lock.
printf 'TITLE broken\nANALYSIS STATIC\nNOT_A_CARD 1\nEND\n' > broken.inp
"$exe" -q -o fresh/nested broken.inp > /dev/null 2>&1
check_rc failed_deck_exit_1 1 $?
check failed_deck_no_root "fresh exists: $(ls -AR fresh 2>/dev/null | tr '\n' ' ')" test ! -e fresh

# ------------------------------------------------------------- visco2d-batch
# The template: the peach at mesh level 2 (~0.1 s a run, long enough to be
# caught running) with a ${height} placeholder.
sed -e 's/^MESH SPHERE R=0.03 LEVEL=3/MESH SPHERE R=0.03 LEVEL=2/' -e 's/^DROP HEIGHT=0.2/DROP HEIGHT=${height}/' \
  "$root/inputs/peach_drop.inp" > drop.inp
sed -e 's/LEVEL=2/LEVEL=1/' drop.inp > quick.inp     # ~15 ms a run: where nothing needs catching running
check template_made "the sed of inputs/peach_drop.inp found no DROP line" grep -q 'HEIGHT=${height}' drop.inp
sweep=(--param height=0.1:0.2:6)
first_case='drop__height=0.1'
# count_ok TABLE: the rows whose status is ok
count_ok() { tail -n +2 "$1" 2>/dev/null | grep -c '^[^,]*,ok,'; }
# kill_a_worker BATCH_PID: once a first case has ended, SIGKILL a running visco2d child of the batch (or of its
# mpirun stand-in); prints the killed process's deck
kill_a_worker() {
  local batch=$1 out=$2 i child
  wait_for "$out/$first_case/summary.txt" || return 1
  for i in $(seq 1 2000); do
    child=$(pgrep -f -- "-o $out/*[^ ]* (--decks-from -|.*decks/drop__height)" | head -1)
    [ -n "$child" ] && { kill -KILL "$child"; return 0; }
    sleep 0.005
  done
  return 1
}
# mtimes OUT: the case folders' summary.txt and their modification times
mtimes() { find "$1" -mindepth 2 -maxdepth 2 -name summary.txt -printf '%p %T@\n' | sort; }

# Ctrl-C: SIGINT to the batch process (job control on: a background job would otherwise ignore it).
set -m
"$tool" run drop.inp "${sweep[@]}" --exe "$exe" -j 1 -q -o interrupted > interrupted.log 2>&1 &
batch_pid=$!
set +m
wait_for "interrupted/$first_case/summary.txt"
start=$(date +%s%N)
kill -INT "$batch_pid"
wait "$batch_pid"
status=$?
elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
echo "# Ctrl-C: visco2d-batch ended $elapsed_ms ms after SIGINT, exit $status"
check_rc interrupt_exit_130 130 "$status"
check interrupt_prompt "it took $elapsed_ms ms to stop" test "$elapsed_ms" -lt 3000
ran=$(ls -d interrupted/drop__* 2>/dev/null | wc -l)
check interrupt_stops_the_queue "$ran of 6 cases ran after SIGINT" test "$ran" -lt 6 -a "$ran" -ge 1
check interrupt_table_written "interrupted/table.csv: $(first_lines interrupted/table.csv)" \
  test "$(count_ok interrupted/table.csv)" = "$ran" -a "$(grep -c ',not run,' interrupted/table.csv)" = $(( 6 - ran ))
check interrupt_says_what_did_not_run "log: $(first_lines interrupted.log)" \
  grep -q "^visco2d-batch: interrupted: $ran of 6 cases ended (their table: interrupted/table.csv); $(( 6 - ran )) did not run: drop__height=0.2\|, drop__height=0.2" interrupted.log
check interrupt_no_partial "interrupted holds: $(ls -A interrupted | tr '\n' ' ')" \
  test -z "$(ls -A interrupted | grep -e '^\.')"
batch run drop.inp "${sweep[@]}" -j 2 --resume -o interrupted > resumed.log 2>&1
check_rc interrupt_resume_exit_0 0 $?
check interrupt_resume_runs_the_rest "resumed.log: $(first_lines resumed.log)" \
  grep -q -- "--resume: $ran of 6 cases have a complete, verified result in interrupted; running the other $(( 6 - ran ))" resumed.log
check interrupt_resume_table "interrupted/table.csv: $(count_ok interrupted/table.csv) ok rows" test "$(count_ok interrupted/table.csv)" = 6

# --resume after a killed worker (-j 2): the killed case fails, the others end; --resume runs only it.
"$tool" run drop.inp "${sweep[@]}" --exe "$exe" -j 2 -q -o killed > killed.log 2>&1 &
batch_pid=$!
kill_a_worker "$batch_pid" killed
check killed_worker_found "no visco2d process of the batch to kill" test $? = 0
wait "$batch_pid"
check_rc killed_worker_batch_exit_1 1 $?
failed=$(grep -c ',failed,.*stopped by signal 9' killed/table.csv)
check killed_worker_case_failed "killed/table.csv: $(first_lines killed/table.csv)" test "$failed" = 1
before=$(mtimes killed)
rm -f "killed/$first_case/results.h5"    # an incomplete folder is not a result: it runs again
batch run drop.inp "${sweep[@]}" -j 2 --resume -o killed > killed_resume.log 2>&1
check_rc resume_exit_0 0 $?
check resume_runs_only_the_missing "killed_resume.log: $(first_lines killed_resume.log)" \
  grep -q -- '--resume: 4 of 6 cases have a complete, verified result in killed; running the other 2' killed_resume.log
after=$(mtimes killed)
check resume_keeps_the_verified "$(diff <(echo "$before") <(echo "$after") | grep -c '^>') summaries changed, expected 2" \
  test "$(diff <(echo "$before") <(echo "$after") | grep -c '^>')" = 2
check resume_table_all_ok "killed/table.csv: $(count_ok killed/table.csv) ok rows" test "$(count_ok killed/table.csv)" = 6
batch run drop.inp "${sweep[@]}" -j 1 -q -o fresh_sweep > /dev/null 2>&1
check resume_same_table "the resumed table differs from a fresh run's" \
  cmp -s <(cut -d, -f1-9 killed/table.csv) <(cut -d, -f1-9 fresh_sweep/table.csv)
# A case folder of another deck under the same name (another template) is not this sweep's result.
sed -i 's/^TITLE .*/TITLE another template/' "killed/$first_case/$first_case.inp"
batch run drop.inp "${sweep[@]}" -j 1 --resume -o killed > killed_other.log 2>&1
check resume_checks_the_deck "killed_other.log: $(first_lines killed_other.log)" \
  grep -q -- '--resume: 5 of 6 cases' killed_other.log

# --shard K/N --resume: only the shard's cases without a result.
batch run quick.inp "${sweep[@]}" --shard 1/2 -j 1 -q -o shards > /dev/null 2>&1
rm -rf "shards/quick__height=0.12"
batch run quick.inp "${sweep[@]}" --shard 1/2 -j 1 --resume -o shards > shard_resume.log 2>&1
check_rc shard_resume_exit_0 0 $?
check shard_resume_runs_one "shard_resume.log: $(first_lines shard_resume.log)" \
  grep -q -- '--resume: 2 of 3 cases have a complete, verified result in shards; running the other 1' shard_resume.log

# --mpi N --resume, with a stand-in mpirun (runs the farm once) and farm (visco2d itself: one process runs
# every deck in turn, so killing it ends the whole job, as a killed rank aborts mpirun).
mkdir -p fakempi
printf '#!/bin/bash\nwhile [ "${1#-}" != "$1" ]; do case $1 in -np) shift 2;; *) shift;; esac; done\nexec "$@"\n' \
  > fakempi/mpirun
printf '#!/bin/bash\nexec "%s" "$@"\n' "$exe" > fakempi/farm
chmod +x fakempi/mpirun fakempi/farm
PATH="$work/fakempi:$PATH" "$tool" run drop.inp "${sweep[@]}" --mpi 2 --farm fakempi/farm -q -o mpi \
  > mpi.log 2>&1 & batch_pid=$!
kill_a_worker "$batch_pid" mpi
wait "$batch_pid"
check_rc mpi_killed_exit_1 1 $?
done_before=$(count_ok mpi/table.csv)
check mpi_killed_job_lost_the_rest "mpi/table.csv: $done_before ok rows" test "$done_before" -ge 1 -a "$done_before" -lt 6
PATH="$work/fakempi:$PATH" "$tool" run drop.inp "${sweep[@]}" --mpi 2 --farm fakempi/farm --resume -o mpi \
  > mpi_resume.log 2>&1
check_rc mpi_resume_exit_0 0 $?
check mpi_resume_runs_the_rest "mpi_resume.log: $(first_lines mpi_resume.log)" \
  grep -q -- "--resume: $done_before of 6 cases have a complete, verified result in mpi; running the other $(( 6 - done_before ))" mpi_resume.log
check mpi_resume_passes_only_those "mpi/decks/mpi.log: $(grep -o 'drop__height=[0-9.]*\.inp' mpi/decks/mpi.log | head -3 | tr '\n' ' ')" \
  test "$(head -1 mpi/decks/mpi.log | grep -o 'decks/drop__height=[0-9.]*\.inp' | wc -l)" = $(( 6 - done_before ))
check mpi_resume_table "mpi/table.csv: $(count_ok mpi/table.csv) ok rows" test "$(count_ok mpi/table.csv)" = 6

# Ctrl-C during --mpi: mpirun (the stand-in) is sent SIGINT; the table of what ended, exit 130.
set -m
PATH="$work/fakempi:$PATH" "$tool" run drop.inp "${sweep[@]}" --mpi 2 --farm fakempi/farm -q \
  -o mpi_interrupted > mpi_interrupted.log 2>&1 &
batch_pid=$!
set +m
wait_for "mpi_interrupted/$first_case/summary.txt"
kill -INT "$batch_pid"
wait "$batch_pid"
check_rc mpi_interrupt_exit_130 130 $?
ran=$(count_ok mpi_interrupted/table.csv)
check mpi_interrupt_table "mpi_interrupted/table.csv: $ran ok, $(grep -c ',not run,' mpi_interrupted/table.csv) not run" \
  test "$ran" -ge 1 -a "$(grep -c ',not run,' mpi_interrupted/table.csv)" = $(( 6 - ran ))

# A reused output root: the table holds this run's cases; collect gathers the folder on purpose.
batch run quick.inp --param height=0.1,0.2 -q -o reused > /dev/null 2>&1
batch run quick.inp --param height=0.15 -q -o reused > reused.log 2>&1
check_rc reused_exit_0 0 $?
check reused_table_this_run "reused/table.csv: $(first_lines reused/table.csv)" \
  test "$(tail -n +2 reused/table.csv | cut -d, -f1 | tr '\n' ' ')" = "quick__height=0.15 "
"$tool" collect reused -q > /dev/null 2>&1
check reused_collect_all "reused/table.csv after collect: $(tail -n +2 reused/table.csv | wc -l) rows" \
  test "$(tail -n +2 reused/table.csv | wc -l)" = 3

# The size of a sweep, refused before it is expanded (a COUNT of 1e8 took 948 MB in 40 s).
start=$(date +%s%N)
batch run drop.inp --param height=0.1:0.2:100000000 -o huge > huge.log 2>&1
status=$?
elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
check_rc huge_range_exit_2 2 "$status"
check huge_range_at_once "$elapsed_ms ms" test "$elapsed_ms" -lt 2000
check huge_range_message "$(first_lines huge.log)" \
  grep -q 'error: --param height: height: a range of 100000000 values makes more than the 10000 cases a sweep may have; nothing was expanded or run (give --max-cases N' huge.log
check huge_nothing_written "huge/ exists" test ! -e huge
batch expand drop.inp --param height=0.1:0.2:200 --param other=1:2:200 -o product > product.log 2>&1
check_rc huge_product_exit_2 2 $?
check huge_product_message "$(first_lines product.log)" grep -q 'the sweep (200 x 200 values) has 40000 cases per deck' product.log
sed 's/NU=0.35/NU=${nu}/' drop.inp > drop_nu.inp
batch expand drop_nu.inp --param height=0.1:0.2:5 --param nu=0.3,0.35 --max-cases 8 -o capped > capped.log 2>&1
check_rc max_cases_refuses_exit_2 2 $?
batch expand drop_nu.inp --param height=0.1:0.2:5 --param nu=0.3,0.35 --max-cases 10 -o capped > capped.log 2>&1
check_rc max_cases_allows_exit_0 0 $?
check max_cases_allows_decks "capped/decks: $(ls capped/decks 2>/dev/null | grep -c '\.inp$') decks" \
  test "$(ls capped/decks 2>/dev/null | grep -c '\.inp$')" = 10

# A parameter given twice; TOML entries of the wrong kind: exit 2, a message naming where.
batch run drop.inp --param height=0.1 --param height=0.2 -o twice_param > twice_param.log 2>&1
check_rc repeated_param_exit_2 2 $?
check repeated_param_message "$(first_lines twice_param.log)" \
  grep -q 'error: --param height: the parameter "height" is already given by --param height' twice_param.log
check repeated_param_nothing_run "twice_param/ exists" test ! -e twice_param
printf 'param = 3\n' > bad.toml
batch run drop.inp --sweep bad.toml -o bad_toml > bad_toml.log 2>&1
check_rc toml_param_scalar_exit_2 2 $?
check toml_param_scalar_message "$(first_lines bad_toml.log)" \
  grep -q '^visco2d-batch: error: bad.toml: param: expected a table: \[param\]' bad_toml.log
check toml_param_no_traceback "$(first_lines bad_toml.log)" bash -c '! grep -q Traceback bad_toml.log'
printf 'zip = "yes"\n[param]\nheight = [0.1]\n' > bad_zip.toml
batch run drop.inp --sweep bad_zip.toml -o bad_toml > bad_zip.log 2>&1
check_rc toml_zip_string_exit_2 2 $?
printf '[param]\nheight = [0.1]\n' > height.toml
batch run drop.inp --sweep height.toml --param height=0.2 -o bad_toml > both.log 2>&1
check_rc toml_and_param_twice_exit_2 2 $?
check toml_and_param_twice_message "$(first_lines both.log)" grep -q 'already given by --param height' both.log
exit 0
