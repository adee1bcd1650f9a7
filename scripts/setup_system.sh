#!/usr/bin/env bash
# Installs what the build needs from Debian's packages when it is missing: a C++ compiler,
# pkg-config, FFTW3 (double precision, with its threads library) and Python's venv module.
# Without root or apt-get it prints the exact command to run instead and fails.
set -euo pipefail
PYTHON=${PYTHON:-python3}

missing=()
command -v g++ >/dev/null 2>&1 || missing+=(g++)
command -v pkg-config >/dev/null 2>&1 || missing+=(pkg-config)
if ! pkg-config --exists fftw3 2>/dev/null || ! ls /usr/lib/*/libfftw3_threads.so /usr/lib/libfftw3_threads.so \
      /usr/local/lib/libfftw3_threads.so >/dev/null 2>&1; then
  missing+=(libfftw3-dev)
fi
if ! "$PYTHON" -c "import venv, ensurepip" >/dev/null 2>&1; then
  ver=$("$PYTHON" -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')
  missing+=("python${ver}-venv")
fi
if ! "$PYTHON" -c "import sysconfig, os, sys; sys.exit(not os.path.exists(os.path.join(sysconfig.get_paths()['include'], 'Python.h')))"; then
  missing+=(python3-dev)
fi

[ ${#missing[@]} -eq 0 ] && exit 0

cmd="apt-get update && apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "setup: installing ${missing[*]} from Debian's packages"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: missing ${missing[*]}. Run this as root, then run make again:" >&2
  echo "  sudo sh -c '$cmd'" >&2
  exit 1
fi
