# Sourced by the tests of visco2d-batch (test_batch.sh, test_hosts.sh, test_boundary.sh).
# batch_tool EXE WORK: the visco2d-batch to test, the launcher `make build` writes beside the
# executable (python/launchers.py), else one written into WORK/bin for this checkout's python/.
batch_tool() {
  local tool
  tool="$(dirname "$1")/visco2d-batch"
  if [ ! -x "$tool" ]; then
    python3 "$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/python/launchers.py" "$2/bin" > /dev/null
    tool="$2/bin/visco2d-batch"
  fi
  echo "$tool"
}
