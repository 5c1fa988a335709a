# visco2d — the two commands of a new user:
#   make run    install what is missing, build (release), run every deck in inputs/ into out/,
#               then print the impact results beside the paper's (scripts/paper_table.py)
#   make test   install what is missing, run the tests and the reference-output diffs
#   make figures  pictures of the paper's figures into out/figures/ (scripts/figures.py)
#   make report   one picture per case of out/: out/<case>/report.png (scripts/report.py)
#   make fuzz     N mutated decks through the release build (scripts/fuzz.py; N=10000: ~4 min)
#   make checked  every deck under -fcheck=all and the address/undefined-behaviour sanitizers
# and, on purpose only:
#   make bless  regenerate reference_outputs/ from the current code (say why in the commit)

SHELL := /bin/bash
PREFIX := build/install
EXE := $(PREFIX)/bin/visco2d
DECKS := $(sort $(wildcard inputs/*.inp))

.PHONY: all setup build run test bless check clean

all: build

setup:
	@bash scripts/setup.sh

build: setup
	@start=$$(date +%s); echo "visco2d: building with fpm (release profile; full log in build/build.log) ..."; \
	  mkdir -p build; fpm install --profile release --prefix $(PREFIX) > build/build.log 2>&1 \
	    || { cat build/build.log; exit 1; }; \
	  n=$$(grep -c 'done\.' build/build.log); \
	  echo "visco2d: built $(EXE) ($$( [ $$n -gt 0 ] && echo "$$n files compiled" || echo "up to date" ), $$(( $$(date +%s) - start )) s)"
	@install -m 755 scripts/visco2d_batch.py $(PREFIX)/bin/visco2d-batch   # sweeps, all cores, the cluster: doc/batch.md

run: build
	@echo "visco2d: running $(words $(DECKS)) decks into out/"
	@$(EXE) -o out $(DECKS); status=$$?; \
	  echo; python3 scripts/paper_table.py out; \
	  exit $$status

# make figures: PNGs of the paper's Figs. 2-6 and of the maximum shear at maximum
# deformation into out/figures/ (runs any paper deck missing from out/, and Table 1 on a
# level-4 mesh into out/figures/runs/); scripts/figures.py --help for options.
.PHONY: figures
figures: build
	@python3 scripts/figures.py --out out --exe $(EXE)

# make report      one picture per case, <case folder>/report.png, of every case in out/ (from make run or
#                  visco2d -o out): alpha(t), F(t), q(t), p(r), and with a BRUISE card the criterion's envelope
#                  over the r-z section with the bruised region outlined, the key numbers beside;
#                  OUT=dir for another output root, REPORT_ARGS="case1 case2" for some cases only.
.PHONY: report
OUT ?= out
report: setup
	@python3 scripts/report.py --out $(OUT) $(REPORT_ARGS)

check: build
	@$(EXE) check $(DECKS)

test: build
	@VISCO2D=$(EXE) bash scripts/run_tests.sh

bless: build
	@rm -rf build/bless && mkdir -p build/bless
	@$(EXE) -q -o build/bless $(DECKS)
	@for deck in $(DECKS); do \
	  case_name=$$(basename $$deck .inp); \
	  mkdir -p reference_outputs/$$case_name; \
	  grep -v '^cpu_s = ' build/bless/$$case_name/summary.txt > reference_outputs/$$case_name/summary.txt; \
	  cp build/bless/$$case_name/history.csv reference_outputs/$$case_name/history.csv; \
	done
	@echo "reference_outputs/ regenerated for $(words $(DECKS)) decks: review 'git diff reference_outputs' and say why in the commit"

# make study       what accuracy costs in time: the Table 1 and Table 2 impacts over mesh levels 1-5
#                  and DT 0.04 ... 0.0025 ms into out/study/ (study.csv, study.md, study.png); long: the
#                  level-5 runs dominate. STUDY_ARGS="--levels 1,2,3,4" (or --dts-ms, --cases, --reuse).
# make study-fast  the same on levels 1-3 at DT 0.02 and 0.01 ms into out/study-fast/ (seconds)
.PHONY: study study-fast
study: build
	@python3 scripts/study.py $(STUDY_ARGS)

study-fast: build
	@python3 scripts/study.py --fast $(STUDY_ARGS)

# make bench       seconds per phase (visco2d --timing) of the Table 1 impact at levels 1, 4, 5 into
#                  out/bench/ (bench.md, bench.csv); BENCH_ARGS="--levels 1,2,3" for a quick one.
.PHONY: bench
bench: build
	@python3 scripts/bench.py $(BENCH_ARGS)

# make fuzz        N mutated decks (default 1000) of the seed decks in inputs/ and test/fuzz/ through the
#                  release build, 20 s bound each, report in out/fuzz/ (summary.md, cases.csv, failures/);
#                  exit 1 on any failing deck: a crash, a hang, a partial folder, a NaN/Inf output,
#                  an error without a line, ... (the classes: scripts/fuzz.py --help).
#                  FUZZ_ARGS="--seed 2 --bound 5 -j 4" (scripts/fuzz.py --help).
.PHONY: fuzz
N ?= 1000
fuzz: build
	@python3 scripts/fuzz.py -n $(N) --exe $(EXE) $(FUZZ_ARGS)

# make checked     the checked build (fpm --profile debug with -fcheck=all and the address and
#                  undefined-behaviour sanitizers, installed in build/checked/) running every deck in
#                  inputs/ and test/fuzz/, clean or FAIL (scripts/test_checked.sh);
#                  CHECKED_N=200 adds that many mutated decks.
.PHONY: checked
CHECKED_N ?= 0
checked: setup
	@mkdir -p build && bash scripts/test_checked.sh $(CHECKED_N) | tee build/checked.log; ! grep -q "^FAIL " build/checked.log

clean:
	rm -rf build out
