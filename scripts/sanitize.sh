#!/usr/bin/env bash
# make sanitize: the core, the C++ tests and the Python module built with AddressSanitizer and
# UndefinedBehaviorSanitizer (no recovery: the first finding fails), then ctest and a pytest subset that
# exercises the core's numerics and its hostile-input paths against the sanitized module.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=${VENV:-.venv}
JOBS=${JOBS:-2}
BUILD=build/sanitize
PYTHON_BIN=$(realpath "$VENV/bin/python")

"$VENV/bin/cmake" -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DLIDAR_OVERLAP_SANITIZE=ON \
  -DLIDAR_OVERLAP_TESTS=ON -DLIDAR_OVERLAP_PYTHON=ON -DPython_EXECUTABLE="$PYTHON_BIN" \
  -Dpybind11_DIR="$("$PYTHON_BIN" -m pybind11 --cmakedir)" -DCMAKE_INSTALL_PREFIX="$PWD/$BUILD/install" \
  -DCMAKE_MAKE_PROGRAM="$PWD/$VENV/bin/ninja" >/dev/null
"$VENV/bin/cmake" --build "$BUILD" -j "$JOBS"
rm -rf "$BUILD/install" && "$VENV/bin/cmake" --install "$BUILD" --component cpp >/dev/null

export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# ctest without the find_package consumer (a Release project of its own, not built with the sanitizers).
"$VENV/bin/ctest" --test-dir "$BUILD" --output-on-failure -j "$JOBS" -E find_package_consumer

# The Python package with the sanitized module beside it; the interpreter is not sanitized, so the
# runtimes are preloaded. Leaks are not checked there (CPython keeps its allocations until exit).
PKG="$BUILD/pkg"
rm -rf "$PKG" && mkdir -p "$PKG"
cp -r python/lidar_overlap "$PKG/"
rm -f "$PKG"/lidar_overlap/_core*.so
cp "$(find "$BUILD/bindings" -name '_core*.so' | head -1)" "$PKG/lidar_overlap/"
RUNTIMES="$(g++ -print-file-name=libasan.so):$(g++ -print-file-name=libubsan.so)"
export LIDAR_OVERLAP_PROBE_MEMORY=-1          # ASan reserves terabytes of address space: no rlimit
export LIDAR_OVERLAP_PROBE_TIME_LIMIT=60      # the sanitized core runs ~3-5x slower
for file in test_bad_input test_bad_input_field_beams test_limits test_overlap_fo test_aberrations \
            test_turbulence \
            test_hostile_sizes test_hostile_slow_inputs test_hostile_extreme_values \
            test_hostile_error_names test_hostile_results test_hostile_inputs; do
  echo "sanitize: pytest tests/$file.py"
  LD_PRELOAD="$RUNTIMES" PYTHONPATH="$PKG" "$VENV/bin/python" -m pytest -q -p no:cacheprovider -x "tests/$file.py"
done
echo "sanitize: clean"
