#!/usr/bin/env bash
# Equal-time errors on the media scenes: `path` and `photon` in each caustic
# mode (`mis`, `photons`, `gather`) at each time budget, one seed, 2
# threads, against long `path` references; errors (MSE) over the whole image
# and over the volumetric caustic: the beam under the sphere in fog-glass,
# the caustic through the tea under its sphere. A benchmark, not a test.
#
#   scripts/media-equal-time.sh [--times "15 60"] [--seed S] [--ref-spp N]
#
# Everything goes under target/media-equal-time: the references (made once,
# `path` at --ref-spp samples, default 131072: about 10 and 4 minutes),
# the renders and table.md.
set -euo pipefail
cd "$(dirname "$0")/.."
TIMES="15 60" SEED=1 REF_SPP=131072
while [ $# -gt 0 ]; do
  case $1 in
  --times) TIMES=$2; shift ;;
  --seed) SEED=$2; shift ;;
  --ref-spp) REF_SPP=$2; shift ;;
  -h | --help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "media-equal-time.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
OUT=target/media-equal-time
mkdir -p "$OUT"
cargo build --release -q -p lumis
LUMIS=${CARGO_TARGET_DIR:-target}/release/lumis
mse() { "$LUMIS" compare "$@" | awk '/^MSE/ { print $2 }'; }
{
  echo "| scene | region | method | ${TIMES// / s | } s |"
  echo "|---|---|---|$(for _ in $TIMES; do printf -- '---|'; done)"
} > "$OUT/table.md"
# name, scene file, resolution, region (fractions x0,x1,y0,y1) and its name
for case in "fog-glass scenes/media/fog-glass.pbrt 80x60 0.425,0.575,0.4,0.8667 beam" \
  "tea scenes/media/tea.pbrt 64x64 0.35,0.65,0.68,0.86 caustic"; do
  set -- $case
  name=$1 scene=$2 res=$3 region=$4 rname=$5
  ref=$OUT/$name-ref.exr
  if [ ! -f "$ref" ]; then
    echo "reference: $name, path, $REF_SPP spp"
    "$LUMIS" render "$scene" --integrator path --resolution "$res" --spp "$REF_SPP" --threads 2 --seed 2024 -q -o "$ref"
  fi
  for method in path mis photons gather; do
    row_img="| $name | image | $method |" row_reg="| $name | $rname | $method |"
    for t in $TIMES; do
      out=$OUT/$name-$method-$t.exr
      if [ $method = path ]; then
        "$LUMIS" render "$scene" --integrator path --resolution "$res" --time "$t" --threads 2 --seed "$SEED" -q -o "$out"
      else
        "$LUMIS" render "$scene" --integrator photon --caustics "$method" --resolution "$res" --time "$t" --threads 2 --seed "$SEED" -q -o "$out"
      fi
      row_img="$row_img $(mse "$out" "$ref") |"
      row_reg="$row_reg $(mse "$out" "$ref" --mask "$region") |"
    done
    echo "$row_img" >> "$OUT/table.md"
    echo "$row_reg" >> "$OUT/table.md"
  done
done
cat "$OUT/table.md"
