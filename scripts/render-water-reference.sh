#!/bin/sh
# Renders the reference of scenes/water/water.pbrt into scenes/water/ref/:
# `path` (unbiased), 200000 spp, seed 7, two threads, at nice 19, with a
# checkpoint every 300 s. If the checkpoint exists, the render resumes from it
# (it must be the same lumis build: a checkpoint of another version is
# refused); the image is bit-identical to an uninterrupted run. Run it from the
# repository's root. At the end it writes the sidecar water.txt.
#
#   scripts/render-water-reference.sh [LUMIS_BINARY] [CHECKPOINT]
#
# Copy the binary out of the target folder first (cp target/release/lumis
# /somewhere/lumis) so that rebuilding during the render does not replace it.
set -eu
LUMIS=${1:-target/release/lumis}
CKPT=${2:-scenes/water/ref/water.ckpt}
SCENE=scenes/water/water.pbrt
OUT=scenes/water/ref/water.exr
SPP=200000
ARGS="--integrator path --spp $SPP --threads 2 --seed 7 -q -o $OUT"
mkdir -p scenes/water/ref
if [ -f "$CKPT" ]; then
    echo "resuming $CKPT"
    set -- render --resume "$CKPT" -o "$OUT" -q --checkpoint-every 300
else
    # shellcheck disable=SC2086
    set -- render "$SCENE" $ARGS --checkpoint "$CKPT" --checkpoint-every 300
fi
start="$(date -u +%Y-%m-%dT%H:%MZ), load $(cut -d' ' -f1-3 /proc/loadavg)"
status=0
log=$(nice -n 19 "$LUMIS" "$@" 2>&1) || status=$?
# Appends this run to the sidecar: $1 the sample count line, $2 how it ended.
sidecar() {
    {
        echo "reference for $SCENE"
        echo "command: lumis render $SCENE $ARGS --checkpoint $CKPT --checkpoint-every 300 (under nice -n 19)"
        echo "samples per pixel: $1"
        echo "this run: started $start; $2 $(date -u +%Y-%m-%dT%H:%MZ) on $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
        printf '%s\n' "$log"
    } >>scenes/water/ref/water.txt
}
if [ "$status" -eq 130 ]; then
    # interrupted: lumis wrote the image so far and the checkpoint; record
    # its true sample count (a later run resumes and appends again)
    spp=$(printf '%s\n' "$log" | sed -n 's/.*wrote the image so far (\([0-9]*\) spp).*/\1/p' | tail -1)
    sidecar "${spp:-unknown} (interrupted: the image so far; $SPP planned)" interrupted
fi
if [ "$status" -ne 0 ]; then
    # interrupted (130) or failed: the checkpoint holds what was done
    printf '%s\n' "$log" >&2
    exit "$status"
fi
sidecar "$SPP" finished
printf '%s\n' "$log" | tail -1
