#!/usr/bin/env bash
# A render split into TASKS partial renders and merged: bit-identical to
# rendering it whole. Runs the parts one after another here, or submits
# them to Slurm as a job array with a merge job that waits for them.
#
#   bash scripts/render-parts.sh TASKS OUTDIR -- RENDER-ARGS...          # here, in a loop
#   bash scripts/render-parts.sh --slurm TASKS OUTDIR -- RENDER-ARGS...  # sbatch: array + merge
#
# RENDER-ARGS are `lumis render`'s (scene, --spp N, --seed, ...); --spp is
# required (a part is a range of passes, one sample per pixel each). Part
# i of TASKS renders passes [i*N/TASKS, (i+1)*N/TASKS) to OUTDIR/part-i.lpart;
# the merge writes OUTDIR/image.exr. OUTDIR and the scene must be on a
# filesystem every node sees, and every node must run the same lumis
# version (merge refuses parts of another). An array task that fails or
# is preempted can be rerun alone (sbatch --array=i ...), or continued
# with `lumis render --resume OUTDIR/part-i.lpart`.
#
# Extra sbatch options go in SBATCH_ARGS (e.g. "--partition=cpu --cpus-per-task=32").
# LUMIS: the binary (default: `lumis` on PATH, else target/release/lumis).
set -euo pipefail

slurm=0
if [ "${1:-}" = "--slurm" ]; then
    slurm=1
    shift
fi
# Internal: one array task (Slurm sets SLURM_ARRAY_TASK_ID).
task=""
if [ "${1:-}" = "--task" ]; then
    task=${SLURM_ARRAY_TASK_ID:?--task runs inside a Slurm array}
    shift
fi
if [ $# -lt 3 ] || [ "$3" != "--" ]; then
    sed -n '2,20p' "$0" >&2
    exit 2
fi
tasks=$1
out=$2
shift 3
args=("$@")

lumis=${LUMIS:-}
if [ -z "$lumis" ]; then
    if command -v lumis >/dev/null; then
        lumis=$(command -v lumis)
    else
        lumis="$(cd "$(dirname "$0")/.." && pwd)/target/release/lumis"
    fi
fi

spp=""
for ((k = 0; k < ${#args[@]}; k++)); do
    case ${args[k]} in
        --spp) spp=${args[k + 1]:-} ;;
        --spp=*) spp=${args[k]#--spp=} ;;
    esac
done
if ! [[ "$spp" =~ ^[0-9]+$ ]] || [ "$spp" -lt 1 ]; then
    echo "render-parts: give the render's sample count as --spp N (found '${spp}')" >&2
    exit 2
fi
if ! [[ "$tasks" =~ ^[0-9]+$ ]] || [ "$tasks" -lt 1 ] || [ "$tasks" -gt "$spp" ]; then
    echo "render-parts: TASKS must be a whole number from 1 to the sample count ($spp), found '$tasks'" >&2
    exit 2
fi

# Part i: passes [i*spp/tasks, (i+1)*spp/tasks), never empty since tasks <= spp.
part() {
    local i=$1
    local a=$((i * spp / tasks)) b=$(((i + 1) * spp / tasks))
    "$lumis" render "${args[@]}" -q --passes "$a..$b" --partial "$out/part-$i.lpart"
}

if [ -n "$task" ]; then
    part "$task"
    exit
fi
mkdir -p "$out"
if [ "$slurm" = 1 ]; then
    # Slurm runs a copy of this script: the binary goes by absolute path.
    export LUMIS=$lumis
    # shellcheck disable=SC2086 # SBATCH_ARGS is a list of options
    jid=$(sbatch --parsable ${SBATCH_ARGS:-} --array="0-$((tasks - 1))" \
        --output="$out/part-%a.log" "$0" --task "$tasks" "$out" -- "${args[@]}")
    jid=${jid%%;*}
    # shellcheck disable=SC2086
    sbatch --parsable ${SBATCH_ARGS:-} --dependency="afterok:$jid" --output="$out/merge.log" \
        --wrap="\"$lumis\" merge \"$out\"/part-*.lpart -o \"$out/image.exr\""
    echo "render-parts: array job $jid ($tasks parts), then the merge, into $out" >&2
    exit
fi
for ((i = 0; i < tasks; i++)); do
    part "$i"
done
"$lumis" merge "$out"/part-*.lpart -o "$out/image.exr"
