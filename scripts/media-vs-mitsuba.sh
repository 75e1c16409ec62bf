#!/usr/bin/env bash
# lumis `path` against Mitsuba 3's `volpath` (llvm_ad_rgb) on the media
# scenes, at the same samples per pixel, seed and maximum depth, 2 threads
# each: the agreement of the two images (means per channel, 4x4 tiles) and
# their times. A check of the volumetric path tracer against an independent
# renderer, not a test: nothing in `cargo test` runs it. Everything it
# installs or makes goes under target/ (Mitsuba in target/bench-venv, with
# Debian's libllvm19; scenes and images in target/media-vs-mitsuba).
#
#   scripts/media-vs-mitsuba.sh [--spp N] [--seed S]
#
# Scenes: scenes/media/fog-glass.pbrt (160x120), the same without its glass
# sphere (fog, light and floor only: no caustic, so less noise), and
# scenes/media/tea.pbrt (128x128). Default 2048 spp (about 4 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
SPP=2048 SEED=1
while [ $# -gt 0 ]; do
  case $1 in
  --spp) SPP=$2; shift ;;
  --seed) SEED=$2; shift ;;
  -h | --help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "media-vs-mitsuba.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
OUT=$ROOT/target/media-vs-mitsuba
VENV=$ROOT/target/bench-venv
PY=$VENV/bin/python
export DRJIT_LIBLLVM_PATH=${DRJIT_LIBLLVM_PATH:-/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1}
bash scripts/bench/setup.sh "$VENV"
cargo build --release -q -p lumis
LUMIS=${CARGO_TARGET_DIR:-$ROOT/target}/release/lumis
mkdir -p "$OUT"
# The fog without its sphere (its AttributeBegin ... AttributeEnd block).
python3 - "$OUT/fog-noglass-src.pbrt" <<'PY'
import sys
s = open("scenes/media/fog-glass.pbrt").read()
a = s.index('AttributeBegin\n  Material "dielectric"')
b = s.index("AttributeEnd", a) + len("AttributeEnd\n")
open(sys.argv[1], "w").write(s[:a] + s[b:])
PY
for case in "fog-glass scenes/media/fog-glass.pbrt 160x120" \
  "fog-noglass $OUT/fog-noglass-src.pbrt 160x120" "tea scenes/media/tea.pbrt 128x128"; do
  set -- $case
  python3 scripts/bench/convert.py "$2" "$OUT" "$1" --res "$3" --maxdepth 20
  echo "== $1 ($3, $SPP spp, seed $SEED)"
  "$PY" scripts/bench/run_mitsuba.py "$OUT/$1.xml" "$OUT/$1-mitsuba.exr" --spp "$SPP" --threads 2 --seed "$SEED"
  "$LUMIS" render "$OUT/$1.pbrt" --spp "$SPP" --threads 2 --seed "$SEED" -q -o "$OUT/$1-lumis.exr"
  "$LUMIS" compare "$OUT/$1-lumis.exr" "$OUT/$1-mitsuba.exr" | grep -E "mean|ratio"
  "$PY" scripts/bench/tiles.py "$OUT/$1-mitsuba.exr" "$OUT/$1-lumis.exr"
done
