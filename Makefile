# tidalcrust: make run | make test | make bench | make check-viewers | make install | make package
# Installs the Debian packages it needs (when root; otherwise prints the apt-get line),
# configures with CMake and builds what the target needs: `make run` and `make check-viewers` the
# program only, `make test` the program and the test suite, `make bench` the program and the
# micro-benchmarks, `make` (all) everything.
BUILD    ?= build
JOBS     ?= $(shell nproc 2>/dev/null || echo 2)
PACKAGES := g++ cmake make pkg-config git libeigen3-dev libhdf5-dev libcxxopts-dev libfmt-dev \
            libtomlplusplus-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev libxxhash-dev libboost-dev libudunits2-dev libcgal-dev libsleef-dev \
            slurm-wlm munge python3 \
            python3-h5py python3-numpy python3-xarray python3-matplotlib python3-pyproj python3-geopandas \
            python3-shapely python3-cartopy python3-nbclient python3-nbformat python3-ipykernel
EXE      := $(BUILD)/tidalcrust
# Only for check-viewers: the outside readers the files are checked with.
VIEWER_PACKAGES := python3-paraview python3-mdanalysis python3-h5py python3-numpy xvfb

PREFIX   ?= /usr/local
DESTDIR  ?=

.PHONY: all deps configure build program tests microbench test run bench check-viewers install package clean

all: build

deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "installing:$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	  else \
	    echo "missing packages; run: sudo apt-get install -y$$missing"; exit 1; \
	  fi; \
	fi

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

program: configure
	cmake --build $(BUILD) -j $(JOBS) --target tidalcrust

# The suite's binary (it depends on the program and the portable-kernel probe the tests start).
tests: configure
	cmake --build $(BUILD) -j $(JOBS) --target tidalcrust_tests

microbench: configure
	cmake --build $(BUILD) -j $(JOBS) --target tidalcrust tidalcrust_microbench

test: tests
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The demo: the quick body with a crust free of pre-stress and the local failure rule, end to end;
# the same encounter at half the time step and how alike their fractures are. Figures land in
# checkpoints/quick-balanced/*/analysis/. (workflows/quick.toml keeps the paper's support and rule.)
run: program
	$(EXE) run workflows/quick-balanced.toml
	$(EXE) run workflows/quick-balanced.toml --dt-factor 0.5 --quiet
	@echo; echo "half-dt check (A: dt, B: dt/2):"
	$(EXE) compare checkpoints/quick-balanced/strong/encounter.h5 checkpoints/quick-balanced/dt0.5/strong/encounter.h5
	@echo; echo "figures: $$(ls checkpoints/quick-balanced/strong/analysis/*.png | tr '\n' ' ')"

# Direct sum vs tree code (issue 13) at N ~ 4k (paper-T), 16k, 61k and 224k (shell levels 5-7:
# bench bodies, not physical ones), ending with the table of docs/results/speed.md (the runs and
# the table: tools/results_tables.py, BENCH_RUNS), then gravity alone at 256k random points
# (direct timed on 65k, scaled).
bench: microbench
	$(EXE) bench --config workflows/quick.toml --steps 50
	$(EXE) bench --random 262144 --repeats 3
	python3 tools/results_tables.py bench --exe $(EXE) --work $(BUILD)/bench-runs
	$(BUILD)/tidalcrust_microbench --benchmark_min_time=0.2

# Every .xdmf sidecar of a quick run opened in ParaView's default and legacy XDMF readers, and
# its checkpoints in MDAnalysis's H5MD reader (tools/check_viewers.py; installs the readers;
# /usr/bin/python3: the Debian packages install for the system python).
check-viewers: program
	@$(MAKE) --no-print-directory deps PACKAGES="$(VIEWER_PACKAGES)"
	xvfb-run -a /usr/bin/python3 tools/check_viewers.py --exe $(EXE)

# docs/results/: rerun every table a quick body gives (~2 min of CPU) and rewrite it in its page;
# `make test` checks them (CTest results.quick_tables). tools/results_tables.py.
.PHONY: results-quick
results-quick: build
	python3 tools/results_tables.py quick --exe $(EXE) --write

# The program, the Python package (PREFIX/lib/python3.X/dist-packages; /usr/lib/python3/dist-packages
# for PREFIX=/usr), the man page and the bash completion, under $(DESTDIR)$(PREFIX).
install: configure
	cmake -S . -B $(BUILD) -DCMAKE_INSTALL_PREFIX=$(PREFIX) > /dev/null
	cmake --build $(BUILD) -j $(JOBS) --target tidalcrust tidalcrust_usage_docs
	DESTDIR=$(DESTDIR) cmake --install $(BUILD)

# The Debian package of the same install rules (CPack, cmake/packaging.cmake):
# $(BUILD)/tidalcrust_<version>_amd64.deb; `sudo apt install ./$(BUILD)/tidalcrust_*.deb` installs it
# with its dependencies. For other machines configure with -DTIDALCRUST_NATIVE=OFF (no -march=native).
package: configure
	cmake --build $(BUILD) -j $(JOBS) --target tidalcrust tidalcrust_usage_docs
	cd $(BUILD) && cpack -G DEB

clean:
	rm -rf $(BUILD)
