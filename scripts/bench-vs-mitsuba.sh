#!/usr/bin/env bash
# Side-by-side speed of lumis `path`, Mitsuba 3 (`path`, llvm_ad_rgb) and
# pbrt-v4 (`path`) on the same scenes, at the same samples per pixel and
# maximum depth, on 2 threads each. A benchmark, not a test: nothing in
# `cargo test` runs it. See docs/measured.md ("lumis against Mitsuba 3 and
# pbrt-v4") for what it does and how to read its table.
#
#   scripts/bench-vs-mitsuba.sh [--quick] [--spp N] [--res WxH] [--ref-spp N]
#                               [--scenes "glass default"] [--threads N]
#
# Full size: 512x512, 64 spp, references of 4096 spp. --quick: 128x128,
# 16 spp, references of 256 spp. Everything it installs or makes goes under
# target/ (ignored by git): the Python environment with Mitsuba in
# target/bench-venv (and Debian's libllvm19 with apt), the scenes, images
# and cached references in target/bench. Environment:
#   LUMIS=path     lumis binary (default: built with cargo build --release)
#   PBRT_DIR=dir   folder of the pbrt-v4 binary and its install-deps.sh
#                  (default ../shared/peers/pbrt-v4); missing: pbrt is skipped
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
QUICK=0 RES="" SPP="" REF_SPP="" SCENES="glass default" THREADS=2
while [ $# -gt 0 ]; do
  case $1 in
  --quick) QUICK=1 ;;
  --spp) SPP=$2; shift ;;
  --res) RES=$2; shift ;;
  --ref-spp) REF_SPP=$2; shift ;;
  --scenes) SCENES=$2; shift ;;
  --threads) THREADS=$2; shift ;;
  -h | --help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "bench-vs-mitsuba.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
if [ $QUICK = 1 ]; then
  RES=${RES:-128x128} SPP=${SPP:-16} REF_SPP=${REF_SPP:-256}
else
  RES=${RES:-512x512} SPP=${SPP:-64} REF_SPP=${REF_SPP:-4096}
fi
[[ $RES =~ ^[0-9]+x[0-9]+$ ]] || { echo "bench-vs-mitsuba.sh: --res wants WxH, got '$RES'" >&2; exit 2; }

BENCH=$ROOT/target/bench
VENV=$ROOT/target/bench-venv
PY=$VENV/bin/python
PBRT_DIR=${PBRT_DIR:-$ROOT/../shared/peers/pbrt-v4}
PBRT=$PBRT_DIR/pbrt
export DRJIT_LIBLLVM_PATH=${DRJIT_LIBLLVM_PATH:-/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1}

bash scripts/bench/setup.sh "$VENV" "$PBRT_DIR"
if [ -z "${LUMIS:-}" ]; then
  cargo build --release -q -p lumis
  LUMIS=${CARGO_TARGET_DIR:-$ROOT/target}/release/lumis
fi
if [ ! -x "$PBRT" ]; then
  echo "pbrt-v4 not found at $PBRT (set PBRT_DIR): skipping it"
  PBRT=""
elif rc=$(sh -c '"$1" --help >/dev/null 2>&1; echo $?' _ "$PBRT" 2>/dev/null); [ "$rc" -gt 128 ]; then
  # The shared build uses AVX-512; without it on this CPU: SIGILL (132).
  echo "pbrt-v4 at $PBRT cannot run here (killed by signal $((rc - 128))$([ $rc = 132 ] && echo ', SIGILL: instructions this CPU lacks, e.g. AVX-512')): skipping it"
  PBRT=""
fi

now() { date +%s.%N; }
secs() { "$PY" -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.3f}')" "$1" "$2"; }
# timed NAME CMD...: runs CMD, its output into $OUT/NAME.log, its times into $OUT/NAME.times
timed() {
  local n=$1
  shift
  "$PY" scripts/bench/timed.py "$OUT/$n.times" "$@" >"$OUT/$n.log" 2>&1 ||
    { echo "bench-vs-mitsuba.sh: $n failed; the end of $OUT/$n.log:" >&2; tail -20 "$OUT/$n.log" >&2; exit 1; }
}
# record NAME JSON: JSON (label, render seconds, notes) with the image
# $OUT/NAME.exr, the times of $OUT/NAME.times and $SPP, one line into $RESULTS
record() {
  "$PY" -c 'import json, sys
name, r, spp = sys.argv[1], json.loads(sys.argv[2]), int(sys.argv[3])
r.update(json.load(open(name + ".times")), image=name + ".exr", spp=spp)
print(json.dumps(r))' "$OUT/$1" "$2" "$SPP" >>"$RESULTS"
}

# Scene NAME -> $BENCH/scenes/NAME.{pbrt,xml} at $RES; sets MAXDEPTH.
make_scene() {
  local dir=$BENCH/scenes
  mkdir -p "$dir"
  case $1 in
  glass)
    MAXDEPTH=65
    "$PY" scripts/bench/glass_box.py "$dir/glass-box"
    "$PY" scripts/bench/convert.py "$dir/glass-box/glass-box.pbrt" "$dir" glass --res "$RES" --maxdepth $MAXDEPTH ;;
  default)
    MAXDEPTH=12
    "$PY" scripts/bench/convert.py scenes/default.pbrt "$dir" default --res "$RES" --maxdepth $MAXDEPTH ;;
  *) echo "bench-vs-mitsuba.sh: unknown scene '$1' (glass, default)" >&2; exit 2 ;;
  esac
}

# The reference: a long lumis `path` render, another seed, cached by the
# content of the scene files and the sample count.
reference() {
  local name=$1 key files
  shopt -s nullglob
  files=("$BENCH/scenes/$name".pbrt "$BENCH/scenes/$name"-mesh-*.ply "$BENCH/scenes/$name"-box/*.ply)
  shopt -u nullglob
  key=$(cat "${files[@]}" | sha256sum | cut -c1-12)
  REF=$BENCH/ref/$name-$RES-$REF_SPP-$key.exr
  if [ ! -f "$REF" ]; then
    mkdir -p "$BENCH/ref"
    echo "making the reference $REF ($REF_SPP spp; cached for later runs)"
    local t0 t1
    t0=$(now)
    "$LUMIS" render "$BENCH/scenes/$name.pbrt" --integrator path --spp "$REF_SPP" \
      --filter-splat false --threads "$THREADS" --seed 99 -q -o "$REF.tmp.exr"
    t1=$(now)
    mv "$REF.tmp.exr" "$REF"
    echo "  took $(secs "$t0" "$t1") s"
  fi
}

# run_lumis NAME LABEL [FLAGS]: lumis `path` as row NAME.
run_lumis() {
  local n=$1 label=$2
  shift 2
  timed "$n" "$LUMIS" render "$SCENE.pbrt" --integrator path --spp "$SPP" --threads "$THREADS" \
    --seed 1 -q --stats "$@" -o "$OUT/$n.exr"
  # the rendering phase of --stats: after parsing and the BVH build, before writing
  local t
  t=$(sed -n 's/.* rendering \([0-9.]*\) s.*/\1/p' "$OUT/$n.log")
  record "$n" "{\"label\": \"$label\", \"render\": ${t:-null}}"
}

run_mitsuba() {
  timed mitsuba "$PY" scripts/bench/run_mitsuba.py "$SCENE.xml" "$OUT/mitsuba.exr" --spp "$SPP" \
    --threads "$THREADS" --seed 1
  record mitsuba "$(tail -1 "$OUT/mitsuba.log")"
}

run_pbrt() {
  timed pbrt "$PBRT" --nthreads "$THREADS" --spp "$SPP" --outfile "$OUT/pbrt.exr" "$SCENE.pbrt"
  # the progress bar's last "(12.3s)" is the rendering time
  local t
  t=$(tr '\r' '\n' <"$OUT/pbrt.log" | sed -n 's/^Rendering: .*(\([0-9.]*\)s) *$/\1/p' | tail -1)
  record pbrt "{\"label\": \"pbrt-v4 path\", \"render\": ${t:-null}, \"notes\": \"render time from its progress bar (0.1 s steps)\"}"
}

echo "lumis against Mitsuba 3 and pbrt-v4: $RES, $SPP spp, $THREADS threads, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
status=0
for name in $SCENES; do
  make_scene "$name"
  SCENE=$BENCH/scenes/$name
  reference "$name"
  OUT=$BENCH/out/$name
  RESULTS=$OUT/results.jsonl
  mkdir -p "$OUT"
  : >"$RESULTS"
  # lumis' default film weights each sample into every pixel the filter
  # reaches, as Mitsuba's does; the second row samples the filter instead
  # (pbrt-v4's film, one pixel per sample). The reference samples it.
  run_lumis lumis "lumis path"
  run_lumis lumis-fis "lumis path, filter sampled" --filter-splat false
  run_mitsuba
  if [ -n "$PBRT" ]; then run_pbrt; fi
  echo
  echo "== $name: $RES, $SPP spp, maxdepth $MAXDEPTH (pbrt's meaning; Mitsuba max_depth $((MAXDEPTH + 1))), reference lumis path $REF_SPP spp"
  "$PY" scripts/bench/report.py "$RESULTS" "$REF" "$REF_SPP" || status=1
done
exit $status
