"""Find and run the visco2d executable.

Every tool of the package starts visco2d through `run`: one process for any
number of decks (visco2d reads them in turn and writes OUT/<case>/ for each),
BLAS threads pinned to one so that timings and `-j` sweeps mean what they say.
"""
import os
import shutil
import subprocess
import sys

#: One BLAS/OpenMP thread per visco2d process: the sweeps put one process on each core.
#: OMP_THREAD_LIMIT too: CHOLMOD's supernodal factor asks OpenMP for 4 threads whatever
#: OMP_NUM_THREADS says (its num_threads clause); the limit is the one setting that caps it.
ONE_THREAD = {name: "1" for name in ("OMP_NUM_THREADS", "OMP_THREAD_LIMIT", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
                                     "GOTO_NUM_THREADS", "BLIS_NUM_THREADS")}


def repository_root():
    """The visco2d checkout this package lies in (the folder with fpm.toml), or None when installed elsewhere."""
    here = os.path.dirname(os.path.realpath(__file__))
    candidate = os.path.normpath(os.path.join(here, "..", ".."))
    return candidate if os.path.exists(os.path.join(candidate, "fpm.toml")) else None


#: The checkout's root (None outside one): the default place of decks, builds and outputs.
ROOT = repository_root() or os.getcwd()


def find_program(explicit=None, variable="VISCO2D", name="visco2d", relative="build/install/bin/visco2d"):
    """An executable: the option, the environment variable, beside the running tool, in the checkout, on PATH.

    An explicit path that is not an executable raises FileNotFoundError; nothing found returns None.
    """
    if explicit:
        if os.path.isfile(explicit) and os.access(explicit, os.X_OK):
            return os.path.abspath(explicit)
        raise FileNotFoundError(f"{explicit}: not an executable")
    candidates = [os.environ.get(variable),
                  os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), name)]
    root = repository_root()
    if root:
        candidates.append(os.path.join(root, relative))
    candidates.append(shutil.which(name))
    for candidate in candidates:
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return os.path.abspath(candidate)
    return None


def default_exe():
    """The visco2d to run when no --exe is given (the checkout's build when there is one)."""
    return find_program() or os.path.join(ROOT, "build", "install", "bin", "visco2d")


def command(exe, decks, out, quiet=True, options=()):
    """The command line `exe [options] [-q] -o OUT DECK...`."""
    return [exe, *options, *(["-q"] if quiet else []), "-o", out, *decks]


def run(exe, decks, out, quiet=True, options=(), env=None, timeout=None):
    """Run visco2d on the decks into OUT/ and wait; a CompletedProcess with text stdout and stderr.

    env adds to (never replaces) the environment, after the one-thread settings.
    """
    environment = dict(os.environ, **ONE_THREAD, **(env or {}))
    return subprocess.run(command(exe, decks, out, quiet, options), capture_output=True, text=True,
                          env=environment, timeout=timeout)


def located_error(stderr, deck=None):
    """The located message of a failed run: the `visco2d: error:` line (of that deck), else the last line."""
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    errors = [line for line in lines if "error:" in line and (deck is None or deck in line)]
    if errors:
        return errors[-1].split("error:", 1)[1].strip()
    return lines[-1] if lines else "failed without a message"


def last_line(result):
    """The last line of a failed run's messages (stderr, else stdout), for a one-line report."""
    return ((result.stderr or result.stdout).strip().splitlines() or ["no output"])[-1]


def cpu_model():
    """The CPU model from /proc/cpuinfo ('?' when unknown)."""
    try:
        with open("/proc/cpuinfo") as handle:
            return next((line.split(":", 1)[1].strip() for line in handle if line.startswith("model name")), "?")
    except OSError:
        return "?"


def version(exe):
    """`visco2d --version`'s line ('?' when it prints none)."""
    return subprocess.run([exe, "--version"], capture_output=True, text=True).stdout.strip() or "?"
