#!/bin/sh
# Takes a headless-Chromium screenshot of a study report, to check that the
# page looks right in a real browser when opened from disk (no server, no
# network). Installs Debian's `chromium` if it is missing.
#
#   scripts/screenshot-report.sh docs/study/index.html docs/study/screenshot.png [WIDTHxHEIGHT]
set -eu
PAGE=${1:?usage: screenshot-report.sh REPORT.html OUT.png [WxH]}
OUT=${2:?usage: screenshot-report.sh REPORT.html OUT.png [WxH]}
SIZE=${3:-1400x2400}
if ! command -v chromium >/dev/null 2>&1; then
    apt-get update && apt-get install -y chromium
fi
PROFILE=$(mktemp -d)
trap 'rm -rf "$PROFILE"' EXIT
ABS_PAGE=$(cd "$(dirname "$PAGE")" && pwd)/$(basename "$PAGE")
case $OUT in /*) ABS_OUT=$OUT ;; *) ABS_OUT=$(pwd)/$OUT ;; esac
chromium --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run \
    --user-data-dir="$PROFILE" --hide-scrollbars \
    --window-size="$(echo "$SIZE" | tr x ,)" --screenshot="$ABS_OUT" "file://$ABS_PAGE"
echo "wrote $ABS_OUT"
