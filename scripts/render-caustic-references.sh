#!/bin/sh
# Renders the references of scenes/caustics/ into scenes/caustics/ref/:
# `path` with a wall-clock budget on ONE thread (the sample count it reached is
# in the EXR header, `lumis:spp`, and in the sidecar .txt; rerunning with
# `--spp N` in place of `--time` gives the identical image), except for the
# scenes lit by delta lights (point, spot), whose caustics `path` cannot see:
# those use `photon --caustics photons` with many aimed caustic photons.
#
#   scripts/render-caustic-references.sh [LUMIS_BINARY] [SECONDS_PER_SCENE] [SCENE...]
set -eu
LUMIS=${1:-target/release/lumis}
SECS=${2:-420}
shift 2 2>/dev/null || true
DIR=scenes/caustics
mkdir -p "$DIR/ref"
SCENES=${*:-sphere-small-light sphere-large-light glossy-floor through-glass water-pool ring-point spot-glass}
for s in $SCENES; do
    case $s in
    ring-point | spot-glass)
        set -- --integrator photon --caustics photons --aim-caustics \
            --caustic-photons 20000000 --photons 2000000 --time "$SECS" ;;
    *)
        set -- --integrator path --time "$SECS" ;;
    esac
    out="$DIR/ref/$s.exr"
    log=$("$LUMIS" render "$DIR/$s.pbrt" "$@" --threads 1 --seed 7 -q -o "$out" 2>&1)
    spp=$(printf '%s\n' "$log" | sed -n 's/.* \([0-9][0-9]*\) spp (.*/\1/p' | tail -1)
    {
        echo "reference for $DIR/$s.pbrt"
        echo "command: lumis render $DIR/$s.pbrt $* --threads 1 --seed 7 -q -o $out"
        echo "samples per pixel: $spp (same image: replace --time $SECS by --spp $spp)"
        echo "made: $(date -u +%Y-%m-%dT%H:%MZ) on $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
        printf '%s\n' "$log"
    } >"$DIR/ref/$s.txt"
    echo "$s: $spp spp"
done
