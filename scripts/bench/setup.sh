#!/usr/bin/env bash
# Installs what scripts/bench-vs-mitsuba.sh needs, when it is missing; safe to
# run again:
# - Debian's libllvm19 (Dr.Jit's LLVM backend, used by Mitsuba's llvm_*
#   variants; libLLVM 15 crashes it);
# - a private Python virtual environment with Mitsuba 3 and numpy
#   (VENV, default target/bench-venv; /target is ignored by git);
# - the runtime libraries of pbrt-v4, through its own install-deps.sh, when
#   PBRT_DIR holds one.
#
#   bash scripts/bench/setup.sh VENV [PBRT_DIR]
set -euo pipefail
VENV=${1:?usage: setup.sh VENV [PBRT_DIR]}
PBRT_DIR=${2:-}
MITSUBA_VERSION=3.9.1

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
if ! dpkg -s libllvm19 >/dev/null 2>&1; then
  echo "installing Debian's libllvm19 (apt)"
  $SUDO apt-get update -qq
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libllvm19 >/dev/null
fi

if ! "$VENV/bin/python" -c "import mitsuba, numpy, sys; sys.exit(mitsuba.__version__ != '$MITSUBA_VERSION')" 2>/dev/null; then
  echo "installing mitsuba==$MITSUBA_VERSION and numpy into $VENV"
  python3 -m venv "$VENV"
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check "mitsuba==$MITSUBA_VERSION" numpy
fi

# A pbrt-v4 whose set-up fails (the shared build needs AVX-512: on a CPU
# without it the binary dies with SIGILL, exit 132) does not stop the
# benchmark: bench-vs-mitsuba.sh checks the binary itself and skips its row.
if [ -n "$PBRT_DIR" ] && [ -x "$PBRT_DIR/install-deps.sh" ]; then
  rc=0
  bash "$PBRT_DIR/install-deps.sh" >/dev/null 2>&1 || rc=$?
  if [ $rc != 0 ]; then
    echo "pbrt-v4's install-deps.sh failed (exit $rc): its row is skipped if the binary cannot run"
  fi
fi
