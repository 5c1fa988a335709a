# visco2d — the two commands of a new user:
#   make run    install what is missing, build (release), run every deck in inputs/ into out/,
#               then print the impact results beside the paper's (python/visco2d/paper_table.py)
#   make test   install what is missing, run the tests and the reference-output diffs
#   make figures  pictures of the paper's figures into out/figures/ (python/visco2d/figures.py)
#   make report   one picture per case of out/: out/<case>/report.png (python/visco2d/report.py)
#   make fuzz     N mutated decks through the release build (python/visco2d/fuzz.py; N=10000: ~4 min)
#   make checked  every deck under -fcheck=all and the address/undefined-behaviour sanitizers
#   make mpi      the MPI task farm build/mpi/bin/visco2d-farm (installs OpenMPI if missing)
#   make docs     the API pages of every module, from its !> comments, into build/docs/api/ (FORD)
# and, on purpose only:
#   make bless  update reference_outputs/ where the current code's outputs differ (say why in the commit)

SHELL := /bin/bash
PREFIX := build/install
EXE := $(PREFIX)/bin/visco2d
DECKS := $(sort $(wildcard inputs/*.inp))
# The Python tools are the package in python/visco2d/ (doc/python.md): `python3 -m visco2d.<tool>`.
export PYTHONPATH := $(CURDIR)/python$(if $(PYTHONPATH),:$(PYTHONPATH))

.PHONY: all setup build run test bless check clean

all: build

setup:
	@bash scripts/setup.sh

build: setup
	@start=$$(date +%s); echo "visco2d: building with fpm (release profile; full log in build/build.log) ..."; \
	  mkdir -p build; sources=$$(find src app -name '*.[fFc]90' -o -name '*.c' | sort | cksum); \
	  if [ -f build/sources.cksum ] && [ "$$(cat build/sources.cksum)" != "$$sources" ]; then \
	    echo "visco2d: source files added, moved or removed since the last build: rebuilding all (fpm keeps stale objects)"; \
	    rm -rf build/gfortran_*; fi; \
	  echo "$$sources" > build/sources.cksum; fpm install --profile release --prefix $(PREFIX) > build/build.log 2>&1 \
	    || { cat build/build.log; exit 1; }; \
	  n=$$(grep -c 'done\.' build/build.log); \
	  echo "visco2d: built $(EXE) ($$( [ $$n -gt 0 ] && echo "$$n files compiled" || echo "up to date" ), $$(( $$(date +%s) - start )) s)"
	@python3 python/launchers.py $(PREFIX)/bin   # visco2d-batch, visco2d-diff, visco2d-report: doc/python.md
	@python3 -m compileall -q python/visco2d > /dev/null || true   # their byte code once, not at each start: a sweep starts sooner

run: build
	@echo "visco2d: running $(words $(DECKS)) decks into out/"
	@$(EXE) -o out $(DECKS); status=$$?; \
	  echo; python3 -m visco2d.paper_table out; \
	  exit $$status

# make figures: PNGs of the paper's Figs. 2-6 and of the maximum shear at maximum
# deformation into out/figures/ (runs any paper deck missing from out/, and Table 1 on a
# level-4 mesh into out/figures/runs/); python/visco2d/figures.py --help for options.
.PHONY: docs
docs: setup
	@command -v ford > /dev/null || python3 -m pip install -q ford 2>/dev/null || python3 -m pip install -q --break-system-packages ford
	@command -v pyenv > /dev/null && pyenv rehash || true
	@echo "visco2d: API pages with FORD into build/docs/api/ (about a minute) ..."
	@ford --quiet scripts/ford_project.md && echo "visco2d: open build/docs/api/index.html"

.PHONY: figures
figures: build
	@python3 -m visco2d.figures --out out --exe $(EXE)

# make report      one picture per case, <case folder>/report.png, of every case in out/ (from make run or
#                  visco2d -o out): alpha(t), F(t), q(t), p(r), and with a BRUISE card the criterion's envelope
#                  over the r-z section with the bruised region outlined, the key numbers beside;
#                  OUT=dir for another output root, REPORT_ARGS="case1 case2" for some cases only.
.PHONY: report
OUT ?= out
report: setup
	@python3 -m visco2d.report --out $(OUT) $(REPORT_ARGS)

check: build
	@$(EXE) check $(DECKS)

test: build
	@VISCO2D=$(EXE) bash scripts/run_tests.sh

# make bless       on purpose only (say why in the commit): DECK=inputs/x.inp archives just that case
#                  (several: DECK="a.inp b.inp"); without DECK every deck of inputs/, rewriting only the
#                  references that differ beyond the diff's tolerance and printing why; a deck that fails
#                  to run is refused, nothing written; FORCE=1 rewrites even within tolerance (python/visco2d/bless.py).
bless: build
	@python3 -m visco2d.bless --exe $(EXE) $(if $(FORCE),--force) $(or $(DECK),--all)

# make study       what accuracy costs in time: the Table 1 and Table 2 impacts over mesh levels 1-5
#                  and DT 0.04 ... 0.0025 ms into out/study/ (study.csv, study.md, study.png); long: the
#                  level-5 runs dominate. STUDY_ARGS="--levels 1,2,3,4" (or --dts-ms, --cases, --reuse).
# make study-fast  the same on levels 1-3 at DT 0.02 and 0.01 ms into out/study-fast/ (seconds)
.PHONY: study study-fast
study: build
	@python3 -m visco2d.study $(STUDY_ARGS)

study-fast: build
	@python3 -m visco2d.study --fast $(STUDY_ARGS)

# make bench       seconds per phase (visco2d --timing) of the Table 1 impact at levels 1, 4, 5 into
#                  out/bench/ (bench.md, bench.csv); BENCH_ARGS="--levels 1,2,3" for a quick one; then
#                  what plasticity costs (bench_plastic.md; BENCH_PLASTIC_ARGS="--level 2 --repeat 5"), then
#                  the sweep throughput (make bench-sweep, below; about a minute).
.PHONY: bench
bench: build
	@python3 -m visco2d.bench $(BENCH_ARGS)
	@python3 -m visco2d.bench_plastic $(BENCH_PLASTIC_ARGS)   # what plasticity costs: python/visco2d/bench_plastic.py
	@python3 -m visco2d.bench_sweep $(BENCH_SWEEP_ARGS)       # what a sweep loses: python/visco2d/bench_sweep.py

# make bench-sweep  sweep throughput: 200 level-1 peach impacts by visco2d-batch run -j (all cores) against
#                  the per-case compute (all 200 decks in one visco2d process): cases/s achieved, ideal
#                  (cores / per-case compute), efficiency: the median of 3 rounds of both, outputs on a RAM
#                  file system; into out/bench-sweep/ (python/visco2d/bench_sweep.py;
#                  BENCH_SWEEP_ARGS="--cases 400 --level 2 -j 2 --repeat 5", --disk to write onto the disk).
.PHONY: bench-sweep
bench-sweep: build
	@python3 -m visco2d.bench_sweep $(BENCH_SWEEP_ARGS)

# make fuzz        N mutated decks (default 1000) of the seed decks in inputs/ and test/fuzz/ through the
#                  release build, 20 s bound each, report in out/fuzz/ (summary.md, cases.csv, failures/);
#                  exit 1 on any failing deck: a crash, a hang, a partial folder, a NaN/Inf output,
#                  an error without a line, ... (the classes: python/visco2d/fuzz.py --help).
#                  FUZZ_ARGS="--seed 2 --bound 5 -j 4" (python/visco2d/fuzz.py --help).
.PHONY: fuzz
N ?= 1000
fuzz: build
	@python3 -m visco2d.fuzz -n $(N) --exe $(EXE) $(FUZZ_ARGS)

# make checked     the checked build (fpm --profile debug with -fcheck=all and the address and
#                  undefined-behaviour sanitizers, installed in build/checked/) running every deck in
#                  inputs/ and test/fuzz/, clean or FAIL (scripts/test_checked.sh);
#                  CHECKED_N=200 adds that many mutated decks.
.PHONY: checked
CHECKED_N ?= 0
checked: setup
	@mkdir -p build && bash scripts/test_checked.sh $(CHECKED_N) | tee build/checked.log; ! grep -q "^FAIL " build/checked.log

# make mpi         the MPI task farm: build/mpi/bin/visco2d-farm from the same sources, compiled with
#                  the mpif90 wrapper and -DVISCO2D_MPI (app/farm.F90) in fpm's own build folder for that
#                  compiler and flags, so it never rebuilds the default build; OpenMPI (Debian's) is
#                  installed by scripts/setup.sh mpi if missing. Run it with
#                  mpirun -np N build/mpi/bin/visco2d-farm [-q] [-o OUT] DECK...   (doc/command_line.md)
.PHONY: mpi
MPI_PREFIX := build/mpi
mpi: setup
	@bash scripts/setup.sh mpi
	@start=$$(date +%s); echo "visco2d: building the MPI task farm (mpif90 -DVISCO2D_MPI; log in build/mpi-build.log) ..."; \
	  mkdir -p build; fpm install --profile release --compiler mpif90 --flag "-DVISCO2D_MPI" --prefix $(MPI_PREFIX) \
	    > build/mpi-build.log 2>&1 || { cat build/mpi-build.log; exit 1; }; \
	  echo "visco2d: built $(MPI_PREFIX)/bin/visco2d-farm ($$(( $$(date +%s) - start )) s)"

clean:
	rm -rf build out
