#!/bin/sh
# measure-slurm-overhead.sh STATE_DIR [TASKS]
#
# Slurm's cost per array task on a cluster started by slurm-cluster.sh, so
# that cohort runs can choose how much work to put in one task.
#
# Why it measures this way:
# - Each task stamps its own start and end (date +%s.%N), because squeue and
#   scontrol only report whole seconds and the cost we want is sub-second.
# - The makespan runs from just before sbatch to the last task's end, so it
#   includes submission, the wait for the first start and every gap between
#   one task ending and the next starting, which is the overhead a cohort
#   pays. The squeue polling only tells when to read the files; its interval
#   does not enter the figures.
# - With C tasks able to run at once (the node's CPUs, one per task), the
#   ideal makespan is sum(run)/C, so the overhead per task is
#   (makespan * C - sum(run)) / TASKS. It is also shown as a share of a
#   20 s task, a plausible short cohort case.
# - It is run twice, with tasks of 0 s and of 2 s: if the overhead were a
#   fixed cost per task the two would agree; if the scheduler works on a
#   timer they differ, since short tasks wait for the next pass.
set -u
[ $# -ge 1 ] || { echo "usage: $0 STATE_DIR [TASKS]" >&2; exit 2; }
. "$1/env.sh" || exit 1
tasks=${2:-40}
cpus=$(sinfo -h -o %C | cut -d/ -f4) # allocated/idle/other/total
conc=$((cpus < tasks ? cpus : tasks))
work=$(mktemp -d /tmp/slurm-overhead.XXXXXX) || exit 1

for len in 0 2; do
    mkdir "$work/$len"
    t0=$(date +%s.%N)
    job=$(sbatch --parsable --array=0-$((tasks - 1)) --cpus-per-task=1 \
        --output=/dev/null --job-name=overhead \
        --wrap "s=\$(date +%s.%N); sleep $len; echo \$s \$(date +%s.%N) >$work/$len/\$SLURM_ARRAY_TASK_ID") ||
        exit 1
    while squeue -h -j "$job" 2>/dev/null | grep -q .; do sleep 0.2; done
    n=$(ls "$work/$len" | wc -l)
    [ "$n" -eq "$tasks" ] || { echo "only $n of $tasks tasks left a time stamp" >&2; exit 1; }
    cat "$work/$len"/* | awk -v t0="$t0" -v n="$tasks" -v c="$conc" -v len="$len" '
        { run += $2 - $1; if ($2 > last) last = $2 }
        END {
            span = last - t0; o = (span * c - run) / n
            printf "%d tasks of %d s, %d at a time: makespan %.2f s, run %.2f s, " \
                "overhead %.3f s per task = %.1f%% of a 20 s task\n", n, len, c, span, run, o, 100 * o / 20
        }'
done
rm -rf "$work"
