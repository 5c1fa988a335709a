#!/usr/bin/env bash
# Tests of `visco2d-batch boundary` (python/visco2d/boundary.py): the damage boundary of a 2 x 2
# grid (two fruit sizes on the bare plate and on a foam pad), against separate `threshold`
# searches, its table, its chart and the marking of warned points; a threshold's warned result line.
#
#   bash scripts/test_boundary.sh PATH/TO/visco2d
#
# Prints `PASS name` or `FAIL name: detail` per check (`# ` lines are notes) and always exits 0:
# the caller counts. The deck: inputs/peach_drop.inp at mesh level 1 (88 elements) with
# ${radius}, ${height} and a ${surface} line; everything in a temporary folder, removed at the end.

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

pass() { echo "PASS $1"; }
fail() { echo "FAIL $1: $2"; }
check() {  # check NAME DETAIL COMMAND...
  local name=$1 detail=$2
  shift 2
  if "$@"; then pass "$name"; else fail "$name" "$detail"; fi
}
check_rc() { if [ "$3" = "$2" ]; then pass "$1"; else fail "$1" "exit status $3, expected $2"; fi; }
check_ok() { if [ "$2" = 0 ]; then pass "$1"; else fail "$1" "exit status $2: $(tail -3 "$3" | tr '\n' '|')"; fi; }
first_lines() { head -c 400 "$1" 2>/dev/null | tr '\n' '|'; }

if [ $# -ne 1 ] || [ ! -x "$1" ] || [ -d "$1" ]; then
  fail executable "usage: bash scripts/test_boundary.sh PATH/TO/visco2d (got '${1:-}')"
  exit 0
fi
exe="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
batch() { "$tool" "$@" --exe "$exe"; }

work=$(mktemp -d "${TMPDIR:-/tmp}/visco2d_boundary.XXXXXX") || { fail mktemp "cannot create a temporary folder"; exit 0; }
trap 'rm -rf "$work"' EXIT
cd "$work" || { fail cd "cannot enter $work"; exit 0; }
source "$root/scripts/batch_tool.sh"
tool=$(batch_tool "$exe" "$work")

installed="$(dirname "$exe")/visco2d_boundary.py"
if [ -f "$installed" ]; then
  check installed_copy "$installed differs from python/visco2d/boundary.py (make build installs it)" \
    cmp -s "$installed" "$root/python/visco2d/boundary.py"
fi

# The template: the peach on the coarse mesh, its flesh named on MESH and BRUISE (a pad is another
# material), the surface's cards on a line of their own after PLATE.
sed -e 's/^MESH SPHERE R=0.03 LEVEL=3 /MESH SPHERE R=${radius} LEVEL=1 MAT=peach/' \
    -e 's/^DROP HEIGHT=0.2/DROP HEIGHT=${height}/' -e 's/^BRUISE \(.*\)$/BRUISE \1 MAT=peach/' \
    -e 's/^STOP AT=SEPARATION/${surface}\nSTOP AT=SEPARATION/' \
    -e 's/STRESS=0.3e6/STRESS=0.2e6/' "$root/inputs/peach_drop.inp" > peach.inp
# (a failure stress of 0.2 MPa: the onset on steel, near 2 cm, stays below alpha/R = 4.5 %, where the
#  approach warning starts, so that the steel cells are the ones without warnings)
check template_made "the sed of inputs/peach_drop.inp did not make 3 placeholders" \
  test "$(grep -o '\${[a-z]*}' peach.inp | wc -l)" = 3
foam='MATERIAL foam ELASTIC E=1e6 NU=0.3 RHO=100; PAD THICKNESS=0.01 MAT=foam'
grid=(peach.inp --param height=0.01:2.0 --param radius=0.025,0.035 --surface steel=none --surface "foam=$foam"
      --when 'bruise_volume_cm3>0' --tol 0.02 --x-scale 1000 --x-label 'fruit radius (mm)')

# 1. The 2 x 2 boundary on two processes.
batch boundary "${grid[@]}" -j 2 -q -o grid > grid.log 2>&1
check_ok boundary_runs $? grid.log
for file in boundary.csv boundary.txt boundary.png; do
  check "boundary_writes_${file/./_}" "grid/$file is missing" test -s "grid/$file"
done
check boundary_chart_is_png "grid/boundary.png does not start with the PNG signature" \
  test "$(head -c 8 grid/boundary.png | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a
check boundary_no_surface_card_on_steel "grid/templates/peach__surface=steel.inp holds a PAD card or \${surface}" \
  bash -c '! grep -q -e "^PAD" -e "surface}" grid/templates/peach__surface=steel.inp'
check boundary_foam_cards "grid/templates/peach__surface=foam.inp: no PAD line after PLATE" \
  grep -q '^PAD THICKNESS=0.01 MAT=foam$' grid/templates/peach__surface=foam.inp

# 2. Each search is the same as a separate `threshold` of its surface's template and fruit:
#    the same runs, the same bracket, the same record.
for surface in steel foam; do for radius in 0.025 0.035; do
  batch threshold "grid/templates/peach__surface=$surface.inp" --param radius=$radius --param height=0.01:2.0 \
    --when 'bruise_volume_cm3>0' --tol 0.02 -q -o "alone_${surface}_$radius" > "alone_${surface}_$radius.log" 2>&1
done; done
python3 - grid > verdict.log 2>&1 <<'PY'
import csv, re, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(f'{out}/boundary.csv')))
assert len(rows) == 4, f'{len(rows)} rows in boundary.csv, expected 4'
value = {}
for row in rows:
    assert row['status'] == 'ok', f'{row["search"]}: {row["status"]}'
    alone = f'alone_{row["surface"]}_{row["radius"]}'
    record = open(f'{alone}/threshold.txt').read()
    mine = open(f'{out}/searches/{row["search"]}.txt').read()
    assert record == mine, f'{row["search"]}: its record differs from a separate threshold search\'s'
    text = open(f'{alone}.log').read()
    critical = re.search(r'height_critical = (\S+)', text).group(1)
    low, high = re.search(r'bracket = \[(\S+), (\S+)\]', text).group(1, 2)
    assert (critical, low, high) == (row['height_critical'], row['bracket_low'], row['bracket_high']), \
        f'{row["search"]}: {row["height_critical"]} [{row["bracket_low"]}, {row["bracket_high"]}] against ' \
        f'threshold\'s {critical} [{low}, {high}]'
    assert float(high) - float(low) <= 0.02 + 1e-12, f'{row["search"]}: bracket wider than --tol'
    assert float(low) <= float(critical) <= float(high)
    value[row['surface'], row['radius']] = float(critical)
    print(f'# {row["surface"]} R {row["radius"]}: height_critical {critical} in [{low}, {high}], '
          f'{row["runs"]} runs, {row["warnings"]} warnings at the bracket (as threshold\'s)')
for radius in ('0.025', '0.035'):
    assert value['foam', radius] > value['steel', radius] + 0.1, f'R {radius}: the foam pad does not protect: {value}'
assert value['foam', '0.025'] > value['foam', '0.035'], f'on the pad the larger fruit bruises lower: {value}'
print('verdict ok')
PY
check boundary_equals_threshold "$(grep -v '^# ' verdict.log | tr '\n' ' ' | head -c 600)" grep -q '^verdict ok' verdict.log
grep '^# ' verdict.log
steel=$(grep '^steel,0.035,' grid/boundary.csv | cut -d, -f3,4,5 | tr , ' ')
cell=$(printf '%#.4g [%#.4g, %#.4g]' $steel)
check boundary_text_table "grid/boundary.txt: no row 'radius=0.035  $cell ...' (boundary.csv: $steel)" \
  bash -c 'grep "^radius=0.035 " grid/boundary.txt | grep -qF " $0  "' "$cell"

# 3. Warnings: the foam pad's strain warning at the bracket marks its points (table, text, chart);
#    the plate's do not; a threshold search that warns says so in its result line and record.
check warned_rows "grid/boundary.csv: the foam rows lack their pad warning, or a steel row has one: $(first_lines grid/boundary.csv)" \
  python3 -c '
import csv, sys
for row in csv.DictReader(open("grid/boundary.csv")):
    warned = int(row["warnings"]) > 0 and "PAD: the largest principal strain in the pad" in row["warning"]
    clean = row["warnings"] == "0" and row["warning"] == ""
    if (row["surface"] == "foam" and not warned) or (row["surface"] == "steel" and not clean):
        sys.exit(1)'
check warned_text_marks "grid/boundary.txt: $(first_lines grid/boundary.txt)" \
  bash -c 'grep -q "^radius=0.025 .*\] \*1\( \*[0-9]*\)*$" grid/boundary.txt && grep -q "^1) PAD: the largest principal strain" grid/boundary.txt'
python3 - grid/boundary.png > png.log 2>&1 <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], 'rb').read()
position, text = 8, {}
while position < len(data):
    length, kind = struct.unpack('>I4s', data[position:position + 8])
    body = data[position + 8:position + 8 + length]
    if kind == b'tEXt':
        key, value = body.split(b'\0', 1)
        text[key.decode()] = value.decode('latin-1')
    position += 12 + length
points = text.get('Description', '').split('; ')
print('\n'.join(points))
hollow = sorted(point.split(' x=')[0] + ' ' + point.split(' x=')[1].split()[0] for point in points if ' hollow ' in point)
filled = sorted(point.split(' x=')[0] + ' ' + point.split(' x=')[1].split()[0] for point in points if point.endswith(' filled'))
assert hollow == ['foam 25', 'foam 35'] and filled == ['steel 25', 'steel 35'], (hollow, filled)
print('chart ok')
PY
check warned_chart_points_hollow "the chart's points: $(tr '\n' ' ' < png.log | head -c 400)" grep -q '^chart ok' png.log
check threshold_result_line_warns "alone_foam_0.035.log: $(first_lines alone_foam_0.035.log)" \
  grep -q '^height_critical = [0-9.]*  (warned: [0-9]* warning(s) in the runs at the bracket' alone_foam_0.035.log
check threshold_warning_lines "alone_foam_0.035.log: no 'warning = <case>: PAD: ...' line" \
  grep -q '^warning = peach__surface=foam__radius=0.035__height=[0-9.]*: PAD: the largest principal strain' alone_foam_0.035.log
check threshold_record_warns "alone_foam_0.035/threshold.txt: $(first_lines alone_foam_0.035/threshold.txt)" \
  bash -c 'grep -q "^warnings = [1-9]" alone_foam_0.035/threshold.txt && grep -q "^run = .* warnings=[1-9]$" alone_foam_0.035/threshold.txt'
check threshold_clean_line "alone_steel_0.025.log: the result line of a search without warnings at the bracket: $(first_lines alone_steel_0.025.log)" \
  grep -q '^height_critical = [0-9.]*  ([0-9]* of the [0-9]* runs warned, none at the bracket)$\|^height_critical = [0-9.]*$' alone_steel_0.025.log

# 4. One process: the same table (each search bisects, one point a round, whatever -j).
batch boundary "${grid[@]}" -j 1 -q -o serial > serial.log 2>&1
check_ok boundary_one_process $? serial.log
check boundary_one_process_same_table "serial/boundary.csv differs from grid/boundary.csv" \
  cmp -s serial/boundary.csv grid/boundary.csv

# 4b. Ctrl-C (at level 2, long enough to be caught running): exit 130, no partial folder, no process
#     left; --resume ends the searches reusing the runs that ended, and a second --resume reruns
#     nothing and gives the same table.
sed 's/LEVEL=1/LEVEL=2/' peach.inp > peach2.inp
grid2=(peach2.inp "${grid[@]:1}")
wait_for() { local i; for i in $(seq 1 2000); do [ -e "$1" ] && return 0; sleep 0.005; done; return 1; }
set -m
"$tool" boundary "${grid2[@]}" --exe "$exe" -j 2 -q -o stopped > stopped.log 2>&1 &
batch_pid=$!
set +m
wait_for "stopped/peach2__surface=steel__radius=0.025__height=0.01/summary.txt"
kill -INT "$batch_pid"
wait "$batch_pid"
check_rc interrupt_exit_130 130 $?
check interrupt_message "stopped.log: $(first_lines stopped.log)" grep -q '^visco2d-batch: interrupted: ' stopped.log
check interrupt_no_partial "stopped holds: $(ls -A stopped | grep '^\.' | tr '\n' ' ')" test -z "$(ls -A stopped | grep '^\.')"
check interrupt_no_process_left "$(pgrep -af -- '-o [s]topped ' | head -c 300)" bash -c '! pgrep -f -- "-o [s]topped " > /dev/null'
ended=$(ls -d stopped/peach2__*/ | wc -l)
batch boundary "${grid2[@]}" -j 2 -o stopped --resume > resumed.log 2>&1
check_ok resume_ends $? resumed.log
check resume_reuses "resumed.log: $(grep -- '--resume' resumed.log)" \
  grep -q -- "--resume: $ended of the [0-9]* runs had a verified result in stopped" resumed.log
cp stopped/boundary.csv resumed.csv
batch boundary "${grid2[@]}" -j 2 -o stopped --resume > again.log 2>&1
runs=$(tail -n +2 stopped/boundary.csv | cut -d, -f7 | paste -sd+ | bc)
check resume_again_reruns_nothing "again.log: $(grep -- '--resume' again.log) ($runs runs in the table)" \
  grep -q -- "--resume: $runs of the $runs runs had a verified result" again.log
check resume_same_table "a second --resume changed stopped/boundary.csv" cmp -s resumed.csv stopped/boundary.csv

# 5. No onset in the bracket: exit 1, the cell says so; a surface given as parameters.
sed -e 's/^\${surface}$/MATERIAL foam ELASTIC E=${pad_e} NU=0.3 RHO=100\nPAD THICKNESS=${pad_t} MAT=foam/' peach.inp > pad.inp
batch boundary pad.inp --param height=0.01:0.03 --param radius=0.03 --surface 'thin:pad_t=0.005,pad_e=3e6' \
  --when 'bruise_volume_cm3>0' --tol 0.01 -q -o none > none.log 2>&1
check_rc no_onset_exit_1 1 $?
check no_onset_cell "none/boundary.txt: $(first_lines none/boundary.txt)" grep -q '^radius=0.03 *> 0.03$' none/boundary.txt
check parameter_surface_cases "none/: no case pad__surface=thin__radius=0.03__pad_t=0.005__pad_e=3e6__height=0.01" \
  test -f "none/pad__surface=thin__radius=0.03__pad_t=0.005__pad_e=3e6__height=0.01/summary.txt"
check no_onset_chart "none/boundary.png is missing" test -s none/boundary.png

# 6. The example template of doc/batch.md (on the coarse mesh): the bare plate and a pad run, the TITLE
#    names the surface.
sed 's/LEVEL=3/LEVEL=1/' "$root/inputs/examples/peach_boundary.inp" > peach_boundary.inp
batch boundary peach_boundary.inp --param height=0.01:0.02 --param radius=0.03 --surface steel=none \
  --surface "foam=$foam" --when 'bruise_volume_cm3>0' --tol 0.01 -q -o example > example.log 2>&1
check_rc example_runs_no_onset_exit_1 1 $?
check example_four_runs "example/: $(ls -d example/peach_boundary__* 2>/dev/null | wc -l) case folders, expected 4" \
  test "$(ls -d example/peach_boundary__*/ 2>/dev/null | wc -l)" = 4
check example_title_names_surface "example/templates/peach_boundary__surface=foam.inp: $(grep '^TITLE' example/templates/peach_boundary__surface=foam.inp)" \
  grep -q '^TITLE Peach, R ${radius} m, E 5 MPa, dropped ${height} m onto foam$' example/templates/peach_boundary__surface=foam.inp

# 7. Usage errors: exit 2, nothing run.
sed 's/^\${surface}$//' peach.inp > plain.inp
batch boundary plain.inp --param height=0.01:1 --param radius=0.03 --surface "foam=$foam" --when 'bruise_volume_cm3>0' \
  --tol 0.1 -o usage1 > usage1.log 2>&1
check_rc cards_without_placeholder_exit_2 2 $?
check cards_without_placeholder_message "$(first_lines usage1.log)" grep -q 'has no ${surface} line' usage1.log
batch boundary peach.inp --param height=0.01:1 --param radius=0.03 --when 'bruise_volume_cm3>0' --tol 0.1 -o usage2 \
  > usage2.log 2>&1
check_rc placeholder_without_surfaces_exit_2 2 $?
batch boundary peach.inp --param height=0.01:1 --param radius=0.03 --surface 'bad name' --when 'bruise_volume_cm3>0' \
  --tol 0.1 -o usage3 > usage3.log 2>&1
check_rc bad_surface_exit_2 2 $?
batch boundary peach.inp --param radius=0.03 --surface steel=none --when 'bruise_volume_cm3>0' --tol 0.1 -o usage4 \
  > usage4.log 2>&1
check_rc no_searched_parameter_exit_2 2 $?
timeout 60 "$tool" boundary peach.inp --param height=0.01:1 --param radius=0.03 --surface steel=none \
  --when 'no_such_key>0' --tol 0.1 --exe "$exe" -q -o nokey > nokey.log 2>&1
check_rc unknown_key_exit_2 2 $?
check unknown_key_message "$(first_lines nokey.log)" grep -q 'error: --when: the summary of .* has no key "no_such_key"' nokey.log
check usage_nothing_run "a usage error ran cases: $(ls -d usage*/peach__* 2>/dev/null | head -3)" \
  test -z "$(ls -d usage*/*__height=* 2>/dev/null)"
exit 0
