# spallbar: a thin facade over CMake. `make help` lists the targets.
#   make setup     install the Debian packages and the Python venv (needs root or sudo)
#   make           Release build in build/release
#   make run       build and run the seed example deck (input/$(RUN_DECK).nml)
#   make test      Debug build (all checks on, -std=f2008) and ctest; unit tests under real
#                  pFUnit with PFUNIT_PREFIX=DIR, else under the translator (doc/build.md)
#   make test-translator  the .pf unit tests again through tests/pf2f90.py (what CI adds)
#   make figures   run the paper's examples, render its figures into build/release/figures
#   make bench     benchmarks (bench/run.py): table doc/benchmarks-latest.md, plot
#   make event-study  the event layer's energy, momentum, invariance table (bench/event_study.py)
#   make consistency  the event corrections under refinement: x_drift, e_lost_w (bench/consistency.py)
#   make case2-ensemble  case 2's predictability horizons and ensemble statistics (bench/case2_ensemble.py)
#   make blows     the striking mass's worked examples: doc/figures/{drop_hammer,striker}_blows.png
#   make fragmentation  fragment size vs strain rate (doc/fragmentation.md): brittle Weibull bar
#                  and the cohesive ZMR benchmark (plots/zmr_study.py): figures, tables
#   make golden REF=REV  every output of the Release program against revision REV's (scripts/golden.py)
#   make archive-check   every deck of input/ against the results archive (archive/, doc/archive.md)
#   make rebaseline WHY="..."  rewrite archive/ with this program; WHY goes to archive/CHANGES.md
#   make install PREFIX=DIR  install spallbar, spallbar-compare, plots, example decks, man page
#   make clean     remove build/
SHELL := /bin/bash
BUILD_RELEASE ?= build/release
# Unit-test framework: PFUNIT_PREFIX=DIR (pFUnit 4.14 installed there, e.g. by
# ../shared/tools/pfunit/build-pfunit.sh DIR) builds the tests against real pFUnit in its own
# folder; without it CMake looks for pFUnit and falls back to the translator.
PFUNIT_PREFIX ?=
ifneq ($(strip $(PFUNIT_PREFIX)),)
BUILD_DEBUG    ?= build/debug-pfunit
TEST_FRAMEWORK ?= pfunit
else
BUILD_DEBUG    ?= build/debug
TEST_FRAMEWORK ?= auto
endif
CTEST_ARGS ?=
RUN_DECK      ?= example2
JOBS          ?= $(shell nproc 2>/dev/null || echo 2)
# extra CMake options, e.g. make build CMAKE_FLAGS=-DSPALLBAR_NATIVE=OFF (a cluster binary)
CMAKE_FLAGS   ?=
CMAKE_COMMON  := -G Ninja -DCMAKE_Fortran_COMPILER=gfortran $(CMAKE_FLAGS)

PREFIX ?= /usr/local

.PHONY: install all setup build debug debug-configure run test test-translator figures bench event-study consistency case2-ensemble blows fragmentation golden archive-check rebaseline clean help

all: build

help:
	@sed -n '1,20p' Makefile

setup:
	bash scripts/setup-debian.sh

$(BUILD_RELEASE)/build.ninja:
	cmake -S . -B $(BUILD_RELEASE) $(CMAKE_COMMON) -DCMAKE_BUILD_TYPE=Release -DSPALLBAR_BUILD_TESTING=OFF

# configured on every call: the framework given now wins over what the folder cached
debug-configure:
	cmake -S . -B $(BUILD_DEBUG) $(CMAKE_COMMON) -DCMAKE_BUILD_TYPE=Debug -DSPALLBAR_BUILD_TESTING=ON \
	  -DSPALLBAR_TEST_FRAMEWORK=$(TEST_FRAMEWORK) $(if $(strip $(PFUNIT_PREFIX)),-DCMAKE_PREFIX_PATH=$(abspath $(PFUNIT_PREFIX)))

build: $(BUILD_RELEASE)/build.ninja
	cmake --build $(BUILD_RELEASE) -j $(JOBS)

debug: debug-configure
	cmake --build $(BUILD_DEBUG) -j $(JOBS)

run: build
	mkdir -p $(BUILD_RELEASE)/runs
	cd input && ../$(BUILD_RELEASE)/bin/spallbar $(RUN_DECK).nml --output ../$(BUILD_RELEASE)/runs/$(RUN_DECK)
	@echo "outputs: $(BUILD_RELEASE)/runs/$(RUN_DECK).{his,prf,evt,frg}"

test: debug
	cd $(BUILD_DEBUG) && ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS)
	@python3 tests/pf_summary.py $(BUILD_DEBUG)

test-translator:
	$(MAKE) test PFUNIT_PREFIX= TEST_FRAMEWORK=translator BUILD_DEBUG=build/debug-translator \
	  CTEST_ARGS="-L pf"

figures: build
	cmake --build $(BUILD_RELEASE) --target figures
	@echo "figures: $(BUILD_RELEASE)/figures/fig{07c,08b,10,11,12,13}.png"

PYTHON ?= $(shell test -x .venv/bin/python && echo .venv/bin/python || echo python3)
bench: build
	$(PYTHON) bench/run.py --exe $(BUILD_RELEASE)/bin/spallbar --label "$$(git describe --always --dirty 2>/dev/null || echo build)" \
	  --table doc/benchmarks-latest.md --plot doc/figures/bench_scaling.png

# doc/method.md "What the corrections move": x_drift and e_lost_w under refinement, every rule
consistency: build
	$(PYTHON) bench/consistency.py --exe $(BUILD_RELEASE)/bin/spallbar --work $(BUILD_RELEASE)/consistency \
	  --json $(BUILD_RELEASE)/consistency/results.json --case2-meshes 19,95,190,380

# case 2 ensembles (issue 34): horizons per mesh and policy, mean +- std at 0.1, 0.3, 0.6 s
case2-ensemble: build
	$(PYTHON) bench/case2_ensemble.py --exe $(BUILD_RELEASE)/bin/spallbar --work $(BUILD_RELEASE)/case2-ensemble \
	  --table $(BUILD_RELEASE)/case2-ensemble/tables.md

# doc/benchmarks.md "The event study": the tables doc/validation.md summarises (wave measure)
event-study: build
	$(PYTHON) bench/event_study.py --exe $(BUILD_RELEASE)/bin/spallbar --work $(BUILD_RELEASE)/event-study \
	  --energy-column e_wave --json $(BUILD_RELEASE)/event-study/results.json \
	  --label "$$(git describe --always --dirty 2>/dev/null || echo build), wave measure"

# doc/impactor.md: the worked examples' blows (input/drop_hammer.nml, input/striker_spall.nml)
blows: build
	mkdir -p $(BUILD_RELEASE)/blows
	cd input && for d in drop_hammer striker_spall; do \
	  ../$(BUILD_RELEASE)/bin/spallbar $$d.nml --quiet --output ../$(BUILD_RELEASE)/blows/$$d || exit 1; done
	$(PYTHON) plots/blows.py $(BUILD_RELEASE)/blows/drop_hammer --units s -o doc/figures/drop_hammer_blows.png
	$(PYTHON) plots/blows.py $(BUILD_RELEASE)/blows/striker_spall -o doc/figures/striker_blows.png

fragmentation: build
	$(PYTHON) plots/fragmentation_study.py --exe $(BUILD_RELEASE)/bin/spallbar --realizations 16 \
	  --out $(BUILD_RELEASE)/fragmentation --figure doc/figures/fragmentation_rate.png \
	  --table doc/fragmentation-table.md
	$(PYTHON) plots/zmr_study.py --exe $(BUILD_RELEASE)/bin/spallbar --realizations 16 --ranks 2 \
	  --out $(BUILD_RELEASE)/zmr --figure doc/figures/zmr_fragment_size.png \
	  --table doc/zmr-table.md --json $(BUILD_RELEASE)/zmr/results.json

clean:
	rm -rf build

REF ?= HEAD
install: build
	cmake --install $(BUILD_RELEASE) --prefix $(PREFIX)

archive-check: build
	python3 scripts/archive.py check --exe $(BUILD_RELEASE)/bin/spallbar --compare $(BUILD_RELEASE)/bin/spallbar-compare

rebaseline: build
	python3 scripts/archive.py rebaseline --exe $(BUILD_RELEASE)/bin/spallbar --why "$(WHY)"

golden: build
	python3 scripts/golden.py --exe $(BUILD_RELEASE)/bin/spallbar --ref-rev $(REF) --work $(BUILD_RELEASE)/golden
