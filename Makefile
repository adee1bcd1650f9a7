# make demo: set up everything, run the paper's examples, write their plots to out/.
# make test: set up everything, run the whole suite (ruff and mypy, pytest, then the C++ tests through ctest).
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
BIN    := $(VENV)/bin
OUT    := out
JOBS   ?= 2
#: The C++ sources clang-format keeps in the style of .clang-format (make format, make lint).
CPP_SOURCES = $(shell find cpp bindings tests/cpp -type f \( -name "*.cpp" -o -name "*.hpp" \) | sort)
SOURCES := CMakeLists.txt pyproject.toml $(shell find cmake cpp bindings python -type f -not -name "*.pyc" 2>/dev/null)

.PHONY: demo test setup lint format pytest ctest sanitize bench clean

setup: $(VENV)/.installed

$(VENV)/.system-ok: scripts/setup_system.sh
	PYTHON=$(PYTHON) scripts/setup_system.sh
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip
	$(BIN)/pip install -q cmake ninja
	touch $@

$(VENV)/.installed: $(VENV)/.system-ok $(SOURCES)
	CMAKE_BUILD_PARALLEL_LEVEL=$(JOBS) $(BIN)/pip install -q ".[test,plot,viz,io,dask,fit,app]"
	touch $@

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
	cd $(OUT) && ../$(PY) ../examples/telecover.py
	cd $(OUT) && ../$(PY) ../examples/alignment_map.py
	cd $(OUT) && ../$(PY) ../examples/fit_overlap.py
	cd $(OUT) && ../$(PY) ../examples/fit_real_overlap.py
	cd $(OUT) && ../$(PY) ../examples/optimize_design.py
	@echo "demo: plots written to $(OUT)/"

test: setup
	$(MAKE) lint pytest ctest

# ruff (format and lint, 100 columns, import order) and mypy on the package, as configured in pyproject.toml;
# clang-format (.clang-format, the version pinned in pyproject.toml) on the C++ sources.
lint:
	$(BIN)/clang-format --dry-run --Werror $(CPP_SOURCES)
	$(BIN)/ruff format --check python tests benchmarks examples scripts
	$(BIN)/ruff check python tests benchmarks examples scripts
	$(PY) -m mypy

# Rewrite the C++ sources in the style of .clang-format (whitespace only: includes keep their order).
format: setup
	$(BIN)/clang-format -i $(CPP_SOURCES)

pytest:
	$(PY) -m pytest -q

ctest:
	$(BIN)/cmake -S . -B build/cpp -G Ninja -DLIDAR_OVERLAP_TESTS=ON -DLIDAR_OVERLAP_PYTHON=OFF \
	  -DCMAKE_INSTALL_PREFIX=$(CURDIR)/build/cpp-install -DCMAKE_MAKE_PROGRAM=$(CURDIR)/$(BIN)/ninja
	$(BIN)/cmake --build build/cpp -j $(JOBS)
	rm -rf build/cpp-install  # a fresh tree: the consumer test proves that no internal header is installed
	$(BIN)/cmake --install build/cpp --component cpp
	$(BIN)/ctest --test-dir build/cpp --output-on-failure -j $(JOBS)

# ASan + UBSan build of the core, the C++ tests and the module; ctest and a pytest subset against it.
sanitize: setup
	$(BIN)/pip install -q pybind11
	VENV=$(VENV) JOBS=$(JOBS) scripts/sanitize.sh

# Every file in benchmarks/results/ (speed_accuracy.py also draws failure_map.png and scaling.png) but the
# physics snapshot, a reference that changes are compared with and is written on purpose (--write).
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
	$(PY) benchmarks/bench_alignment.py
	$(PY) benchmarks/bench_fit.py
	$(PY) benchmarks/bench_real_fit.py
	$(PY) benchmarks/bench_optimize.py

clean:
	rm -rf build $(VENV) $(OUT)
