# spallbar: a thin facade over CMake. `make help` lists the targets.
#   make setup     install the Debian packages and the Python venv (needs root or sudo)
#   make           Release build in build/release
#   make run       build and run the seed example deck (input/$(RUN_DECK).nml)
#   make test      Debug build (all checks on, -std=f2008) and ctest
#   make figures   run the paper's examples, render its figures into build/release/figures
#   make bench     benchmarks (bench/run.py): table doc/benchmarks-latest.md, plot
#   make fragmentation  fragment size vs strain rate (doc/fragmentation.md): figure, table
#   make clean     remove build/
SHELL := /bin/bash
BUILD_RELEASE ?= build/release
BUILD_DEBUG   ?= build/debug
RUN_DECK      ?= example2
JOBS          ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_COMMON  := -G Ninja -DCMAKE_Fortran_COMPILER=gfortran

.PHONY: all setup build debug run test figures bench fragmentation clean help

all: build

help:
	@sed -n '1,9p' Makefile

setup:
	bash scripts/setup-debian.sh

$(BUILD_RELEASE)/build.ninja:
	cmake -S . -B $(BUILD_RELEASE) $(CMAKE_COMMON) -DCMAKE_BUILD_TYPE=Release -DSPALLBAR_BUILD_TESTING=OFF

$(BUILD_DEBUG)/build.ninja:
	cmake -S . -B $(BUILD_DEBUG) $(CMAKE_COMMON) -DCMAKE_BUILD_TYPE=Debug -DSPALLBAR_BUILD_TESTING=ON

build: $(BUILD_RELEASE)/build.ninja
	cmake --build $(BUILD_RELEASE) -j $(JOBS)

debug: $(BUILD_DEBUG)/build.ninja
	cmake --build $(BUILD_DEBUG) -j $(JOBS)

run: build
	mkdir -p $(BUILD_RELEASE)/runs
	cd input && ../$(BUILD_RELEASE)/bin/spallbar $(RUN_DECK).nml --output ../$(BUILD_RELEASE)/runs/$(RUN_DECK)
	@echo "outputs: $(BUILD_RELEASE)/runs/$(RUN_DECK).{his,prf,evt,frg}"

test: debug
	cd $(BUILD_DEBUG) && ctest --output-on-failure -j $(JOBS)

figures: build
	cmake --build $(BUILD_RELEASE) --target figures
	@echo "figures: $(BUILD_RELEASE)/figures/fig{07c,08b,10,11,12}.png"

PYTHON ?= $(shell test -x .venv/bin/python && echo .venv/bin/python || echo python3)
bench: build
	$(PYTHON) bench/run.py --exe $(BUILD_RELEASE)/bin/spallbar --label "$$(git describe --always --dirty 2>/dev/null || echo build)" \
	  --table doc/benchmarks-latest.md --plot doc/figures/bench_scaling.png

fragmentation: build
	$(PYTHON) plots/fragmentation_study.py --exe $(BUILD_RELEASE)/bin/spallbar --realizations 16 \
	  --out $(BUILD_RELEASE)/fragmentation --figure doc/figures/fragmentation_rate.png \
	  --table doc/fragmentation-table.md

clean:
	rm -rf build
