#!/usr/bin/env bash
# The MPI task farm against the serial program (the make test stage
# "MPI task farm (2 ranks)").
#
#   bash scripts/test_mpi.sh [PATH/TO/visco2d]
#
# Builds the farm (make mpi: installs OpenMPI if missing), runs every deck of
# inputs/ plus one failing deck serially with visco2d and over 2 ranks with
# mpirun (and over 3 ranks, so that two workers finish out of order), and
# checks: the same stdout lines in deck order (their "cpu ... s" masked), the
# same error on stderr, exit status 1 because of the failing deck, summaries
# identical key for key except cpu_s, identical history.csv, no partial
# folders and no folder for the failing deck; then the refusal of two decks
# with the same case name (exit 2, nothing written). Prints `PASS ...` /
# `FAIL ...` lines (and `#` notes) and always exits 0: the caller counts them.

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root" || exit 0
exe=${1:-build/install/bin/visco2d}
farm=build/mpi/bin/visco2d-farm

pass() { echo "PASS $1"; }
fail() { echo "FAIL $1: $2"; }
check_rc() { if [ "$3" = "$2" ]; then pass "$1"; else fail "$1" "exit status $3, expected $2"; fi; }

if [ ! -x "$exe" ]; then
  fail mpi_serial_executable "no serial visco2d at $exe (make build)"
  exit 0
fi
start=$(date +%s)
if ! make --no-print-directory mpi > build/test-mpi-build.log 2>&1; then
  fail mpi_build "make mpi failed: $(tail -5 build/test-mpi-build.log | tr '\n' '|')"
  exit 0
fi
pass mpi_build
echo "# make mpi (OpenMPI install if missing, farm build): $(( $(date +%s) - start )) s"

# mpirun as root (CI) needs the permission; on 2 cores 3 ranks need --oversubscribe.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun_n() { local n=$1; shift; mpirun --oversubscribe -np "$n" "$@"; }

work=$(mktemp -d "${TMPDIR:-/tmp}/visco2d_mpi.XXXXXX") || { fail mktemp "cannot create a temporary folder"; exit 0; }
trap 'rm -rf "$work"' EXIT
# A deck that reads up to line 3 and fails there: an error, exit 1, no folder.
cat > "$work/broken.inp" <<'EOF'
TITLE broken
ANALYSIS STATIC
NOT_A_CARD 1
END
EOF
# Every deck of inputs/ (dynamic impacts, quasi-static, static) with the failing deck among them.
decks=()
for deck in inputs/*.inp; do
  decks+=("$deck")
  [ ${#decks[@]} -eq 5 ] && decks+=("$work/broken.inp")
done

# The lines a run printed, with the CPU time masked (it differs between runs).
mask_cpu() { sed -E 's/; cpu [^;]* s$/; cpu (masked) s/' "$1"; }
# Key = value lines of a summary except cpu_s, sorted by key.
summary_keys() { grep -v '^cpu_s = ' "$1" | sort; }

"$exe" -o "$work/serial" "${decks[@]}" > "$work/serial.out" 2> "$work/serial.err"
serial_status=$?
check_rc mpi_serial_exit_1 1 "$serial_status"
count=$(ls "$work/serial" | wc -l)
echo "# ${#decks[@]} decks, $count case folders serially"
lines=$(wc -l < "$work/serial.out")
if [ "$count" -eq $(( ${#decks[@]} - 1 )) ] && [ "$lines" -eq "$count" ]; then
  pass "mpi_serial_reference_run ($count cases, $lines lines)"
else
  fail mpi_serial_reference_run "$count folders and $lines lines for ${#decks[@]} decks (one failing)"
fi

for ranks in 2 3; do
  run="farm$ranks"
  mpirun_n "$ranks" "$farm" -o "$work/$run" "${decks[@]}" > "$work/$run.out" 2> "$work/$run.err"
  check_rc "mpi_${ranks}_ranks_exit_1" 1 $?
  if diff <(mask_cpu "$work/serial.out") <(mask_cpu "$work/$run.out") > "$work/$run.diff"; then
    pass "mpi_${ranks}_ranks_stdout_lines_in_deck_order"
  else
    fail "mpi_${ranks}_ranks_stdout_lines_in_deck_order" "$(head -c 400 "$work/$run.diff" | tr '\n' '|')"
  fi
  if diff <(grep '^visco2d: error: \|^visco2d: [0-9]* of' "$work/serial.err") \
          <(grep '^visco2d: error: \|^visco2d: [0-9]* of' "$work/$run.err") > /dev/null; then
    pass "mpi_${ranks}_ranks_same_errors"
  else
    fail "mpi_${ranks}_ranks_same_errors" "$(grep 'visco2d: ' "$work/$run.err" | head -3 | tr '\n' '|')"
  fi
  if diff <(ls -A "$work/serial") <(ls -A "$work/$run") > /dev/null; then
    pass "mpi_${ranks}_ranks_same_case_folders_no_partial"
  else
    fail "mpi_${ranks}_ranks_same_case_folders_no_partial" "$(ls -A "$work/$run" | tr '\n' ' ')"
  fi
  if [ -e "$work/$run/broken" ]; then fail "mpi_${ranks}_ranks_no_folder_for_failed_deck" "$work/$run/broken exists"
  else pass "mpi_${ranks}_ranks_no_folder_for_failed_deck"; fi
  bad_summary=""
  bad_history=""
  for folder in "$work/serial"/*/; do
    name=$(basename "$folder")
    cmp -s <(summary_keys "$folder/summary.txt") <(summary_keys "$work/$run/$name/summary.txt") \
      || bad_summary="$bad_summary $name"
    cmp -s "$folder/history.csv" "$work/$run/$name/history.csv" || bad_history="$bad_history $name"
  done
  if [ -z "$bad_summary" ]; then pass "mpi_${ranks}_ranks_summaries_equal_but_cpu_s ($count cases)"
  else fail "mpi_${ranks}_ranks_summaries_equal_but_cpu_s" "differ:$bad_summary"; fi
  if [ -z "$bad_history" ]; then pass "mpi_${ranks}_ranks_history_identical ($count cases)"
  else fail "mpi_${ranks}_ranks_history_identical" "differ:$bad_history"; fi
done

# -q: no result lines, the same exit status.
mpirun_n 2 "$farm" -q -o "$work/quiet" inputs/sphere_pressure.inp "$work/broken.inp" > "$work/quiet.out" 2> /dev/null
check_rc mpi_quiet_exit_1 1 $?
if [ -s "$work/quiet.out" ]; then fail mpi_quiet_no_lines "$(head -c 200 "$work/quiet.out")"; else pass mpi_quiet_no_lines; fi
mpirun_n 2 "$farm" -o "$work/good" inputs/sphere_pressure.inp inputs/lame_axisymmetric.inp > /dev/null 2>&1
check_rc mpi_all_good_exit_0 0 $?

# A deck that misses its own EXPECT card: results written, the miss on stderr, exit 3 (as visco2d);
# with the failing deck too, 1 wins.
sed -e 's/^EXPECT probe_pole_uz_m .*/EXPECT probe_pole_uz_m 2.0e-3 RTOL=1e-6/' inputs/sphere_pressure.inp \
  > "$work/missed.inp"
for ranks in 1 3; do
  mpirun_n $ranks "$farm" -q -o "$work/missed_$ranks" inputs/lame_axisymmetric.inp "$work/missed.inp" \
    > /dev/null 2> "$work/missed_$ranks.err"
  check_rc "mpi_${ranks}_ranks_expect_miss_exit_3" 3 $?
  if grep -q "^visco2d: error: .*missed.inp:23:[0-9]*: EXPECT: probe_pole_uz_m = " "$work/missed_$ranks.err" \
     && [ -s "$work/missed_$ranks/missed/summary.txt" ]; then pass "mpi_${ranks}_ranks_expect_miss_reported"
  else fail "mpi_${ranks}_ranks_expect_miss_reported" "$(head -c 300 "$work/missed_$ranks.err" | tr '\n' '|')"; fi
done
mpirun_n 2 "$farm" -q -o "$work/missed_mixed" "$work/missed.inp" "$work/broken.inp" > /dev/null 2>&1
check_rc mpi_expect_miss_and_failure_exit_1 1 $?

# Two decks with one case name: refused before anything runs, like visco2d.
mkdir -p "$work/a" "$work/b"
cp inputs/sphere_pressure.inp "$work/a/peach.inp"
cp inputs/lame_axisymmetric.inp "$work/b/peach.inp"
mpirun_n 2 "$farm" -o "$work/twin" "$work/a/peach.inp" "$work/b/peach.inp" > "$work/twin.out" 2> "$work/twin.err"
check_rc mpi_duplicate_case_exit_2 2 $?
if grep -q "a/peach.inp and .*b/peach.inp have the same case name \"peach\"" "$work/twin.err"; then
  pass mpi_duplicate_case_names_both
else
  fail mpi_duplicate_case_names_both "$(head -c 300 "$work/twin.err" | tr '\n' '|')"
fi
if [ -e "$work/twin" ]; then fail mpi_duplicate_nothing_written "$work/twin exists"; else pass mpi_duplicate_nothing_written; fi
mpirun_n 2 "$farm" -o "$work/usage" --no-such-option inputs/sphere_pressure.inp > /dev/null 2>&1
check_rc mpi_unknown_option_exit_2 2 $?

# The default build's farm (no MPI) says how to get the real one.
default_farm=$(dirname "$exe")/visco2d-farm
if [ -x "$default_farm" ]; then
  "$default_farm" inputs/sphere_pressure.inp > /dev/null 2> "$work/nompi.err"
  check_rc mpi_default_build_exit_2 2 $?
  if grep -q "built without MPI: make mpi" "$work/nompi.err"; then pass mpi_default_build_says_make_mpi
  else fail mpi_default_build_says_make_mpi "$(head -c 200 "$work/nompi.err")"; fi
fi
echo "# test_mpi: $(( $(date +%s) - start )) s in all"
exit 0
