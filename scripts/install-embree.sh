#!/usr/bin/env bash
# Installs Debian's Embree 3 (libembree-dev) for the optional `embree`
# feature, when it is missing. Used by .ci/run; safe to run again.
set -euo pipefail
if ! dpkg -s libembree-dev >/dev/null 2>&1; then
  SUDO=""
  if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq libembree-dev
fi
