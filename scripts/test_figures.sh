#!/usr/bin/env bash
# Smoke check of `make figures` (python/visco2d/figures.py): on a fresh output folder it
# runs the decks it needs, writes every PNG, and its exact-Hertz integration
# reproduces eqs. [43]-[45]; bad paths fail with a clear message.
# usage: scripts/test_figures.sh [EXE]   (prints PASS/FAIL lines)
set -uo pipefail
cd "$(dirname "$0")/.."
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"   # the package python/visco2d/ (doc/python.md)
exe=${1:-${VISCO2D:-build/install/bin/visco2d}}
tmp=build/test-tmp/figures
rm -rf "$tmp" && mkdir -p "$tmp"

pass() { echo "PASS $*"; }
fail() { echo "FAIL $*"; }

# 1. A fresh output folder, the fine Table 1 runs on level 2 (fast): everything is made.
if python3 -m visco2d.figures --out "$tmp/out" --exe "$exe" --level 2 > "$tmp/log.txt" 2>&1; then
  pass "figures.py ran on an empty output folder"
else
  fail "figures.py exited with status $? (see $tmp/log.txt)"; tail -5 "$tmp/log.txt"
fi
for name in fig2_center_acceleration fig3_deformation fig4_pressure fig5_apple_0.7 fig6_apple_1.2 \
            fig5_6_apple_velocities max_shear_contour max_shear_contour_slip; do
  png="$tmp/out/figures/$name.png"
  # a PNG starts with the 8-byte signature 89 50 4E 47 0D 0A 1A 0A; a drawn figure is > 20 kB
  if [ -f "$png" ] && [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] \
     && [ "$(stat -c %s "$png")" -gt 20000 ] && grep -q "  $png\$" "$tmp/log.txt"; then
    pass "$name.png written, a PNG, listed"
  else
    fail "$name.png missing, not a PNG, too small, or not listed"
  fi
done
for case_name in apple_center_accel apple_center_accel_separation table1_elastic apple_v0.7 apple_v1.2; do
  [ -f "$tmp/out/$case_name/results.h5" ] && pass "missing $case_name run made" \
    || fail "missing $case_name run not made"
done
[ -f "$tmp/out/figures/runs/table1_elastic_level2/results.h5" ] && \
  grep -q 'LEVEL=2' "$tmp/out/figures/decks/table1_elastic_level2.inp" && \
  grep -q '^PLATE Z=0 SLIP' "$tmp/out/figures/decks/table1_elastic_level2_slip.inp" \
  && pass "fine decks generated (LEVEL=2, SLIP) and run" || fail "fine decks not generated or not run"

# 2. A second call reuses the fine runs (same deck text, same executable).
python3 -m visco2d.figures --out "$tmp/out" --exe "$exe" --level 2 > "$tmp/log2.txt" 2>&1
grep -q 'running' "$tmp/log2.txt" && fail "second call ran a deck again" || pass "second call reuses the runs"

# 3. The exact Hertz curve: its peak is eq. [43] and t_m = 1.4716 alpha_m / V (the
#    Timoshenko-Goodier constant), q_m eq. [45]. RK4 with 4000 steps over 1.25 t_m:
#    the peak value is flat (error ~ (dt/t_m)^2 < 1e-6), the time is sampled to dt/2 = 2e-4 t_m.
python3 - <<'EOF' || fail "the Hertz checks did not run (python exit status $?)"
import math, sys
from visco2d import hertz as F
E, nu, R, M, V = 18.11e6, 0.219, 0.0366, 0.155, 0.9982     # the paper's Table 1 data
am = F.alpha_max(E, nu, R, M, V)
t, a, q = F.exact(E, nu, R, M, V, 1.25 * 1.4716 * am / V)
k = a.argmax()
checks = [("alpha_m eq. [43] (paper 1.097 mm)", a[k], am, 1e-6),
          ("t_m = 1.4716 alpha_m / V", t[k], 1.4716 * am / V, 5e-4),
          ("q_m eq. [45] (paper 2.10 MPa)", q[k], F.pressure(E, nu, R, am), 1e-6),
          ("alpha_m = 1.0962 mm (deck comment)", am * 1e3, 1.0962, 1e-4)]
for name, got, want, rtol in checks:
    ok = abs(got - want) <= rtol * abs(want)
    print(f"{'PASS' if ok else 'FAIL'} exact Hertz {name}: {got:.6g} vs {want:.6g} (rtol {rtol:g})")
EOF

# 4. Clear errors.
out=$(python3 -m visco2d.figures --out "$tmp/bad" --exe "$tmp/no-such-exe" 2>&1); status=$?
[ $status -ne 0 ] && echo "$out" | grep -q "error: .*no-such-exe not found" \
  && pass "missing executable: clear error" || fail "missing executable: status $status, '$out'"
out=$(python3 -m visco2d.figures --out "$tmp/bad" --exe "$exe" --inputs "$tmp/no-inputs" 2>&1); status=$?
[ $status -ne 0 ] && echo "$out" | grep -q "error: deck .*no-inputs/.*\.inp not found" \
  && pass "missing deck: clear error" || fail "missing deck: status $status, '$out'"
