#!/bin/sh
# slurm-cluster.sh start|stop STATE_DIR
#
# A throw-away one-node Slurm cluster on loopback, so the cohort tests can
# drive the real sbatch/squeue/scontrol/scancel instead of a mock.
#
# Why it is built this way:
# - Plain background processes, no systemd and no /etc: CI runs as root in a
#   container without an init system, and two tests (or a developer's own
#   cluster) must be able to run side by side. Everything a daemon writes,
#   including munge's key, socket and seed, lives in STATE_DIR; stop leaves
#   it there so a failed test can be inspected.
# - Our own munged with a fresh key: the system one may not run, and sharing
#   its key would let two clusters accept each other's credentials.
#   AuthInfo=socket= in slurm.conf points daemons and clients alike at it, so
#   a client needs nothing but SLURM_CONF (see STATE_DIR/env.sh).
# - Daemons run in the foreground (-D, -F) behind '&' so that $! is the real
#   daemon pid; stop signals exactly those pids and never searches by name,
#   since other clusters' daemons carry the same names. All their output goes
#   to files so that ctest, which waits for its pipes to close, is not held.
# - Ports are picked at random below the kernel's ephemeral range (outgoing
#   connections cannot take them meanwhile) and checked free with ss.
# - slurmd -N names the node after the short hostname, which is also what
#   slurmctld requires as SlurmctldHost; both are pinned to 127.0.0.1 so no
#   name resolution or network is needed. CPUs and RealMemory come from
#   slurmd -C, i.e. what slurmd itself will report, so the node is never
#   drained for having less than configured.
# - proctrack/linuxproc, task/none and no accounting: these need no cgroups
#   and no slurmdbd. select/cons_tres with CR_CPU lets one job per CPU share
#   the node, as array tasks on a real cluster would, without making every
#   job ask for memory.
# - Scheduling: measured with measure-slurm-overhead.sh, 40 tasks on the
#   2-core node. Slurm's defaults (bf_interval=30, batch_sched_delay=3) cost
#   2.9 s a task of 0 s and 1.1 s a task of 2 s; batch_sched_delay=0 alone
#   1.0 and 1.0 s; with bf_interval=1 (the backfill pass every second) too,
#   0.9-1.0 and 0.6-0.7 s. Other settings tried (sched/builtin,
#   sched_min_interval=0, MinJobAge=2) did not help. A real cluster's cost
#   is its own: the cohort plans for about a second a task.
# - MaxArraySize is Slurm's default of 1001 (indices 0-1000), the value most
#   real sites keep, unless SLURM_CLUSTER_MAX_ARRAY_SIZE asks for another
#   (a test that splits a cohort into several arrays).
# - slurmctld -c starts from empty state, so each start is a fresh cluster.
# - Exit 77 with one line when a package is missing, for ctest's SKIP.
set -u
PATH=$PATH:/usr/sbin:/sbin

usage() { echo "usage: $0 start|stop STATE_DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
case $2 in /*) D=$2 ;; *) D=$(pwd)/$2 ;; esac
CONF=$D/slurm.conf

alive() { # pid file -> true if that pid still runs one of our daemons
    [ -s "$1" ] || return 1
    p=$(cat "$1")
    # The command line names STATE_DIR: guards against a recycled pid.
    { tr '\0' ' ' <"/proc/$p/cmdline"; } 2>/dev/null | grep -qF "$D/"
}

stop() {
    if alive "$D/slurmctld.pid"; then
        # slurmd leaves running job steps behind when it exits; cancel first.
        SLURM_CONF=$CONF timeout 5 scancel --full --user="$(id -un)" 2>/dev/null
        i=0
        while [ $i -lt 20 ] && SLURM_CONF=$CONF timeout 5 squeue -h -o %i 2>/dev/null | grep -q .; do
            sleep 0.25; i=$((i + 1))
        done
    fi
    for d in slurmd slurmctld munged; do
        f=$D/$d.pid
        alive "$f" || continue
        kill -TERM "$(cat "$f")" 2>/dev/null
        i=0
        while alive "$f" && [ $i -lt 20 ]; do sleep 0.25; i=$((i + 1)); done
        alive "$f" && kill -KILL "$(cat "$f")" 2>/dev/null
    done
    return 0
}

fail() {
    echo "slurm-cluster: start failed: $*" >&2
    stop
    for l in munged slurmctld slurmd; do
        [ -s "$D/log/$l.log" ] && { echo "--- tail of $D/log/$l.log" >&2; tail -n 15 "$D/log/$l.log" >&2; }
    done
    exit 1
}

port_busy() {
    ss -Hltn "sport = :$1" 2>/dev/null | grep -q .
}

free_port() { # random free TCP port in [20000, 32000), not equal to $1
    while :; do
        p=$((20000 + $(od -An -N2 -tu2 /dev/urandom) % 12000))
        [ "$p" != "${1:-}" ] && ! port_busy "$p" && { echo "$p"; return; }
    done
}

start() {
    missing=
    for b in munged:munge slurmctld:slurmctld slurmd:slurmd sbatch:slurm-client; do
        command -v "${b%%:*}" >/dev/null 2>&1 || missing="$missing ${b#*:}"
    done
    command -v ss >/dev/null 2>&1 || missing="$missing iproute2"
    [ -z "$missing" ] || { echo "slurm-cluster: missing Debian package(s):$missing"; exit 77; }

    for d in munged slurmctld slurmd; do
        alive "$D/$d.pid" && { echo "slurm-cluster: $d already running for $D" >&2; exit 1; }
    done
    t0=$(date +%s.%N)
    mkdir -p "$D/munge" "$D/state" "$D/spool" "$D/log" || exit 1
    # munged wants the socket's directory open to all users (clients) but
    # writable by us only, and the key readable by us only.
    chmod 755 "$D/munge" || exit 1
    rm -f "$D"/*.pid "$D/env.sh"

    [ -s "$D/munge/munge.key" ] ||
        { dd if=/dev/urandom of="$D/munge/munge.key" bs=1024 count=1 2>/dev/null &&
          chmod 400 "$D/munge/munge.key"; } || fail "cannot write munge key"
    sock=$D/munge/munge.socket
    munged -F --socket="$sock" --key-file="$D/munge/munge.key" \
        --pid-file="$D/munge/munged.pid" --log-file="$D/log/munged.log" \
        --seed-file="$D/munge/munged.seed" </dev/null >>"$D/log/munged.log" 2>&1 &
    echo $! >"$D/munged.pid"

    host=$(uname -n); host=${host%%.*}
    # e.g. "CPUs=2 Boards=1 SocketsPerBoard=1 CoresPerSocket=2 ThreadsPerCore=1
    # RealMemory=24105"; the full topology keeps slurmd from warning.
    hw=$(slurmd -C | sed -n 's/^NodeName=[^ ]* \(CPUs=.*RealMemory=[0-9]*\).*/\1/p')
    cpus=$(echo "$hw" | sed -n 's/^CPUs=\([0-9]*\).*/\1/p')
    [ -n "$cpus" ] || fail "slurmd -C did not report CPUs and RealMemory"
    cport=$(free_port); dport=$(free_port "$cport")

    cat >"$CONF" <<EOF
ClusterName=vimlop
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$cport
SlurmdPort=$dport
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$sock
CredType=cred/munge
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pidfile
SlurmdPidFile=$D/slurmd.pidfile
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0,bf_interval=1
MaxArraySize=${SLURM_CLUSTER_MAX_ARRAY_SIZE:-1001}
ReturnToService=2
KillWait=5
MpiDefault=none
MailProg=/bin/true
NodeName=$host NodeAddr=127.0.0.1 NodeHostname=$host $hw State=UNKNOWN
PartitionName=main Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
    [ -n "${SLURM_CLUSTER_EXTRA_CONF:-}" ] && printf '%s\n' "$SLURM_CLUSTER_EXTRA_CONF" >>"$CONF"

    i=0
    until [ -S "$sock" ]; do
        alive "$D/munged.pid" || fail "munged exited"
        [ $i -lt 100 ] || fail "munged socket did not appear"
        sleep 0.1; i=$((i + 1))
    done

    slurmctld -D -c -f "$CONF" </dev/null >>"$D/log/slurmctld.out" 2>&1 &
    echo $! >"$D/slurmctld.pid"
    slurmd -D -N "$host" -f "$CONF" </dev/null >>"$D/log/slurmd.out" 2>&1 &
    echo $! >"$D/slurmd.pid"

    export SLURM_CONF="$CONF"
    deadline=$(($(date +%s) + ${SLURM_CLUSTER_TIMEOUT:-30}))
    until [ "$(sinfo -h -N -o %t 2>/dev/null)" = idle ]; do
        for d in munged slurmctld slurmd; do alive "$D/$d.pid" || fail "$d exited"; done
        [ "$(date +%s)" -lt "$deadline" ] || fail "node not idle after ${SLURM_CLUSTER_TIMEOUT:-30} s"
        sleep 0.2
    done
    printf "export SLURM_CONF='%s'\n" "$CONF" >"$D/env.sh"
    echo "slurm-cluster: up in $(awk "BEGIN { printf \"%.1f\", $(date +%s.%N) - $t0 }") s," \
        "node $host ($cpus CPUs), ports $cport/$dport; . $D/env.sh"
}

case $1 in
    start) start ;;
    stop) stop ;;
    *) usage ;;
esac
