#!/usr/bin/env bash
# Command-line tests of visco2d.
#
#   bash scripts/test_cli.sh PATH/TO/visco2d
#
# (find the executable with `fpm run --runner` or
#  `find build -type f -name visco2d -path '*app*' | head -1`)
#
# Prints one line per check, `PASS name` or `FAIL name: detail` (lines starting
# with `#` are notes), and always exits 0: the caller counts the lines.
# Everything happens in a fresh temporary folder, removed at the end.

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export PYTHONPATH="$root/python${PYTHONPATH:+:$PYTHONPATH}"   # the package python/visco2d/ (doc/python.md)
good_source="$root/inputs/sphere_pressure.inp"

pass() { echo "PASS $1"; }
fail() { echo "FAIL $1: $2"; }
# check NAME DETAIL COMMAND...: PASS if the command succeeds.
check() {
  local name=$1 detail=$2
  shift 2
  if "$@"; then pass "$name"; else fail "$name" "$detail"; fi
}
# check_rc NAME EXPECTED ACTUAL
check_rc() {
  if [ "$3" = "$2" ]; then pass "$1"; else fail "$1" "exit status $3, expected $2"; fi
}
# One line of a file, for details.
first_lines() { head -c 400 "$1" 2>/dev/null | tr '\n' '|'; }
# Entries (hidden ones too) of a folder whose name contains a text.
entries_matching() { ls -A "$1" 2>/dev/null | grep -F -- "$2"; }

if [ $# -ne 1 ] || [ ! -x "$1" ] || [ -d "$1" ]; then
  fail executable "usage: bash scripts/test_cli.sh PATH/TO/visco2d (got '${1:-}')"
  exit 0
fi
exe="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
if [ ! -f "$good_source" ]; then
  fail good_deck_source "$good_source is missing"
  exit 0
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/visco2d_cli.XXXXXX") || { fail mktemp "cannot create a temporary folder"; exit 0; }
trap 'rm -rf "$work"' EXIT
cd "$work" || { fail cd "cannot enter $work"; exit 0; }
mkdir decks
cp "$good_source" decks/sphere_pressure.inp

# A bad deck: NU out of range on line 4, the NU field at column 32.
cat > decks/bad.inp <<'EOF'
TITLE bad
ANALYSIS STATIC
GEOMETRY PLANESTRAIN
MATERIAL steel ELASTIC E=200e9 NU=0.7
MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=2 NZ=2
FIX BOTTOM RZ
END
EOF
# A bad layered deck: the skin's material is not defined (SKINMAT= at column 30).
cat > decks/bad_skin.inp <<'EOF'
TITLE bad skin
ANALYSIS STATIC
MATERIAL flesh ELASTIC E=3e6 NU=0.3
MATERIAL skin ELASTIC E=30e6 NU=0.3
MESH SPHERE R=0.03 MAT=flesh SKINMAT=wood SKIN_LAYERS=2
PRESSURE OUTER P=1e3
FIX TOP Z
END
EOF
# Small valid decks for the batch run.
for name in first last; do
  cat > "decks/$name.inp" <<'EOF'
TITLE block
ANALYSIS STATIC
GEOMETRY PLANESTRAIN
MATERIAL steel ELASTIC E=200e9 NU=0.3
MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=2 NZ=2
FIX BOTTOM RZ
PRESSURE TOP P=1e6
END
EOF
done
# Reads cleanly, fails at solve time (no supports: a rigid-body mode).
cat > decks/loose.inp <<'EOF'
TITLE no supports
ANALYSIS STATIC
GEOMETRY PLANESTRAIN
MATERIAL steel ELASTIC E=200e9 NU=0.3
MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=2 NZ=2
PRESSURE TOP P=1e6
END
EOF

# ------------------------------------------------------------------ usage
mkdir usage && cd usage || exit 0
"$exe" --help > help.out 2> help.err
check_rc help_exit_0 0 $?
check help_mentions_check "--help output does not mention 'check': $(first_lines help.out)" grep -q check help.out

"$exe" > none.out 2> none.err
check_rc no_arguments_exit_2 2 $?
check no_arguments_usage_on_stderr "stderr: $(first_lines none.err)" grep -qi usage none.err

"$exe" --no-such-option ../decks/first.inp > opt.out 2> opt.err
check_rc unknown_option_exit_2 2 $?
check unknown_option_named "stderr: $(first_lines opt.err)" grep -qF -- --no-such-option opt.err
check unknown_option_runs_nothing "an output folder was created" test ! -e out

"$exe" -o > o.out 2> o.err
check_rc out_option_without_folder_exit_2 2 $?
cd "$work" || exit 0

# --------------------------------------------------------------- good deck
mkdir good && cd good || exit 0
"$exe" ../decks/sphere_pressure.inp > run.out 2> run.err
check_rc good_deck_exit_0 0 $?
check good_deck_case_folder "out/sphere_pressure/ missing; stderr: $(first_lines run.err)" test -d out/sphere_pressure
for file in listing.txt summary.txt history.csv results.h5; do
  check "good_deck_writes_$file" "out/sphere_pressure/$file missing or empty" test -s "out/sphere_pressure/$file"
done
check good_deck_no_hidden_folders "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test "$(ls -A out 2>/dev/null)" = sphere_pressure
check good_deck_reports_case "stdout: $(first_lines run.out)" grep -q '^sphere_pressure:' run.out
check good_deck_stderr_empty "stderr: $(first_lines run.err)" test ! -s run.err

# summary.txt: key = value lines with the documented keys.
summary=out/sphere_pressure/summary.txt
bad_lines=$(grep -Evc '^[A-Za-z_][A-Za-z0-9_]* =( .*)?$' "$summary" 2>/dev/null)
check summary_key_value_lines "$bad_lines line(s) not 'key = value': $(grep -Ev '^[A-Za-z_][A-Za-z0-9_]* =( .*)?$' "$summary" 2>/dev/null | head -3 | tr '\n' '|')" \
  test -s "$summary" -a "$bad_lines" = 0
for key in case title effects nodes elements dofs half_bandwidth steps cpu_s; do
  check "summary_has_$key" "no '$key = ' line in summary.txt" grep -qs "^$key = " "$summary"
done
value_of() { sed -n "s/^$1 = //p" "$summary" 2>/dev/null | head -1; }
nnode=$(value_of nodes)
nelem=$(value_of elements)
check summary_case_is_stem "case = '$(value_of case)'" test "$(value_of case)" = sphere_pressure
check summary_dofs_twice_nodes "nodes = '$nnode', dofs = '$(value_of dofs)'" \
  test -n "$nnode" -a "$(value_of dofs)" = "$((2 * ${nnode:-0}))"

# results.h5 through h5dump.
h5=out/sphere_pressure/results.h5
if command -v h5dump > /dev/null; then
  h5dump -H "$h5" > h5.header 2> h5.err
  check_rc h5dump_reads_results 0 $?
  h5dump -H -d /mesh/nodes "$h5" > /dev/null 2>&1
  check_rc h5_has_mesh_nodes 0 $?
  h5dump -H -d /mesh/elements "$h5" > /dev/null 2>&1
  check_rc h5_has_mesh_elements 0 $?
  h5dump -H -g /fields "$h5" > fields.header 2>&1
  field=$(sed -n 's/^ *GROUP "\([^"/]*\)" {.*/\1/p' fields.header | grep -v '^fields$' | head -1)
  check h5_has_a_field_group "no group under /fields: $(first_lines fields.header)" test -n "$field"
  if [ -n "$field" ]; then
    h5dump -H -d "/fields/$field/displacement" "$h5" > /dev/null 2>&1
    check_rc h5_field_has_displacement 0 $?
    h5dump -H -d "/fields/$field/stress" "$h5" > /dev/null 2>&1
    check_rc h5_field_has_stress 0 $?
    h5dump -a "/fields/$field/time" "$h5" > time.out 2>&1
    check_rc h5_field_has_time_attribute 0 $?
  fi
else
  fail h5dump_available "h5dump is not on PATH"
fi

# results.h5 through h5py (if available).
if command -v python3 > /dev/null && python3 -c 'import h5py' > /dev/null 2>&1; then
  python3 - "$h5" > h5py.out 2> h5py.err <<'EOF'
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    nodes = f["/mesh/nodes"]
    elements = f["/mesh/elements"][()]
    print("nodes_shape", "x".join(str(n) for n in nodes.shape))
    print("elements_shape", "x".join(str(n) for n in elements.shape))
    print("elements_min", int(elements.min()))
    print("elements_max", int(elements.max()))
    print("elements_distinct", len(set(int(v) for v in elements.ravel())))
EOF
  check_rc h5py_reads_results 0 $?
  got() { sed -n "s/^$1 //p" h5py.out; }
  check h5py_nodes_shape "shape $(got nodes_shape), expected ${nnode}x2" test "$(got nodes_shape)" = "${nnode}x2"
  check h5py_elements_shape "shape $(got elements_shape), expected ${nelem}x4" test "$(got elements_shape)" = "${nelem}x4"
  check h5py_elements_min_1 "min $(got elements_min), expected 1 (1-based)" test "$(got elements_min)" = 1
  check h5py_elements_max_nnode "max $(got elements_max), expected $nnode" \
    test -n "$nnode" -a "$(got elements_max)" = "$nnode"
  check h5py_elements_use_every_node "$(got elements_distinct) distinct node numbers, expected $nnode" \
    test -n "$nnode" -a "$(got elements_distinct)" = "$nnode"
else
  echo "# h5py not available: h5py checks skipped"
fi
cd "$work" || exit 0

# ------------------------------------------------------------- -o DIR
mkdir custom && cd custom || exit 0
"$exe" -o results/nested ../decks/sphere_pressure.inp > run.out 2> run.err
check_rc out_option_exit_0 0 $?
check out_option_case_folder "results/nested/sphere_pressure/summary.txt missing; stderr: $(first_lines run.err)" \
  test -s results/nested/sphere_pressure/summary.txt
check out_option_default_unused "out/ was created although -o was given" test ! -e out
cd "$work" || exit 0

# ------------------------------------------------------------- bad deck
mkdir bad && cd bad || exit 0
"$exe" ../decks/bad.inp > run.out 2> run.err
check_rc bad_deck_exit_1 1 $?
check bad_deck_located_error "stderr: $(first_lines run.err)" \
  grep -qF '../decks/bad.inp:4:32: MATERIAL: NU must be in (-1, 0.5), got 0.7' run.err
check bad_deck_error_format "no 'file:line:col: CARD:' line on stderr: $(first_lines run.err)" \
  grep -Eq '^visco2d: error: [^ :]+:[0-9]+:[0-9]+: [A-Z]+: ' run.err
check bad_deck_stderr_clean "stderr holds more than the error message: $(first_lines run.err)" \
  test "$(grep -cv '^visco2d: error: ' run.err)" = 0
check bad_deck_no_case_folder "out/bad exists" test ! -e out/bad
check bad_deck_no_hidden_folder "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test -z "$(entries_matching out bad)"

# The layered deck with an undefined skin material.
"$exe" ../decks/bad_skin.inp > skin.out 2> skin.err
check_rc bad_skin_deck_exit_1 1 $?
check bad_skin_deck_located_error "stderr: $(first_lines skin.err)" \
  grep -qF '../decks/bad_skin.inp:5:30: MESH: ' skin.err
check bad_skin_deck_names_material "stderr: $(first_lines skin.err)" \
  grep -qF 'uses material WOOD, which is not defined by a MATERIAL card' skin.err
check bad_skin_deck_no_case_folder "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test -z "$(entries_matching out bad_skin)"

# A deck that reads but fails at solve time.
"$exe" ../decks/loose.inp > loose.out 2> loose.err
check_rc solve_failure_exit_1 1 $?
check solve_failure_mentions_fix "stderr: $(first_lines loose.err)" grep -q 'FIX' loose.err
check solve_failure_names_node "stderr: $(first_lines loose.err)" grep -Eq 'node [0-9]+' loose.err
check solve_failure_no_case_folder "out/loose exists" test ! -e out/loose
check solve_failure_no_hidden_folder "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test -z "$(entries_matching out loose)"

# The case folder cannot be created (a plain file is in the way): the
# temporary folder must be cleaned up and the file left alone.
mkdir -p blocked && echo keep > blocked/first
"$exe" -o blocked ../decks/first.inp > blocked.out 2> blocked.err
check_rc blocked_case_exit_1 1 $?
check blocked_case_error_names_folder "stderr: $(first_lines blocked.err)" grep -q 'blocked/first' blocked.err
check blocked_case_no_hidden_folder "blocked/ holds: $(ls -A blocked | tr '\n' ' ')" \
  test "$(ls -A blocked)" = first
check blocked_case_file_untouched "blocked/first changed" test "$(cat blocked/first 2>/dev/null)" = keep
cd "$work" || exit 0

# ------------------------------------------------------------- batch
mkdir batch && cd batch || exit 0
"$exe" ../decks/first.inp ../decks/bad.inp ../decks/last.inp > run.out 2> run.err
check_rc batch_exit_1 1 $?
check batch_first_deck_ran "out/first/summary.txt missing" test -s out/first/summary.txt
check batch_deck_after_bad_ran "out/last/summary.txt missing; stderr: $(first_lines run.err)" test -s out/last/summary.txt
check batch_bad_deck_no_folder "out/bad exists" test ! -e out/bad
check batch_only_good_folders "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test "$(ls -A out 2>/dev/null | tr '\n' ' ')" = "first last "
check batch_reports_failure_count "stderr: $(first_lines run.err)" grep -q '1 of 3 decks failed' run.err
check batch_reports_good_decks "stdout: $(first_lines run.out)" \
  test "$(grep -c '^first:\|^last:' run.out)" = 2
cd "$work" || exit 0

# ------------------------------------------------------------- rerun
mkdir rerun && cd rerun || exit 0
"$exe" ../decks/first.inp > run1.out 2> run1.err
check rerun_first_run "out/first/summary.txt missing after the first run" test -s out/first/summary.txt
echo stale 2>/dev/null > out/first/stale_marker.txt
"$exe" ../decks/first.inp > run2.out 2> run2.err
check_rc rerun_exit_0 0 $?
check rerun_replaces_folder "out/first/stale_marker.txt survived the rerun (or out/first is missing)" \
  test -d out/first -a ! -e out/first/stale_marker.txt
check rerun_writes_all_files "out/first holds: $(ls -A out/first 2>/dev/null | tr '\n' ' ')" \
  test "$(ls out/first 2>/dev/null | sort | tr '\n' ' ')" = "history.csv listing.txt results.h5 results.xmf summary.txt "
check rerun_no_hidden_folders "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test "$(ls -A out 2>/dev/null)" = first
cd "$work" || exit 0

# ------------------------------------------------------------- check
mkdir checking && cd checking || exit 0
"$exe" check ../decks/sphere_pressure.inp > check.out 2> check.err
check_rc check_exit_0 0 $?
for word in nodes elements half-bandwidth effects; do
  check "check_prints_$word" "stdout: $(first_lines check.out)" grep -q "^ *$word " check.out
done
check check_nodes_match_run "check says nodes '$(sed -n 's/^ *nodes *//p' check.out)', run says '$nnode'" \
  test -n "$nnode" -a "$(sed -n 's/^ *nodes *//p' check.out)" = "$nnode"
check check_writes_nothing "check created: $(ls -A | grep -v '^check\.' | tr '\n' ' ')" \
  test -z "$(ls -A | grep -v '^check\.')"
# ------------------------------------------------------------- dynamic
# A dynamic deck: check names the analysis, theta, the initial velocity and
# the effects; a run writes history and fields with velocity and acceleration.
cd "$work" || exit 0
cat > decks/flight.inp <<'EOF'
TITLE flying block
ANALYSIS DYNAMIC
GEOMETRY AXISYMMETRIC
MATERIAL flesh ELASTIC E=1e6 NU=0.3 RHO=800
MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2
DROP HEIGHT=0.05
GRAVITY
TIME DT=1e-5 TEND=1e-3
OUTPUT EVERY=10 FIELDS=5e-4
END
EOF
"$exe" check decks/flight.inp > checkflight.out 2> checkflight.err
check_rc check_dynamic_exit_0 0 $?
check check_dynamic_analysis "stdout: $(first_lines checkflight.out)" grep -q "^ *analysis *DYNAMIC$" checkflight.out
check check_dynamic_theta "stdout: $(first_lines checkflight.out)" grep -q "^ *Wilson theta *1.4000E+00$" checkflight.out
check check_dynamic_drop_velocity "stdout: $(first_lines checkflight.out)" \
  grep -q "^ *initial v *(0.0000E+00, -9.8995E-01) m/s$" checkflight.out
check check_dynamic_effects "stdout: $(first_lines checkflight.out)" grep -q "^ *effects *inertia gravity$" checkflight.out
check check_dynamic_no_warning "stderr: $(first_lines checkflight.err)" test ! -s checkflight.err
"$exe" -o dynout decks/flight.inp > runflight.out 2> runflight.err
check_rc run_dynamic_exit_0 0 $?
check run_dynamic_history_rows "history.csv has $(wc -l < dynout/flight/history.csv 2>/dev/null) lines" \
  test "$(wc -l < dynout/flight/history.csv)" = 12
check run_dynamic_energy_columns "header: $(head -1 dynout/flight/history.csv)" \
  grep -q "kinetic_J,strain_J,dissipated_J,external_work_J,gravity_work_J,balance_error_J" dynout/flight/history.csv
check run_dynamic_summary_keys "summary: $(first_lines dynout/flight/summary.txt)" \
  grep -q "^factorizations = 1$" dynout/flight/summary.txt
if command -v h5dump > /dev/null; then
  h5dump -n dynout/flight/results.h5 > flight_h5.txt 2>&1
  check run_dynamic_h5_velocity "h5dump: $(first_lines flight_h5.txt)" grep -q "/fields/step_000050/velocity" flight_h5.txt
  check run_dynamic_h5_acceleration "h5dump: $(first_lines flight_h5.txt)" \
    grep -q "/fields/step_000100/acceleration" flight_h5.txt
fi
# THETA < 1.37 and nu = 0.4999: warnings on stderr (check and run), the deck still runs.
sed -e 's/^DROP HEIGHT=0.05$/WILSON THETA=1.2/' -e 's/NU=0.3 /NU=0.4999 /' decks/flight.inp > decks/warned.inp
"$exe" check decks/warned.inp > checkwarned.out 2> checkwarned.err
check_rc check_warned_exit_0 0 $?
check check_warned_theta "stderr: $(first_lines checkwarned.err)" \
  grep -q "^visco2d: warning: decks/warned.inp:6: WILSON: THETA = 1.2 < 1.37" checkwarned.err
check check_warned_locking "stderr: $(first_lines checkwarned.err)" \
  grep -q "^visco2d: warning: decks/warned.inp:4: MATERIAL: material FLESH is nearly incompressible" checkwarned.err
sed -e 's/^DROP HEIGHT=0.05$/WILSON THETA=1.2/' decks/flight.inp > decks/warned_run.inp
"$exe" -q -o dynout decks/warned_run.inp > runwarned.out 2> runwarned.err
check_rc run_warned_exit_0 0 $?
check run_warned_stderr "stderr: $(first_lines runwarned.err)" grep -q "WILSON: THETA = 1.2" runwarned.err
check run_warned_summary "summary: $(first_lines dynout/warned_run/summary.txt)" \
  grep -q "^warnings = 1$" dynout/warned_run/summary.txt
# An unstable run (THETA = 1 far above its stability limit): exit 1, a clear
# message, and no case folder (no NaN written as if it were a result).
cat > decks/unstable.inp <<'EOF'
TITLE linear acceleration method far above its limit
ANALYSIS DYNAMIC
GEOMETRY PLANESTRAIN
MATERIAL m ELASTIC E=1e7 NU=0.25 RHO=1000
MESH RECT R0=0.01 R1=0.0125 Z0=0 Z1=0.1 NR=1 NZ=40
FIX INNER R
FIX OUTER R
FIX BOTTOM Z
PRESSURE TOP P=1e5
WILSON THETA=1.0
TIME DT=1e-4 TEND=0.1
END
EOF
"$exe" -o dynout decks/unstable.inp > unstable.out 2> unstable.err
check_rc run_unstable_exit_1 1 $?
check run_unstable_message "stderr: $(first_lines unstable.err)" \
  grep -q "^visco2d: error: decks/unstable.inp:11: TIME: the time integration is unstable at step" unstable.err
check run_unstable_advice "stderr: $(first_lines unstable.err)" grep -q "THETA >= 1.37" unstable.err
check run_unstable_no_output "dynout has: $(ls -A dynout | tr '\n' ' ')" test ! -e dynout/unstable
check run_unstable_no_partial "dynout has: $(ls -A dynout | tr '\n' ' ')" test -z "$(entries_matching dynout unstable)"
cd "$work/checking" || exit 0

# A quasi-static viscoelastic deck: check names its time axis and its effect.
"$exe" check "$root/inputs/relaxation_step.inp" > checkvisco.out 2> checkvisco.err
check_rc check_quasistatic_exit_0 0 $?
check check_quasistatic_time_steps "stdout: $(first_lines checkvisco.out)" \
  grep -q "^ *time steps *100 in 11 stage(s) to t = " checkvisco.out
check check_quasistatic_effects "stdout: $(first_lines checkvisco.out)" \
  grep -q "^ *effects *viscoelastic$" checkvisco.out
rm -f checkvisco.out checkvisco.err
"$exe" check ../decks/bad.inp > checkbad.out 2> checkbad.err
check_rc check_bad_deck_exit_1 1 $?
check check_bad_deck_located_error "stderr: $(first_lines checkbad.err)" \
  grep -qF '../decks/bad.inp:4:32: MATERIAL: ' checkbad.err
cd "$work" || exit 0

# ------------------------------------------------------------- relax
# visco2d relax: uniaxial Prony series -> exact shear series (eq. [48]).
mkdir relax && cd relax || exit 0
check help_mentions_relax "--help output does not mention 'relax'" grep -q 'visco2d relax' ../usage/help.out
# Numbers with at least 8 significant digits (mantissa d.ddddddd or more).
number='[-+]?[0-9]\.[0-9]{7,}[eE][-+]?[0-9]+'
# Table 4, 0.7 m/s, nu = 0.25: K* = 1.756 MPa (Table 3), four shear terms.
"$exe" relax --nu 0.25 1.703e6 0.000311 0.258e6 0.0401 0.461e6 1.075 0.212e6 34.49 > table4.out 2> table4.err
check_rc relax_table4_exit_0 0 $?
check relax_table4_stderr_empty "stderr: $(first_lines table4.err)" test ! -s table4.err
check relax_table4_k_line "first line: $(head -1 table4.out)" grep -Eq "^K = $number\$" <(head -1 table4.out)
k4=$(sed -n 's/^K = //p' table4.out | awk '{printf "%.3e", $1}')
check relax_table4_k_4_digits "K = $k4, expected 1.756e+06" test "$k4" = 1.756e+06
check relax_table4_four_terms "stdout: $(first_lines table4.out)" \
  test "$(tail -n +2 table4.out | grep -Ec "^$number +$number\$")" = 4 -a "$(wc -l < table4.out)" = 5
# G(0) = sum G_m = 3K E(0)/(9K - E(0)) = 1.0536 MPa (E(0) = 2.634 MPa).
g0=$(tail -n +2 table4.out | awk '{s += $1} END {printf "%.5e", s}')
check relax_table4_initial_value "sum G = $g0, expected 1.05360e+06" test "$g0" = 1.05360e+06
check relax_table4_increasing_beta "stdout: $(first_lines table4.out)" \
  awk 'NR > 1 { n++; if (n > 1 && $2 <= last) bad = 1; last = $2 } END { exit !(n > 0 && !bad) }' table4.out
"$exe" relax --nu=0.25 1.703e6 0.000311 0.258e6 0.0401 0.461e6 1.075 0.212e6 34.49 > equals.out 2> equals.err
check_rc relax_nu_equals_exit_0 0 $?
check relax_nu_equals_same_output "--nu=0.25 and --nu 0.25 differ (or print nothing)" \
  test -s equals.out -a "$(cat equals.out)" = "$(cat table4.out)"
# Elastic limit: one term with alpha = 0 -> G = 3KE/(9K - E) = E/2.5, beta = 0.
"$exe" relax --nu 0.25 2.634e6 0 > elastic.out 2> elastic.err
check_rc relax_elastic_exit_0 0 $?
check relax_elastic_one_term "stdout: $(first_lines elastic.out)" test "$(wc -l < elastic.out)" = 2
check relax_elastic_shear "stdout: $(first_lines elastic.out)" \
  awk 'NR == 2 { ok = ($1 > 1.0536e6 * (1 - 1e-10) && $1 < 1.0536e6 * (1 + 1e-10) && $2 == 0) } END { exit !ok }' \
  elastic.out
# Errors: exit status (2 usage, 1 invalid value), a message naming the
# problem on stderr, nothing on stdout.
relax_error() {  # relax_error NAME STATUS FRAGMENT ARGUMENTS...
  local name=$1 status=$2 fragment=$3
  shift 3
  "$exe" relax "$@" > "$name.out" 2> "$name.err"
  check_rc "relax_${name}_exit_$status" "$status" $?
  check "relax_${name}_message" "stderr: $(first_lines "$name.err")" grep -qF -- "visco2d relax: " "$name.err"
  check "relax_${name}_names_problem" "no '$fragment' in stderr: $(first_lines "$name.err")" \
    grep -qF -- "$fragment" "$name.err"
  check "relax_${name}_stdout_empty" "stdout: $(first_lines "$name.out")" test ! -s "$name.out"
}
relax_error missing_nu 2 '--nu' 1e6 1
relax_error nu_without_value 2 '--nu' 1e6 1 --nu
relax_error odd_count 2 'odd number of values' --nu 0.25 1e6 1 2e6
relax_error no_terms 2 'no terms' --nu 0.25
relax_error not_a_number 2 '"abc"' --nu 0.25 1e6 abc
relax_error nu_not_a_number 2 '"x"' --nu x 1e6 1
relax_error unknown_option 2 '--bogus' --nu 0.25 --bogus 1e6 1
relax_error young_zero 1 'term 2: E must be > 0' --nu 0.25 1e6 1 0 2
relax_error young_negative 1 'term 1: E must be > 0' --nu 0.25 -1e6 1
relax_error alpha_negative 1 'alpha must be >= 0' --nu 0.25 1e6 -1
relax_error nu_half 1 'nu must be in (-1, 0.5)' --nu 0.5 1e6 1
relax_error nu_minus_one 1 'nu must be in (-1, 0.5)' --nu -1 1e6 1
relax_error young_infinite 2 'is not a finite number' --nu 0.25 1e999 1
cd "$work" || exit 0

# ------------------------------------------------------------- paper table
# python/visco2d/paper_table.py: a table beside the paper's numbers from whatever
# summaries exist; missing cases are named, never a crash (exit 0).
mkdir paper && cd paper || exit 0
mkdir -p tabout/table1_elastic
printf 'alpha_max_mm = 1.234500000E+000\nt_alpha_max_ms = 1.5\nq_max_MPa = 2.0\n' \
  > tabout/table1_elastic/summary.txt
python3 -m visco2d.paper_table tabout > table.out 2> table.err
check_rc paper_table_exit_0 0 $?
check paper_table_stderr_empty "stderr: $(first_lines table.err)" test ! -s table.err
check paper_table_paper_row "stdout: $(first_lines table.out)" \
  grep -q '^| paper: dynamic finite element | 1.096 | 1.51 | 1.99 |' table.out
check paper_table_visco2d_value "stdout: $(first_lines table.out)" \
  grep -q '^| \*\*visco2d\*\* (table1_elastic) | 1.234 | 1.500 | 2.000 |' table.out
check paper_table_hertz_constant "stdout: $(first_lines table.out)" grep -q 't_m = 1.4716 alpha_m/V' table.out
check paper_table_names_missing "stdout: $(first_lines table.out)" grep -q '^- apple_v0.7: no ' table.out
python3 -m visco2d.paper_table no_such_folder > empty.out 2> empty.err
check_rc paper_table_no_folder_exit_0 0 $?
check paper_table_no_folder_all_missing "$(grep -c '^- ' empty.out) missing lines, expected 10" \
  test "$(grep -c '^- ' empty.out)" = 10
cd "$work" || exit 0

# ------------------------------------------------------------- contact
# A sphere dropped onto a rigid plate (level 1, tiny): check names the plate,
# the stop criterion and the effects; one card removed at a time turns off
# exactly its effect; a bad PLATE card is located and leaves no folder; a run
# writes the impact keys, the contact history columns and the snapshots at the
# maxima; a run to separation writes the rebound keys.
mkdir contact && cd contact || exit 0
cat > drop.inp <<'EOF'
TITLE apple dropped onto a plate
ANALYSIS DYNAMIC
GEOMETRY AXISYMMETRIC
MATERIAL apple ELASTIC E=40e6 NU=0.3 RHO=800
MESH SPHERE R=0.0381 LEVEL=1
INITIAL VZ=-1
GRAVITY
PLATE Z=0
TIME DT=1e-5 TEND=4e-3
END
EOF
"$exe" check drop.inp > check.out 2> check.err
check_rc contact_check_exit_0 0 $?
check contact_check_plate "stdout: $(first_lines check.out)" \
  grep -q "^ *plate *z = 0.0000E+00 m, STICK, RELEASE=NO$" check.out
check contact_check_stop_at "stdout: $(first_lines check.out)" grep -q "^ *stop at *MAXDEFORMATION$" check.out
check contact_check_effects "stdout: $(first_lines check.out)" \
  grep -q "^ *effects *inertia contact gravity$" check.out
check contact_check_no_warning "stderr: $(first_lines check.err)" test ! -s check.err
check contact_check_writes_nothing "check created: $(ls -A | grep -v -e '^check\.' -e '\.inp$' | tr '\n' ' ')" \
  test -z "$(ls -A | grep -v -e '^check\.' -e '\.inp$')"
# The full scene (viscoelastic) and one card removed at a time.
sed -e 's/^MATERIAL .*/MATERIAL apple VISCOELASTIC K=13.5e6 RHO=757\nPRONY G=3.91e6 BETA=203/' drop.inp > scene_full.inp
grep -v '^PLATE' scene_full.inp > scene_noplate.inp
grep -v '^GRAVITY' scene_full.inp > scene_nogravity.inp
cat > scene_static.inp <<'EOF'
TITLE apple pressed onto a plate
ANALYSIS STATIC
GEOMETRY AXISYMMETRIC
MATERIAL apple ELASTIC E=40e6 NU=0.3 RHO=800
MESH SPHERE R=0.0381 LEVEL=1
GRAVITY G=1000
PLATE Z=0 SLIP
END
EOF
for pair in "full:inertia viscoelastic contact gravity" "noplate:inertia viscoelastic gravity" \
            "nogravity:inertia viscoelastic contact" "static:contact gravity"; do
  name=${pair%%:*}
  effects=${pair#*:}
  "$exe" check "scene_$name.inp" > "scene_$name.out" 2>&1
  check "contact_check_effects_$name" "expected effects '$effects'; output: $(first_lines "scene_$name.out")" \
    grep -q "^ *effects *$effects\$" "scene_$name.out"
done
check contact_check_static_no_stop_line "stdout: $(first_lines scene_static.out)" \
  test "$(grep -c '^ *stop at ' scene_static.out)" = 0
# A bad PLATE card: Z is not a number (line 8, the Z field at column 7).
sed -e 's/^PLATE Z=0$/PLATE Z=abc/' drop.inp > badplate.inp
"$exe" -o out badplate.inp > badplate.out 2> badplate.err
check_rc contact_bad_plate_exit_1 1 $?
check contact_bad_plate_located "stderr: $(first_lines badplate.err)" \
  grep -qF 'visco2d: error: badplate.inp:8:7: PLATE: Z must be a number, got "abc"' badplate.err
check contact_bad_plate_no_case_folder "out/badplate exists" test ! -e out/badplate
check contact_bad_plate_no_hidden_folder "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test -z "$(entries_matching out badplate)"
"$exe" check badplate.inp > checkbadplate.out 2> checkbadplate.err
check_rc contact_check_bad_plate_exit_1 1 $?
check contact_check_bad_plate_located "stderr: $(first_lines checkbadplate.err)" \
  grep -qF 'badplate.inp:8:7: PLATE: ' checkbadplate.err
# A plate above the sphere's pole (z = 0): located at the PLATE card, no folder.
sed -e 's/^PLATE Z=0$/PLATE Z=0.001/' drop.inp > cutplate.inp
"$exe" -o out cutplate.inp > cutplate.out 2> cutplate.err
check_rc contact_plate_cuts_body_exit_1 1 $?
check contact_plate_cuts_body_located "stderr: $(first_lines cutplate.err)" \
  grep -q '^visco2d: error: cutplate.inp:8:7: PLATE: node [0-9]* (.*) lies below the plate' cutplate.err
check contact_plate_cuts_body_no_folder "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test -z "$(entries_matching out cutplate)"

# The impact run (STOP AT=MAXDEFORMATION by default).
"$exe" -q -o out drop.inp > drop.out 2> drop.err
check_rc contact_run_exit_0 0 $?
check contact_run_stderr_empty "stderr: $(first_lines drop.err)" test ! -s drop.err
summary=out/drop/summary.txt
for key in alpha_max_mm q_max_MPa force_max_N contact_radius_max_mm accel_center_max_g effects cpu_s \
           t_alpha_max_ms stop_reason hertz_alpha_max_mm; do
  check "contact_run_summary_has_$key" "no '$key = ' line in $summary" grep -qs "^$key = " "$summary"
done
check contact_run_summary_effects "effects = '$(value_of effects)'" test "$(value_of effects)" = "inertia contact gravity"
check contact_run_stop_reason "stop_reason = '$(value_of stop_reason)'" \
  test "$(value_of stop_reason)" = "maximum deformation"
check contact_run_no_separation_keys "separation keys in a run stopped at maximum deformation" \
  test "$(grep -c -e '^contact_duration_ms = ' -e '^coefficient_of_restitution = ' "$summary")" = 0
header=$(head -1 out/drop/history.csv 2>/dev/null)
for column in t_ms alpha_mm force_N q_MPa contact_radius_mm accel_center_g n_contact; do
  check "contact_run_history_has_$column" "header: $header" grep -q "\(^\|,\)$column\(,\|$\)" <<< "$header"
done
h5=out/drop/results.h5
if command -v h5dump > /dev/null; then
  h5dump -A -g /fields "$h5" > drop_fields.txt 2>&1
  check_rc contact_h5dump_fields 0 $?
  for label in "maximum deformation" "maximum pressure"; do
    check "contact_h5_label_${label// /_}" \
      "no /fields/<step> with label '$label': $(grep '(0): "' drop_fields.txt | tr '\n' ' ')" \
      grep -q "(0): \"\(.*; \)\?$label\(;.*\)\?\"" drop_fields.txt
  done
else
  fail contact_h5dump_available "h5dump is not on PATH"
fi
if command -v python3 > /dev/null && python3 -c 'import h5py' > /dev/null 2>&1; then
  # The snapshot labelled 'maximum deformation' is taken at t_alpha_max (first contact at t = 0 here).
  python3 - "$h5" > drop_h5py.out 2> drop_h5py.err <<'EOF'
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    for name, group in f["/fields"].items():
        label = group.attrs["label"]
        label = label.decode() if isinstance(label, bytes) else str(label)
        if "maximum deformation" in label.split("; "):
            print("t_ms %.9e" % (1000.0 * float(group.attrs["time"])))
            print("has_stress", "stress" in group)
EOF
  check_rc contact_h5py_reads 0 $?
  t_snap=$(sed -n 's/^t_ms //p' drop_h5py.out)
  t_key=$(value_of t_alpha_max_step_ms)     # the step of the largest sample (t_alpha_max_ms is between steps)
  check contact_h5_max_deformation_time "snapshot at '$t_snap' ms, t_alpha_max_step_ms = '$t_key'" \
    awk -v a="$t_snap" -v b="$t_key" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && b != "" && d <= 1e-6) }'
  check contact_h5_max_deformation_stress "h5py: $(first_lines drop_h5py.out)" grep -q '^has_stress True$' drop_h5py.out
else
  echo "# h5py not available: h5py contact checks skipped"
fi

# To separation: SLIP RELEASE=YES STOP AT=SEPARATION (Hertz duration ~2.4 ms < TEND).
sed -e 's/^PLATE Z=0$/PLATE Z=0 SLIP RELEASE=YES\nSTOP AT=SEPARATION/' drop.inp > bounce.inp
"$exe" check bounce.inp > checkbounce.out 2>&1
check contact_check_separation_stop_at "stdout: $(first_lines checkbounce.out)" \
  grep -q "^ *stop at *SEPARATION$" checkbounce.out
check contact_check_separation_plate "stdout: $(first_lines checkbounce.out)" \
  grep -q "^ *plate *z = 0.0000E+00 m, SLIP, RELEASE=YES$" checkbounce.out
"$exe" -q -o out bounce.inp > bounce.out 2> bounce.err
check_rc contact_separation_exit_0 0 $?
summary=out/bounce/summary.txt
check contact_separation_stop_reason "stop_reason = '$(value_of stop_reason)'; stderr: $(first_lines bounce.err)" \
  test "$(value_of stop_reason)" = separation
for key in contact_duration_ms rebound_velocity_m_s energy_absorbed_J coefficient_of_restitution; do
  check "contact_separation_has_$key" "no '$key = ' line in $summary" grep -qs "^$key = " "$summary"
done
# Their definitions, from the summary's own values (10 digits): e = v_out/V_in,
# energy absorbed = 1/2 M (V_in^2 - v_out^2) with the whole-body mass.
check contact_separation_restitution_definition \
  "e = $(value_of coefficient_of_restitution), v_out = $(value_of rebound_velocity_m_s), V_in = $(value_of impact_velocity_m_s)" \
  awk -v e="$(value_of coefficient_of_restitution)" -v v="$(value_of rebound_velocity_m_s)" \
      -v w="$(value_of impact_velocity_m_s)" \
      'BEGIN { if (e == "" || w + 0 == 0) exit 1; d = e - v / w; if (d < 0) d = -d; exit !(d <= 1e-8) }'
check contact_separation_energy_definition \
  "energy_absorbed_J = $(value_of energy_absorbed_J), M = $(value_of body_mass_kg)" \
  awk -v q="$(value_of energy_absorbed_J)" -v m="$(value_of body_mass_kg)" -v v="$(value_of rebound_velocity_m_s)" \
      -v w="$(value_of impact_velocity_m_s)" \
      'BEGIN { x = 0.5 * m * (w * w - v * v); if (q == "" || x == 0) exit 1; d = (q - x) / x; if (d < 0) d = -d; exit !(d <= 1e-6) }'
cd "$work" || exit 0

# ------------------------------------------------------------- results.h5 and results.xmf
# /summary holds one scalar dataset per summary.txt key, typed: a number (with
# its units) where the text is a number, a real in full precision that rounds
# to summary.txt's text at its digits, the text otherwise; snapshots carry both
# time bases (deck time, time from first contact); results.xmf (XDMF 3) read
# back with meshio gives the mesh, every snapshot, its time and its fields as
# results.h5 read with h5py (vectors with a third component 0, the stress as a
# 3x3 tensor; ParaView's readers: scripts/test_xdmf.sh); pressure.csv (p(r) at the largest force and
# approach) agrees with the history and with /pressure. A drop with a 0.5 mm
# gap (first contact at t > 0) and the static sphere (no contact, no time
# from contact, no pressure.csv).
mkdir xdmf && cd xdmf || exit 0
sed -e 's/^PLATE Z=0$/PLATE Z=-0.0005/' -e 's/^TIME .*/OUTPUT EVERY=1 FIELDS=2e-4\nTIME DT=1e-5 TEND=4e-3/' \
  ../contact/drop.inp > gap.inp
cp "$good_source" sphere.inp
"$exe" -q -o out gap.inp sphere.inp > gap.out 2> gap.err
check_rc xdmf_runs_exit_0 0 $?
for case in gap sphere; do
  check "xdmf_${case}_written" "out/$case/results.xmf missing or empty" test -s "out/$case/results.xmf"
done
if command -v python3 > /dev/null && python3 -c 'import h5py, meshio' > /dev/null 2>&1; then
  python3 - out > xdmf_py.out 2> xdmf_py.err <<'EOF'
import os, re, sys
import h5py, meshio, numpy as np

NUMBER = re.compile(r'^[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?$')


def report(name, ok, detail=""):
    print(f"PASS {name}" if ok else f"FAIL {name}: {detail}")


def shown_as(stored, text):
    # a /summary number is what summary.txt shows, rounded to the text's digits
    # (a real there has 10 significant digits, the CPU time 4; an integer is exact)
    value = float(text.replace("d", "e").replace("D", "e"))
    mantissa, _, exponent = text.upper().replace("D", "E").partition("E")
    if not exponent:
        return float(stored) == value
    digits = len(mantissa.lstrip("+-").replace(".", "")) - 1
    shown, _, power = f"{float(stored):.{digits}E}".partition("E")
    return float(shown) == float(mantissa) and int(power) == int(exponent)


def summary_text(path):
    items = {}
    with open(path) as f:
        for line in f:
            key, _, value = line.rstrip("\n").partition(" = ")
            items[key] = value
    return items


def check_summary(case, folder, f):
    text = summary_text(os.path.join(folder, "summary.txt"))
    group = f["/summary"]
    report(f"h5_summary_keys_{case}", set(group) == set(text),
           f"only in h5: {sorted(set(group) - set(text))[:5]}, only in txt: {sorted(set(text) - set(group))[:5]}")
    bad = []
    for key, value in text.items():
        if key not in group:
            continue
        item = group[key]
        stored = item[()]
        if NUMBER.match(value):
            if item.dtype.kind not in "iuf" or not shown_as(stored, value) or "units" not in item.attrs:
                bad.append(f"{key}: {stored!r} ({item.dtype}) for '{value}'")
        elif item.dtype.kind != "S" or stored.decode() != value:
            bad.append(f"{key}: {stored!r} for '{value}'")
    report(f"h5_summary_values_{case}", not bad, "; ".join(bad[:3]))
    return text


def units(f, key):
    value = f["/summary"][key].attrs.get("units", b"")
    return value.decode() if isinstance(value, bytes) else str(value)


def xdmf_view(group, field):
    # what results.xmf shows of a /fields dataset: vectors (u_r, u_z, 0), the
    # stress as the 3x3 tensor row by row (doc/outputs.md, results.xmf)
    values = group[field][()]
    zero = np.zeros(len(values))
    if field in ("displacement", "velocity", "acceleration"):
        return np.column_stack([values, zero])
    if field == "stress":
        s = values
        return np.column_stack([s[:, 0], s[:, 3], zero, s[:, 3], s[:, 1], zero, zero, zero, s[:, 2]])
    return values


def check_xdmf(case, folder, f):
    names = sorted(f["/fields"])
    times = [float(f["/fields"][name].attrs["time"]) for name in names]
    with meshio.xdmf.TimeSeriesReader(os.path.join(folder, "results.xmf")) as reader:
        points, cells = reader.read_points_cells()
        report(f"xdmf_nodes_{case}", np.array_equal(points, f["/mesh/nodes"][()]),
               f"points {points.shape} vs /mesh/nodes {f['/mesh/nodes'].shape}")
        elements = f["/mesh/elements"][()] - 1
        report(f"xdmf_quads_{case}", len(cells) == 1 and cells[0].type == "quad"
               and np.array_equal(cells[0].data, elements), f"{[(c.type, c.data.shape) for c in cells]}")
        report(f"xdmf_snapshot_count_{case}", reader.num_steps == len(names),
               f"{reader.num_steps} grids, {len(names)} /fields groups")
        got_times, field_bad = [], []
        for k in range(min(reader.num_steps, len(names))):
            t, point_data, cell_data = reader.read_data(k)
            got_times.append(t)
            group = f["/fields"][names[k]]
            for field in ("displacement", "velocity", "acceleration", "stress", "max_shear", "von_mises"):
                if (field in group) != (field in point_data):
                    field_bad.append(f"{names[k]}/{field}: in h5 {field in group}, in xdmf {field in point_data}")
                elif field in group and not np.array_equal(point_data[field], xdmf_view(group, field)):
                    field_bad.append(f"{names[k]}/{field} differs")
            material = cell_data.get("material", [None])[0]
            if material is None or not np.array_equal(material, f["/mesh/element_material"][()]):
                field_bad.append(f"{names[k]}: cell data 'material' missing or different")
        report(f"xdmf_times_{case}", got_times == times, f"xdmf {got_times[:4]}, h5 {times[:4]}")
        report(f"xdmf_fields_{case}", not field_bad, "; ".join(field_bad[:3]))
    return names


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
        rows = [[float(v) for v in line.split(",")] for line in f if line.strip()]
    return header, np.array(rows)


def check_pressure(folder, f, text):
    # p(r) at the largest force and the largest sampled approach: the pole's
    # row is the history's q_MPa at t_force_max_ms and at t_alpha_max_step_ms
    # (the same doubles, both printed with 10 digits: equal as numbers).
    header, rows = read_csv(os.path.join(folder, "pressure.csv"))
    expected = ["node", "r_mm", "r_force_max_mm", "p_force_max_MPa", "r_alpha_max_mm", "p_alpha_max_MPa",
                "reaction_z_force_max_ring_N", "reaction_z_alpha_max_ring_N"]
    report("pressure_csv_header", header == expected, f"{header}")
    if header != expected or rows.ndim != 2:
        return
    column = {name: rows[:, k] for k, name in enumerate(header)}
    report("pressure_rows_every_contact_node", len(rows) >= int(text["contact_nodes_max"]) > 0,
           f"{len(rows)} rows, contact_nodes_max = {text['contact_nodes_max']}")
    report("pressure_rows_by_radius", column["r_mm"][0] == 0 and np.all(np.diff(column["r_mm"]) > 0),
           f"r_mm = {column['r_mm']}")
    names, history = read_csv(os.path.join(folder, "history.csv"))
    t_ms, q_MPa, force = (history[:, names.index(n)] for n in ("t_ms", "q_MPa", "force_N"))
    for instant, key in (("force_max", "t_force_max_ms"), ("alpha_max", "t_alpha_max_step_ms")):
        rows_at = np.flatnonzero(t_ms == float(text[key]))
        ok = len(rows_at) == 1 and q_MPa[rows_at[0]] == column[f"p_{instant}_MPa"][0]
        report(f"pressure_{instant}_pole_is_history_q", ok,
               f"{key} = {text[key]}: history rows {rows_at}, q_MPa {q_MPa[rows_at]}, "
               f"pole p {column[f'p_{instant}_MPa'][0]}")
        if instant == "force_max" and len(rows_at) == 1:
            report("pressure_force_max_at_largest_force", force[rows_at[0]] == float(text["force_max_N"]),
                   f"force_N {force[rows_at[0]]}, force_max_N {text['force_max_N']}")
        # The nodal plate reactions (whole ring) sum to the plate force at that
        # instant (force_max_N; force_N of the history row at alpha max): the
        # same sum as the code's, each term printed to 10 significant digits
        # (es17.9, relative rounding <= 5e-10), so 1e-9 of the sum of |terms|.
        reaction = column[f"reaction_z_{instant}_ring_N"]
        if len(rows_at) == 1:
            reference = float(text["force_max_N"]) if instant == "force_max" else force[rows_at[0]]
            report(f"pressure_reactions_sum_to_force_{instant}",
                   reference > 0 and abs(reaction.sum() - reference) <= 1e-9 * np.abs(reaction).sum(),
                   f"sum of reaction_z_{instant}_ring_N = {reaction.sum()!r}, plate force {reference!r}")
    stored = {name: f["/pressure"][name][()] for name in f["/pressure"]} if "pressure" in f else {}
    bad = [name for name in expected if name not in stored
           or not np.allclose(stored[name], column[name], rtol=1e-9, atol=0)]
    report("pressure_h5_is_csv", not bad, f"columns differing or missing in /pressure: {bad}")
    report("pressure_h5_units", stored and f["/pressure/p_force_max_MPa"].attrs["units"] == b"MPa"
           and f["/pressure/r_mm"].attrs["units"] == b"mm", "units of /pressure datasets")


out = sys.argv[1]
for case in ("gap", "sphere"):
    folder = os.path.join(out, case)
    with h5py.File(os.path.join(folder, "results.h5"), "r") as f:
        text = check_summary(case, folder, f)
        names = check_xdmf(case, folder, f)
        groups = [f["/fields"][name] for name in names]
        if case == "gap":
            expected = {"alpha_max_mm": "mm", "body_mass_kg": "kg", "t_alpha_max_ms": "ms", "nodes": "1",
                        "impact_velocity_m_s": "m/s", "force_max_N": "N"}
            got = {key: units(f, key) for key in expected}
            report("h5_summary_units", got == expected, f"{got}")
            report("h5_summary_integer", f["/summary/nodes"].dtype.kind == "i", f"nodes: {f['/summary/nodes'].dtype}")
            report("h5_summary_real_is_double", f["/summary/alpha_max_mm"].dtype == np.float64,
                   f"alpha_max_mm: {f['/summary/alpha_max_mm'].dtype}")
            report("h5_summary_text_stays_text", f["/summary/stop_reason"][()] == b"maximum deformation",
                   f"stop_reason: {f['/summary/stop_reason'][()]!r}")
            contact = float(text["time_first_contact_s"])
            report("h5_first_contact_after_start", 4e-4 < contact < 6e-4, f"time_first_contact_s = {contact}")
            exact = float(f["/summary/time_first_contact_s"][()])   # full precision (summary.txt: 10 digits)
            report("h5_first_contact_is_summary_txt", abs(exact - contact) <= 5e-10 * contact,
                   f"{exact!r} in /summary, {contact!r} in summary.txt")
            worst = max(abs(g.attrs["time_from_contact"] - (g.attrs["time"] - exact)) for g in groups)
            report("h5_time_from_contact", worst <= 1e-15, f"largest |difference| {worst} s")
            before = [g.attrs["time_from_contact"] for g in groups if g.attrs["time"] < contact]
            report("h5_time_from_contact_negative_before", len(before) >= 2 and max(before) < 0,
                   f"before contact: {before}")
            check_pressure(folder, f, text)
        else:
            report("h5_no_time_from_contact_without_contact",
                   all("time_from_contact" not in g.attrs for g in groups), "a snapshot has time_from_contact")
            report("pressure_none_without_plate", "pressure" not in f
                   and not os.path.exists(os.path.join(folder, "pressure.csv")), "pressure.csv or /pressure written")
EOF
  status=$?
  cat xdmf_py.out
  check_rc xdmf_python_check_ran "0" "$status"
  [ "$status" = 0 ] || echo "# $(first_lines xdmf_py.err)"
else
  echo "# h5py or meshio not available: results.h5 /summary and XDMF checks skipped"
fi
cd "$work" || exit 0

# ------------------------------------------------------------- progress
# Progress of long runs on stderr: `visco2d: <case>: step N, t = X ms[, alpha = Y mm], ~Z s left`,
# a last `..., done in W s` line. VISCO2D_PROGRESS_DELAY=0 shows it from the
# first step (runs here are far shorter than the default 2 s). By default it
# shows only on a terminal; --progress forces it (whole lines when stderr is
# not a terminal); -q turns it off unless --progress is given (either order).
mkdir progress && cd progress || exit 0
cp ../contact/drop.inp drop.inp
progress_line='^visco2d: drop: step [0-9][0-9]*, t = [0-9][0-9.]* ms, alpha = [0-9][0-9.]* mm, ~\([0-9][0-9.]*\|?\) s left$'
done_line='^visco2d: drop: step [0-9][0-9]*, t = [0-9][0-9.]* ms, alpha = [0-9][0-9.]* mm, done in [0-9][0-9.]* s$'
VISCO2D_PROGRESS_DELAY=0 "$exe" --progress -o out drop.inp > forced.out 2> forced.err
check_rc progress_forced_exit_0 0 $?
check progress_forced_lines "stderr: $(first_lines forced.err)" grep -q "$progress_line" forced.err
check progress_forced_done_last "last stderr line: $(tail -1 forced.err)" grep -q "$done_line" <(tail -1 forced.err)
check progress_forced_whole_lines "a carriage return in stderr: $(first_lines forced.err | cat -A | head -c 200)" \
  test "$(tr -cd '\r' < forced.err | wc -c)" = 0
check progress_forced_only_progress "other stderr lines: $(grep -v -e "$progress_line" -e "$done_line" forced.err | head -3 | tr '\n' '|')" \
  test -z "$(grep -v -e "$progress_line" -e "$done_line" forced.err)"
check progress_forced_stdout_result "stdout: $(first_lines forced.out)" grep -q '^drop:' forced.out
# The step and time of the done line are the run's last: summary steps and time_end_s.
steps=$(sed -n 's/^steps = //p' out/drop/summary.txt 2>/dev/null)
check progress_done_step_is_last "done line: $(tail -1 forced.err); summary steps = '$steps'" \
  grep -q "^visco2d: drop: step $steps, " <(tail -1 forced.err)
for order in "-q --progress" "--progress -q"; do
  name="progress_quiet_forced_${order// /_}"
  name=${name//-/}
  # shellcheck disable=SC2086
  VISCO2D_PROGRESS_DELAY=0 "$exe" $order -o out drop.inp > "$name.out" 2> "$name.err"
  check_rc "${name}_exit_0" 0 $?
  check "${name}_shows" "visco2d $order: stderr: $(first_lines "$name.err")" grep -q "$done_line" "$name.err"
  check "${name}_stdout_empty" "stdout: $(first_lines "$name.out")" test ! -s "$name.out"
done
# Default (auto) with stderr into a file: quiet, even with no delay.
VISCO2D_PROGRESS_DELAY=0 "$exe" -o out drop.inp > auto.out 2> auto.err
check_rc progress_auto_file_exit_0 0 $?
check progress_auto_file_quiet "stderr: $(first_lines auto.err)" test ! -s auto.err
# Forced on, default delay (2 s): a run this short stays silent.
"$exe" --progress -o out drop.inp > short.out 2> short.err
check_rc progress_short_run_exit_0 0 $?
check progress_short_run_quiet "stderr: $(first_lines short.err)" test ! -s short.err
# A delay that is not a number: a warning, the default delay, the run goes on.
VISCO2D_PROGRESS_DELAY=soon "$exe" --progress -o out drop.inp > baddelay.out 2> baddelay.err
check_rc progress_bad_delay_exit_0 0 $?
check progress_bad_delay_warns "stderr: $(first_lines baddelay.err)" \
  grep -q '^visco2d: warning: VISCO2D_PROGRESS_DELAY="soon" is not a number' baddelay.err
check progress_bad_delay_default "stderr: $(first_lines baddelay.err)" test "$(grep -c 'drop: step' baddelay.err)" = 0
check progress_help "--help does not mention --progress" grep -q -- '--progress' ../usage/help.out
check progress_help_delay "--help does not mention VISCO2D_PROGRESS_DELAY" grep -q VISCO2D_PROGRESS_DELAY ../usage/help.out
# On a terminal (a pseudo-terminal from util-linux `script`; stdout and stderr
# both go to it): one line overwritten in place with carriage returns, so the
# estimate and the done line share a line; -q turns it off there.
if command -v script > /dev/null && script -qefc true /dev/null > /dev/null 2>&1; then
  VISCO2D_PROGRESS_DELAY=0 script -qefc "'$exe' -o out drop.inp" /dev/null > tty.out 2> tty.err
  check_rc progress_tty_exit_0 0 $?
  check progress_tty_overwrites "terminal output: $(head -c 300 tty.out | cat -A)" \
    grep -q $'\rvisco2d: drop: step [0-9]*, .* s left *\rvisco2d: drop: step [0-9]*, .*done in [0-9.]* s' tty.out
  check progress_tty_result "terminal output: $(head -c 300 tty.out | cat -A)" grep -q '^drop:' tty.out
  VISCO2D_PROGRESS_DELAY=0 script -qefc "'$exe' -q -o out drop.inp" /dev/null > ttyq.out 2> ttyq.err
  check_rc progress_tty_quiet_exit_0 0 $?
  check progress_tty_quiet_silent "terminal output: $(head -c 300 ttyq.out | cat -A)" test ! -s ttyq.out
else
  echo "# script (util-linux) cannot make a terminal here: terminal progress checks skipped"
fi
cd "$work" || exit 0

# ------------------------------------------------------------- output root
# The output root is checked before any deck runs: an empty name, a path
# through a file, or a folder that cannot be made are refused with exit
# status 2 (as for usage errors) and nothing is written anywhere.
mkdir outroot && cd outroot || exit 0
"$exe" -o "" ../decks/first.inp > empty.out 2> empty.err
check_rc out_root_empty_exit_2 2 $?
check out_root_empty_message "stderr: $(first_lines empty.err)" grep -q 'output folder given with -o is empty' empty.err
check out_root_empty_nothing_at_root "/ holds: $(ls -A / | grep -F 'first' | tr '\n' ' ')" \
  test -z "$(ls -A / 2>/dev/null | grep -F '.first.')"
echo plain > plainfile
"$exe" -o plainfile/sub ../decks/first.inp > through.out 2> through.err
check_rc out_root_through_file_exit_2 2 $?
check out_root_through_file_message "stderr: $(first_lines through.err)" grep -q '"plainfile/sub": plainfile is not a folder' through.err
check out_root_through_file_untouched "plainfile changed" test "$(cat plainfile)" = plain
"$exe" -o plainfile ../decks/first.inp > isfile.out 2> isfile.err
check_rc out_root_is_file_exit_2 2 $?
# /proc accepts no new folder, not even from root (a read-only place that works in CI).
if [ -d /proc/self ]; then
  "$exe" -o "/proc/visco2d_cli_$$" ../decks/first.inp > proc.out 2> proc.err
  check_rc out_root_unwritable_exit_2 2 $?
  check out_root_unwritable_message "stderr: $(first_lines proc.err)" \
    grep -qF "visco2d: error: the output folder \"/proc/visco2d_cli_$$\" cannot be created" proc.err
fi
if [ "$(id -u)" != 0 ]; then                # permissions do not stop root
  mkdir locked && chmod 555 locked
  "$exe" -o locked/out ../decks/first.inp > locked.out 2> locked.err
  check_rc out_root_read_only_exit_2 2 $?
  chmod 755 locked
fi
# The root is not created before a deck succeeds: a failing deck leaves no folder at all.
"$exe" -o fresh ../decks/bad.inp > fresh.out 2> fresh.err
check_rc out_root_failed_deck_exit_1 1 $?
check out_root_failed_deck_no_root "fresh/ was created: $(ls -A fresh 2>/dev/null | tr '\n' ' ')" test ! -e fresh
# check never writes, so it does not look at -o.
"$exe" check -o "" ../decks/first.inp > checkempty.out 2> checkempty.err
check_rc out_root_check_ignores_root 0 $?
cd "$work" || exit 0

# ------------------------------------------------------------- write faults
# A full disk part-way through the outputs: a file size limit (ulimit -f, in
# kB) makes writes past it fail (visco2d ignores SIGXFSZ; `trap '' XFSZ` too).
# Each file in turn: a located error naming the file, exit 1 (never a crash),
# no case folder and no partial folder. free_flight writes summary.txt 2.6 kB,
# history.csv 11 kB, listing.txt 28 kB, results.h5 136 kB (results.xmf, 6.5 kB, is
# smaller than results.h5 and written after it: a per-file limit cannot reach it alone).
mkdir faults && cd faults || exit 0
cp "$root/inputs/free_flight.inp" free_flight.inp
for pair in 2:summary.txt 16:listing.txt 64:results.h5; do
  limit=${pair%%:*}
  file=${pair#*:}
  (ulimit -f "$limit"; trap '' XFSZ; exec "$exe" -q -o "full$limit" free_flight.inp) > "full$limit.out" 2> "full$limit.err"
  status=$?
  check_rc "disk_full_${file}_exit_1" 1 $status
  check "disk_full_${file}_located" "stderr: $(first_lines "full$limit.err")" \
    grep -qF "visco2d: error: free_flight.inp: cannot write full$limit/free_flight/$file: " "full$limit.err"
  check "disk_full_${file}_one_line" "stderr: $(first_lines "full$limit.err")" \
    test "$(wc -l < "full$limit.err")" = 1
  check "disk_full_${file}_no_folder" "full$limit holds: $(ls -A "full$limit" 2>/dev/null | tr '\n' ' ')" \
    test -z "$(ls -A "full$limit" 2>/dev/null)"
done
# Unlimited, the same run writes all five files (the limits above were the cause).
"$exe" -q -o fine free_flight.inp > fine.out 2> fine.err
check_rc disk_unlimited_exit_0 0 $?
check disk_unlimited_results "fine/free_flight holds: $(ls fine/free_flight 2>/dev/null | tr '\n' ' ')" \
  test "$(ls fine/free_flight 2>/dev/null | sort | tr '\n' ' ')" = "history.csv listing.txt results.h5 results.xmf summary.txt "
# A failed rewrite keeps the previous case folder as it was.
cp fine/free_flight/summary.txt previous_summary.txt
(ulimit -f 64; exec "$exe" -q -o fine free_flight.inp) > refull.out 2> refull.err
check_rc disk_full_rerun_exit_1 1 $?
check disk_full_rerun_keeps_previous "fine/free_flight/summary.txt changed or missing" \
  cmp -s previous_summary.txt fine/free_flight/summary.txt
check disk_full_rerun_no_partial "fine holds: $(ls -A fine | tr '\n' ' ')" test "$(ls -A fine)" = free_flight
cd "$work" || exit 0

# ------------------------------------------------------------- stale folders
# A run stopped while writing leaves OUT/.<case>.partial.<pid>/ (and, when it
# was replacing a case folder, OUT/.<case>.old.<pid>/). The next run into the
# same root removes those of processes that no longer exist, puts back an old
# folder whose case folder is missing, and keeps those of live processes.
mkdir stale && cd stale || exit 0
sh -c 'exit 0' & dead=$!
wait "$dead"
mkdir -p "out/.first.partial.$dead" "out/.last.partial.$dead" "out/.kept.old.$dead" "out/.other.old.$dead" \
  out/other "out/.first.partial.1" "out/.first.partial.$$"
echo half > "out/.first.partial.$dead/summary.txt"
echo previous > "out/.kept.old.$dead/summary.txt"
"$exe" -q -o out ../decks/first.inp > stale.out 2> stale.err
check_rc stale_run_exit_0 0 $?
check stale_dead_partial_removed "out holds: $(ls -A out | tr '\n' ' ')" \
  test ! -e "out/.first.partial.$dead" -a ! -e "out/.last.partial.$dead"
check stale_dead_old_put_back "out/kept/summary.txt: $(cat out/kept/summary.txt 2>/dev/null)" \
  test "$(cat out/kept/summary.txt 2>/dev/null)" = previous
check stale_dead_old_removed_beside_case "out holds: $(ls -A out | tr '\n' ' ')" \
  test ! -e "out/.other.old.$dead" -a -d out/other
check stale_live_partials_kept "out holds: $(ls -A out | tr '\n' ' ')" \
  test -d out/.first.partial.1 -a -d "out/.first.partial.$$"
check stale_notes "stderr: $(first_lines stale.err)" \
  test "$(grep -c "^visco2d: note: .*(left by process $dead on host [^ ]*, which no longer runs)$" stale.err)" = 4
check stale_run_result "out/first/summary.txt missing" test -s out/first/summary.txt
cd "$work" || exit 0

# ------------------------------------------------------------- non-finite results
# No NaN or Infinity reaches an output: a deck whose result is not finite
# (a modulus at the edge of double precision: refused by the deck checks or
# by the last check before writing) fails with an error naming the deck, exit 1, no folder.
mkdir nonfinite && cd nonfinite || exit 0
sed -e 's/E=200e9/E=1e308/' ../decks/first.inp > huge.inp
"$exe" -o out huge.inp > huge.out 2> huge.err
check_rc non_finite_exit_1 1 $?
check non_finite_names_deck "stderr: $(first_lines huge.err)" grep -q '^visco2d: error: huge\.inp:[0-9]' huge.err
check non_finite_no_folder "out holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" test -z "$(ls -A out 2>/dev/null)"
check non_finite_stdout_empty "stdout: $(first_lines huge.out)" test ! -s huge.out
cd "$work" || exit 0

# ------------------------------------------------------------- EXPECT
# One check per EXPECT card (run line "EXPECT k/n"); an expected 0 or a
# second card for a key is refused at the card, before solving. A deck that
# misses one of its own EXPECT cards writes its results and exits 3 (it
# exited 0), the miss located on stderr; in a batch, 1 (a deck failed) wins.
mkdir expect && cd expect || exit 0
"$exe" -q -o out ../decks/first.inp > /dev/null 2>&1
value_in() { sed -n "s/^$1 = //p" out/first/summary.txt 2>/dev/null | head -1; }
u=$(value_in max_displacement_m); w=$(value_in strain_energy_J)
{ cat ../decks/first.inp | grep -v '^END'
  echo "EXPECT max_displacement_m $u RTOL=1e-6"
  echo "EXPECT strain_energy_J $w RTOL=1e-6"
  echo "EXPECT external_work_J 1.0 RTOL=1e-6"
  echo END; } > three.inp
"$exe" -o out three.inp > three.out 2> three.err
check_rc expect_missed_exit_3 3 $?
check expect_counts_cards "stdout: $(first_lines three.out)" grep -q '; EXPECT 2/3 within RTOL (worst rel. error ' three.out
check expect_missed_located "stderr: $(first_lines three.err)" \
  grep -q '^visco2d: error: three\.inp:10:24: EXPECT: external_work_J = .* is not within RTOL = 1.0E-06 of the expected 1.0 ' three.err
check expect_missed_results_written "no out/three/summary.txt" test -s out/three/summary.txt
check expect_missed_in_summary "out/three/summary.txt" grep -q '^expect_external_work_J_within_rtol = no$' out/three/summary.txt
grep -v '^EXPECT external_work_J' three.inp > two.inp
"$exe" -q -o out two.inp > two.out 2> two.err
check_rc expect_met_exit_0 0 $?
"$exe" -q -o out two.inp three.inp > pair.out 2> pair.err
check_rc expect_batch_with_a_miss_exit_3 3 $?
check expect_batch_miss_counted "stderr: $(first_lines pair.err)" \
  grep -q '^visco2d: 1 of 2 decks missed their own EXPECT cards' pair.err
"$exe" -q -o out three.inp ../decks/missing_file.inp > mixed.out 2> mixed.err
check_rc expect_batch_failure_wins_exit_1 1 $?
sed -e "s/^EXPECT strain_energy_J .*/EXPECT strain_energy_J 0/" three.inp > zero.inp
"$exe" -o out zero.inp > zero.out 2> zero.err
check_rc expect_zero_exit_1 1 $?
check expect_zero_located "stderr: $(first_lines zero.err)" \
  grep -q '^visco2d: error: zero\.inp:9:24: EXPECT: expected value must be nonzero' zero.err
"$exe" check zero.inp > checkzero.out 2> checkzero.err
check_rc expect_zero_check_exit_1 1 $?
sed -e "s/^EXPECT external_work_J .*/EXPECT max_displacement_m 1.0/" three.inp > twice.inp
"$exe" -o out twice.inp > twice.out 2> twice.err
check_rc expect_twice_exit_1 1 $?
check expect_twice_located "stderr: $(first_lines twice.err)" \
  grep -q '^visco2d: error: twice\.inp:10:8: EXPECT: key max_displacement_m is already expected on line 8' twice.err
check expect_no_nan "a NaN in out/: $(grep -rl NaN out 2>/dev/null | tr '\n' ' ')" test -z "$(grep -rl 'NaN\|Infinity' out 2>/dev/null)"
cd "$work" || exit 0

# ------------------------------------------------------------- fuzz regressions
# Decks the fuzzer found writing NaN/Infinity or numbers no reader parses
# (an exponent without its letter, 1.0000000+300; a field of '*'). Each now
# either fails with an error located in the deck (exit 1, no folder) or
# writes outputs that hold only finite, readable numbers.
mkdir fuzzreg && cd fuzzreg || exit 0
cat > expect_denormal.inp <<'EOF'
ANALYSIS DYNAMIC
MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85
MESH SPHERE R=0.0366 LEVEL=1
GRAVITY G=9.8
TIME DT=1e-5 TEND=2e-3
EXPECT az_cm_m_s2 4.9e-324 RTOL=1e-9
END
EOF
cat > hertz_tiny_bulk.inp <<'EOF'
ANALYSIS DYNAMIC
MATERIAL golden VISCOELASTIC K=1e-308 RHO=790
PRONY G=0.099e6 BETA=35.26
MESH SPHERE R=0.035 LEVEL=1
INITIAL VZ=-0.7 AZ=-9.8
TIME DT=1e-5 TEND=8e-3
PLATE Z=0 STICK
END
EOF
cat > gravity_huge.inp <<'EOF'
ANALYSIS QUASISTATIC
MATERIAL apple VISCOELASTIC K=1.756e6 RHO=790
PRONY G=0.099e6 BETA=35.26
MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2
FIX BOTTOM Z
TIME DT=1000 TEND=10000
GRAVITY G=1e300
END
EOF
cat > ring_huge.inp <<'EOF'
ANALYSIS QUASISTATIC
MATERIAL flesh VISCOELASTIC K=5.0e6 RHO=800
PRONY G=0.5e6 BETA=0.1
MESH RING R0=0.01 R1=1e308 NR=32 NT=32
TIME DT=5     TEND=100
END
EOF
cat > density_huge.inp <<'EOF'
ANALYSIS STATIC
MATERIAL fruit ELASTIC E=18.11e6 NU=0.219 RHO=1e300
MESH SPHERE R=0.0366 LEVEL=1
FIX TOP Z
END
EOF
cat > beta_denormal.inp <<'EOF'
ANALYSIS DYNAMIC
MATERIAL golden VISCOELASTIC K=1.756e6 RHO=790
PRONY G=0.099e6 BETA=4.9e-324
MESH SPHERE R=0.035 LEVEL=1
TIME DT=2e-5 TEND=15e-3
END
EOF
cp "$root/inputs/halfspace_wave.inp" halfspace_wave.inp    # probe values ~1e-179 ahead of the wave
for deck in expect_denormal hertz_tiny_bulk gravity_huge ring_huge density_huge beta_denormal halfspace_wave; do
  "$exe" -q -o out "$deck.inp" > "$deck.out" 2> "$deck.err"
  status=$?
  if [ $status = 0 ]; then
    bad=$(grep -liE '(^|[^A-Za-z0-9_])[-+]?(nan|inf|infinity)([^A-Za-z0-9_]|$)' \
          "out/$deck/summary.txt" "out/$deck/history.csv" 2>/dev/null | tr '\n' ' ')
    check "fuzz_${deck}_finite" "non-finite in: $bad" test -z "$bad"
    bad=$(grep -hoE '(^|[^A-Za-z0-9_.])[-+]?[0-9]+\.[0-9]+[-+][0-9]{2,}|\*\*' \
          "out/$deck/summary.txt" "out/$deck/history.csv" "out/$deck/listing.txt" 2>/dev/null | head -3 | tr '\n' ' ')
    check "fuzz_${deck}_readable" "unreadable numbers: $bad" test -z "$bad"
    if command -v h5dump > /dev/null; then
      bad=$(h5dump "out/$deck/results.h5" 2>/dev/null | grep -ciE '(^|[^a-z_])(nan|inf)([^a-z_]|$)')
      check "fuzz_${deck}_h5_finite" "$bad lines with nan/inf in h5dump" test "$bad" = 0
    fi
  else
    check_rc "fuzz_${deck}_exit_1" 1 $status
    check "fuzz_${deck}_located" "stderr: $(first_lines "$deck.err")" \
      grep -qE "^visco2d: error: $deck\.inp:[0-9]+(:[0-9]+)?: [A-Z]+: " "$deck.err"
    check "fuzz_${deck}_no_folder" "out holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
      test -z "$(entries_matching out "$deck")"
  fi
done
cd "$work" || exit 0

# ------------------------------------------------------------- interrupt
# SIGTERM while the case folder is being written (a tall strip whose
# results.h5 takes a moment): the temporary folder is removed, a previous
# case folder is kept whole, and the run ends as killed by the signal (143).
# If the signal comes too late the run has finished (0) with its whole folder.
mkdir interrupt && cd interrupt || exit 0
cat > tall.inp <<'EOF'
TITLE tall strip: 80000 elements, 20 MB of results.h5
ANALYSIS STATIC
GEOMETRY PLANESTRAIN
MATERIAL steel ELASTIC E=200e9 NU=0.3
MESH RECT R0=0 R1=0.01 Z0=0 Z1=10 NR=4 NZ=20000
FIX BOTTOM RZ
PRESSURE TOP P=1e6
END
EOF
interrupted_run() {  # interrupted_run NAME: SIGTERM once out/.tall.partial.* appears
  "$exe" -q -o out tall.inp > "$1.out" 2> "$1.err" &
  local pid=$! i
  for i in $(seq 1 5000); do
    compgen -G "out/.tall.partial.*" > /dev/null && break
    sleep 0.002
  done
  kill -TERM "$pid" 2> /dev/null
  wait "$pid"
}
interrupted_run first
status=$?
check interrupt_first_status "exit status $status, expected 143 (or 0 if the signal came late)" \
  test "$status" = 143 -o "$status" = 0
check interrupt_first_no_partial "out holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
  test -z "$(ls -A out 2>/dev/null | grep -F -e .partial. -e .old.)"
if [ "$status" = 143 ]; then
  check interrupt_first_no_case_folder "out holds: $(ls -A out | tr '\n' ' ')" test ! -e out/tall
fi
"$exe" -q -o out tall.inp > whole.out 2> whole.err
check_rc interrupt_whole_run_exit_0 0 $?
cp out/tall/summary.txt whole_summary.txt
interrupted_run second
status=$?
check interrupt_rerun_status "exit status $status, expected 143 (or 0 if the signal came late)" \
  test "$status" = 143 -o "$status" = 0
check interrupt_rerun_no_partial "out holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" test "$(ls -A out)" = tall
check interrupt_rerun_keeps_folder "out/tall holds: $(ls out/tall 2>/dev/null | tr '\n' ' ')" \
  test "$(ls out/tall 2>/dev/null | sort | tr '\n' ' ')" = "history.csv listing.txt results.h5 results.xmf summary.txt "
check interrupt_rerun_same_summary "out/tall/summary.txt differs from the whole run's (beyond cpu_s)" \
  test "$(grep -v '^cpu_s' out/tall/summary.txt)" = "$(grep -v '^cpu_s' whole_summary.txt)"
echo "# interrupt: the SIGTERMs ended the runs with status $status (143: during writing)"
# ---- size before work: the estimate, --max-memory and VISCO2D_MAX_MEMORY
mkdir -p "$work/size" && cd "$work/size" || exit 0
cp "$good_source" sphere.inp
"$exe" check sphere.inp > size_check.out 2> size_check.err
check_rc size_check_exit_0 0 $?
check size_check_memory "stdout: $(first_lines size_check.out)" grep -q '^  memory          about [0-9.]* [KMG]iB (limit ' size_check.out
check size_check_time "stdout: $(first_lines size_check.out)" grep -q '^  run time        roughly ' size_check.out
"$exe" --max-memory 1x check sphere.inp > size_bad.out 2> size_bad.err
check_rc size_bad_option_exit_2 2 $?
check size_bad_option_message "stderr: $(first_lines size_bad.err)" grep -qF -- '--max-memory "1x" is not a memory size' size_bad.err
"$exe" --max-memory 1M check sphere.inp > size_low.out 2> size_low.err
check_rc size_low_check_exit_1 1 $?
check size_low_check_located "stderr: $(first_lines size_low.err)" \
  grep -q '^visco2d: error: sphere.inp:[0-9]*:[0-9]*: MESH: .*need.*more than the limit of 1.00 MiB set by --max-memory' size_low.err
VISCO2D_MAX_MEMORY=1M "$exe" -o out sphere.inp > size_env.out 2> size_env.err
check_rc size_env_run_exit_1 1 $?
check size_env_names_variable "stderr: $(first_lines size_env.err)" grep -q 'set by VISCO2D_MAX_MEMORY' size_env.err
check size_env_no_output "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" test -z "$(ls -A out 2>/dev/null)"
# A limit in the environment that is not one is refused as the same value on
# the command line is (exit 2, before any deck): it was ignored with a
# warning, and the run had no limit at all.
for value in lots 1s 0 -1 nan garbage; do
  VISCO2D_MAX_MEMORY=$value "$exe" -q -o out sphere.inp > size_junk.out 2> size_junk.err
  check_rc "size_env_memory_${value}_exit_2" 2 $?
  check "size_env_memory_${value}_says_why" "stderr: $(first_lines size_junk.err)" \
    grep -q "^visco2d: VISCO2D_MAX_MEMORY \"$value\" is not a memory size" size_junk.err
  check "size_env_memory_${value}_no_output" "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
    test -z "$(ls -A out 2>/dev/null)"
  VISCO2D_MAX_TIME=$value "$exe" check sphere.inp > size_junk.out 2> size_junk.err
  check_rc "size_env_time_${value}_check_exit_2" 2 $?
  VISCO2D_MAX_TIME=$value "$exe" -q -o out sphere.inp > size_junk.out 2> size_junk.err
  check_rc "size_env_time_${value}_exit_2" 2 $?
  check "size_env_time_${value}_says_why" "stderr: $(first_lines size_junk.err)" \
    grep -q "^visco2d: VISCO2D_MAX_TIME \"$value\" is not a number of seconds > 0" size_junk.err
  check "size_env_time_${value}_no_output" "out/ holds: $(ls -A out 2>/dev/null | tr '\n' ' ')" \
    test -z "$(ls -A out 2>/dev/null)"
done
# An option given overrides the variable, which is then not read; an empty
# variable is an unset one.
VISCO2D_MAX_TIME=1s "$exe" --max-time 600 check sphere.inp > size_junk.out 2> size_junk.err
check_rc size_env_time_option_overrides 0 $?
VISCO2D_MAX_MEMORY=1s "$exe" --max-memory 8G check sphere.inp > size_junk.out 2> size_junk.err
check_rc size_env_memory_option_overrides 0 $?
VISCO2D_MAX_TIME= VISCO2D_MAX_MEMORY= "$exe" check sphere.inp > size_junk.out 2> size_junk.err
check_rc size_env_empty_is_unset 0 $?
check size_help_option "--help does not mention --max-memory" grep -q -- '--max-memory' ../usage/help.out
check size_help_variable "--help does not mention VISCO2D_MAX_MEMORY" grep -q VISCO2D_MAX_MEMORY ../usage/help.out
cd "$work" || exit 0

# ---- bruise: the summary's bruise volume against the /bruise fields of results.h5,
# recomputed independently (numpy: the 2 x 2 Gauss rule on the mesh's
# quadrilaterals, 2 pi |J| r, envelope >= threshold); no /bruise group and no
# bruise keys without a BRUISE card.
mkdir -p "$work/bruise" && cd "$work/bruise" || exit 0
cp "$root/test/decks/bruise_drop.inp" bruise.inp
"$exe" -q -o out bruise.inp > bruise.out 2> bruise.err
check_rc bruise_run_exit_0 0 $?
bruise_value() { sed -n "s/^$1 = //p" out/bruise/summary.txt 2>/dev/null | head -1; }
check bruise_susceptibility_key "summary: no bruise_susceptibility_cm3_per_J" \
  test -n "$(bruise_value bruise_susceptibility_cm3_per_J)"
if command -v python3 > /dev/null && python3 -c 'import h5py, numpy' > /dev/null 2>&1; then
  python3 - out/bruise/results.h5 > bruise_h5py.out 2> bruise_h5py.err <<'PYTHON'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r") as f:
    xy = f["/mesh/nodes"][:]                 # (nnode, 2)
    elements = f["/mesh/elements"][:] - 1    # (nelem, 4), 1-based in the file
    envelope = f["/bruise/max_shear_envelope"][:]    # (nelem, 4 Gauss points)
    threshold = f["/bruise/threshold"][:]
    units = f["/bruise/max_shear_envelope"].attrs["units"]
    print("units", units.decode() if isinstance(units, bytes) else units)
g = 1.0 / np.sqrt(3.0)
volume = np.zeros_like(envelope)
x = xy[elements, 0]
y = xy[elements, 1]
for k, (xi, eta) in enumerate([(-g, -g), (g, -g), (g, g), (-g, g)]):
    n = 0.25 * np.array([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta), (1 - xi) * (1 + eta)])
    dxi = 0.25 * np.array([-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)])
    deta = 0.25 * np.array([-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)])
    jacobian = (x @ dxi) * (y @ deta) - (x @ deta) * (y @ dxi)
    volume[:, k] = 2 * np.pi * jacobian * (x @ n)
print("volume_cm3 %.12e" % (1e6 * volume[envelope >= threshold].sum()))
print("extra_cm3 %.12e" % (1e6 * volume[envelope >= 0.3e6].sum()))
PYTHON
  check_rc bruise_h5py_reads 0 $?
  close_to() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; s = (b < 0 ? -b : b); exit !(a != "" && b != "" && d <= 1e-9 * s + 1e-12) }'; }
  got=$(sed -n 's/^volume_cm3 //p' bruise_h5py.out)
  key=$(bruise_value bruise_volume_cm3)
  check bruise_h5_volume_equals_summary "results.h5 gives '$got' cm^3, summary '$key'" close_to "$got" "$key"
  check bruise_h5_volume_nonzero "summary bruise_volume_cm3 = '$key'" awk -v a="$key" 'BEGIN { exit !(a > 0) }'
  got=$(sed -n 's/^extra_cm3 //p' bruise_h5py.out)
  key=$(bruise_value bruise_volume_threshold_1_cm3)
  check bruise_h5_extra_volume_equals_summary "results.h5 gives '$got' cm^3, summary '$key'" close_to "$got" "$key"
  check bruise_h5_envelope_units "h5py: $(first_lines bruise_h5py.out) $(first_lines bruise_h5py.err)" \
    grep -q '^units Pa$' bruise_h5py.out
  # results.xmf carries the envelopes (nodal) in every grid: meshio reads the
  # same numbers as /bruise/<name>_nodal.
  if python3 -c "import meshio" 2> /dev/null; then
    python3 - out/bruise > bruise_xdmf.out 2> bruise_xdmf.err <<'PYTHON'
import sys, h5py, meshio, numpy
case = sys.argv[1]
reader = meshio.xdmf.TimeSeriesReader(case + "/results.xmf")
reader.read_points_cells()
with h5py.File(case + "/results.h5", "r") as f:
    names = [n[:-len("_nodal")] for n in f["/bruise"] if n.endswith("_nodal")]
    ok = len(names) > 0
    for k in range(reader.num_steps):
        t, point_data, cell_data = reader.read_data(k)
        for name in names:
            ok = ok and numpy.array_equal(point_data[name], f["/bruise/" + name + "_nodal"][()])
print("envelopes", len(names), "equal", ok)
PYTHON
    check bruise_xdmf_envelopes "meshio: $(first_lines bruise_xdmf.out) $(first_lines bruise_xdmf.err)" \
      grep -q 'equal True$' bruise_xdmf.out
  fi
else
  echo "# h5py or numpy not available: bruise h5py checks skipped"
fi
cp "$good_source" plain.inp
"$exe" -q -o out plain.inp > plain.out 2> plain.err
check_rc bruise_plain_run_exit_0 0 $?
if command -v h5dump > /dev/null; then
  h5dump -n out/plain/results.h5 > plain_h5.txt 2>&1
  check bruise_no_group_without_card "results.h5 of a deck without BRUISE has /bruise" \
    sh -c '! grep -q " /bruise" plain_h5.txt'
fi
check bruise_no_keys_without_card "summary of a deck without BRUISE has bruise keys" \
  sh -c '! grep -q "^bruise_\|^envelope_" out/plain/summary.txt'
cd "$work" || exit 0

# Two decks of one batch with the same case name would write the same folder:
# refused before anything runs (exit 2, both paths named), nothing written.
mkdir -p twin_a twin_b
cp decks/first.inp twin_a/twin.inp
cp decks/last.inp twin_b/twin.inp
"$exe" -o twin_out twin_a/twin.inp twin_b/twin.inp > twin.out 2> twin.err
check_rc duplicate_case_exit_2 2 $?
check duplicate_case_names_both "stderr: $(first_lines twin.err)" \
  sh -c 'grep -q "twin_a/twin.inp and twin_b/twin.inp have the same case name \"twin\"" twin.err && grep -q "separate -o folders" twin.err'
check duplicate_case_nothing_written "twin_out exists: $(ls -A twin_out 2>&1 | tr '\n' ' ')" test ! -e twin_out
"$exe" -o twin_out twin_a/twin.inp decks/first.inp twin_a/twin.inp > twin2.out 2> twin2.err
check_rc duplicate_same_deck_exit_2 2 $?
check duplicate_same_deck_named "stderr: $(first_lines twin2.err)" grep -q "twin_a/twin.inp is given twice" twin2.err
"$exe" check twin_a/twin.inp twin_b/twin.inp > twin3.out 2> twin3.err
check_rc duplicate_case_check_allowed 0 $?

# --decks-from: a list file (blank lines, # comments and a CRLF skipped) and standard input, each
# deck of the stream run as its line arrives; the results are those of the same decks as arguments.
printf 'decks/first.inp\r\n\n# a comment\ndecks/last.inp\n' > list.txt
"$exe" -o from_list --decks-from list.txt > from_list.out 2> from_list.err
check_rc decks_from_file_exit_0 0 $?
check decks_from_file_both_run "stdout: $(first_lines from_list.out)" \
  sh -c 'test "$(grep -c " nodes, " from_list.out)" = 2 && test -f from_list/first/summary.txt && test -f from_list/last/summary.txt'
"$exe" -o from_args decks/first.inp decks/last.inp > from_args.out 2>&1
check decks_from_file_same_results "the summaries differ from the same decks given as arguments" \
  bash -c 'for c in first last; do diff <(grep -v "^cpu_s\|^wall_s\|^date\|_path\|^output" from_list/$c/summary.txt) <(grep -v "^cpu_s\|^wall_s\|^date\|_path\|^output" from_args/$c/summary.txt) > /dev/null || exit 1; done'
printf 'decks/first.inp\ndecks/last.inp\ntwin_a/twin.inp\ntwin_b/twin.inp\n' | "$exe" -o from_stdin --decks-from - > from_stdin.out 2> from_stdin.err
check_rc decks_from_stdin_twin_exit_1 1 $?
check decks_from_stdin_three_run "stdout: $(first_lines from_stdin.out)" test "$(grep -c ' nodes, ' from_stdin.out)" = 3
check decks_from_stdin_twin_refused "stderr: $(first_lines from_stdin.err)" \
  grep -q 'twin_b/twin.inp: the case name "twin" was run earlier in this batch' from_stdin.err
"$exe" -o from_bad --decks-from no_such_list.txt > from_bad.out 2> from_bad.err
check_rc decks_from_missing_file_exit_2 2 $?
check decks_from_missing_file_named "stderr: $(first_lines from_bad.err)" \
  sh -c 'grep -q "no_such_list.txt: cannot open it" from_bad.err && test ! -e from_bad'
"$exe" -o from_both --decks-from - decks/first.inp < /dev/null > from_both.out 2> from_both.err
check_rc decks_from_stdin_and_arguments_exit_2 2 $?

exit 0
