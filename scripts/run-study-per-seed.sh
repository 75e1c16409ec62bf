#!/bin/sh
# Run a `lumis study` config whose runs have one thread as one process per
# seed side by side (2 cores: 2 seeds at once), then once more over the whole
# config to gather the report (finished runs are skipped). Installs pbrt-v4's
# runtime libraries first through its own script when it is there.
#
#   sh scripts/run-study-per-seed.sh LUMIS CONFIG OUT
#   e.g. sh scripts/run-study-per-seed.sh target/release/lumis studies/caustics.toml docs/study
set -eu
lumis=$(realpath "$1"); config=$(realpath "$2"); out=$(realpath -m "$3")
dir=$(dirname "$config"); stem=$(basename "$config" .toml)
deps="$dir/../../shared/peers/pbrt-v4/install-deps.sh"
[ -x "$deps" ] && bash "$deps" >/dev/null || echo "pbrt-v4 not ready: its runs are skipped"
seeds=$(sed -n 's/^seeds *= *\[\(.*\)\]/\1/p' "$config" | tr -d ' ' | tr ',' ' ')
pids=""
for s in $seeds; do
  copy="$dir/.$stem-seed$s.toml"
  sed "s/^seeds *=.*/seeds = [$s]/" "$config" > "$copy"
  "$lumis" study --quiet "$copy" --out "$out" > "$out.seed$s.log" 2>&1 &
  pids="$pids $!"
done
status=0
for p in $pids; do wait "$p" || status=1; done
for s in $seeds; do rm -f "$dir/.$stem-seed$s.toml"; done
[ "$status" = 0 ] || { echo "a per-seed run failed: see $out.seed*.log"; exit 1; }
"$lumis" study --quiet "$config" --out "$out"
