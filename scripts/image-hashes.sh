#!/usr/bin/env bash
# Renders every scene of the suite (the default scene, scenes/caustics,
# scenes/test) with every integrator and caustic mode at 1 and 2 threads,
# small and fast, and prints one SHA-256 of the pixels (PFM) per render.
# Two builds are bit-identical on the suite when their outputs are equal:
#   bash scripts/image-hashes.sh OLD_LUMIS > old.txt
#   bash scripts/image-hashes.sh NEW_LUMIS > new.txt && diff old.txt new.txt
set -euo pipefail
lumis=${1:-target/release/lumis}
lumis=$(realpath "$lumis")
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Only top-level files (the meshes in scenes/caustics are included by others).
mapfile -t files < <(grep -l WorldBegin scenes/caustics/*.pbrt scenes/test/*.pbrt)
scenes=(default "${files[@]}")
runs=(
  "--integrator path"
  "--integrator direct"
  "--integrator photon --caustics mis"
  "--integrator photon --caustics photons"
  "--integrator photon --caustics gather"
  "--integrator photon --caustics mis --alpha spp --heuristic power --kernel cone"
)
for s in "${scenes[@]}"; do
  arg=$s; [ "$s" = default ] && arg=""
  for r in "${runs[@]}"; do
    for t in 1 2; do
      # shellcheck disable=SC2086
      "$lumis" render $arg $r --resolution 64x48 --spp 8 --seed 7 \
        --photons 20000 --caustic-photons 20000 --threads "$t" -q \
        -o "$tmp/o.pfm" >/dev/null 2>"$tmp/err" || { echo "$s | $r | t$t FAILED"; cat "$tmp/err"; continue; }
      h=$(sha256sum "$tmp/o.pfm" | cut -c1-16)
      echo "$s | $r | t$t $h"
    done
  done
done
