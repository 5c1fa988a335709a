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
tool="$root/scripts/visco2d_batch.py"

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
batch() { python3 "$tool" "$@" --exe "$exe"; }

work=$(mktemp -d "${TMPDIR:-/tmp}/visco2d_hosts.XXXXXX") || { fail mktemp "cannot create a temporary folder"; exit 0; }
holders=()
trap 'for p in "${holders[@]}"; do kill "$p" 2> /dev/null; done; rm -rf "$work"' EXIT
cd "$work" || { fail cd "cannot enter $work"; exit 0; }

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
