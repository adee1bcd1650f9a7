#!/usr/bin/env bash
# Installs what the build needs from Debian's packages when it is missing: a C++ compiler,
# pkg-config, FFTW3 (double precision, with its threads library), Python's venv module, and an
# off-screen OpenGL (Mesa's EGL, or OSMesa) for the 3D scenes rendered without a display, and as root
# Debian's chromium and chromedriver for the browser tests of the interactive view.
# Without root or apt-get it prints the exact command to run instead and fails. apt's output goes to
# build/setup-system.log: one line says what is installed and where the log is.
set -euo pipefail
PYTHON=${PYTHON:-python3}

missing=()
command -v g++ >/dev/null 2>&1 || missing+=(g++)
command -v pkg-config >/dev/null 2>&1 || missing+=(pkg-config)
fftw_threads=no
for f in /usr/lib/*/libfftw3_threads.so /usr/lib/libfftw3_threads.so /usr/local/lib/libfftw3_threads.so; do
  [ -e "$f" ] && fftw_threads=yes
done
if ! pkg-config --exists fftw3 2>/dev/null || [ "$fftw_threads" = no ]; then
  missing+=(libfftw3-dev)
fi
if ! "$PYTHON" -c "import venv, ensurepip" >/dev/null 2>&1; then
  ver=$("$PYTHON" -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')
  missing+=("python${ver}-venv")
fi
if ! "$PYTHON" -c "import sysconfig, os, sys; sys.exit(not os.path.exists(os.path.join(sysconfig.get_paths()['include'], 'Python.h')))"; then
  missing+=(python3-dev)
fi

# VTK opens libGL/libEGL/libOSMesa at run time: off-screen it needs Mesa's EGL or OSMesa.
libs=$(ldconfig -p 2>/dev/null || true)
if ! { grep -q "libEGL_mesa.so.0" <<<"$libs" && grep -q "libEGL.so.1" <<<"$libs"; } && ! grep -q "libOSMesa.so" <<<"$libs"; then
  missing+=(libosmesa6)
fi

# The browser tests of the interactive view (tests/test_view_browser.py) drive Debian's chromium through its
# chromedriver; nothing downloads a browser. Missing without root, those tests are skipped and say this.
if ! command -v chromium >/dev/null 2>&1 || ! command -v chromedriver >/dev/null 2>&1; then
  if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
    missing+=(chromium chromium-driver)
  else
    echo "setup: the browser tests need chromium and its driver: sudo apt-get install -y chromium chromium-driver" >&2
  fi
fi

[ ${#missing[@]} -eq 0 ] && exit 0

cmd="apt-get update && apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
  # apt's progress (a few hundred lines) goes to the log; one line here, the log's tail on failure.
  log="$(cd "$(dirname "$0")/.." && pwd)/build/setup-system.log"
  mkdir -p "$(dirname "$log")"
  printf 'setup: installing %s from Debian'"'"'s packages (log: %s) ... ' "${missing[*]}" "$log"
  export DEBIAN_FRONTEND=noninteractive
  if ! { apt-get update && apt-get install -y --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
    echo "failed"
    echo "setup: apt-get failed; the last lines of $log:" >&2
    tail -n 30 "$log" >&2
    exit 1
  fi
  echo "done"
else
  echo "setup: missing ${missing[*]}. Run this as root, then run make again:" >&2
  echo "  sudo sh -c '$cmd'" >&2
  exit 1
fi
