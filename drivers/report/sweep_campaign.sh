#!/bin/sh
# Issue 20's fault campaigns on drivers/sweep: a sweep on 2 MPI ranks interrupted KILLS times at
# random moments (after 1..15 new result lines, at random), each time resumed with the same command, then run to the end; its result file
# against an uninterrupted serial run of the same table: rows lost, duplicated, different.
#   mpirun   SIGKILL of mpirun alone (its ranks, in their own process groups, live on a few
#            seconds: the resume waits for the result file's lock)
#   rank     SIGKILL of one rank (chosen at random), as a lost node
#   disk     the result file's write(2) fails with ENOSPC after a random number (1..4) of writes
#            (test/fault/fail_write.c preloaded into the ranks), as a disk that fills mid-run
# Usage: sweep_campaign.sh BINDIR FAIL_WRITE_LIB [KILLS] [SEED]   (KILLS default 20; the table:
#        sweep_tables.sh crank_map 24 24, 576 slider-crank rows at the defaults)
# Output: one line per campaign 'campaign KIND faults=F finished_early=E lost=L duplicated=D
# different=X rows=R' and the commands' exit codes on stderr. Needs mpirun.
set -u
bin=${1:?usage: sweep_campaign.sh BINDIR FAIL_WRITE_LIB [KILLS] [SEED]}
lib=${2:?usage: sweep_campaign.sh BINDIR FAIL_WRITE_LIB [KILLS] [SEED]}
kills=${3:-20}
seed=${4:-20}
here=$(dirname "$0")
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
launch="mpirun --oversubscribe -np 2"
[ "$(id -u)" = 0 ] && launch="$launch --allow-run-as-root"
sh "$here/sweep_tables.sh" crank_map 24 24 >"$tmp/table.txt"
"$bin/sweep" table="$tmp/table.txt" out="$tmp/reference.txt" progress=0 2>/dev/null || exit 1
rows() { grep -v '^#' "$1" | sed 's/ seconds=[^ ]*//; s/ crc=[^ ]*//' | sort; }
count() { if [ -f "$1" ]; then grep -c '^[0-9]' "$1"; else echo 0; fi; }

for kind in mpirun rank disk; do
    out=$tmp/$kind.txt
    rm -f "$out" "$out.crashes"
    faults=0
    early=0
    k=0
    while [ "$k" -lt "$kills" ]; do
        k=$((k + 1))
        if [ "$kind" = disk ]; then
            after=$(awk -v s="$seed" -v k="$k" 'BEGIN { srand(s * 1000 + k); print 1 + int(4 * rand()) }')
            LD_PRELOAD=$lib REGDAE_FAIL_WRITE_PATH=$out REGDAE_FAIL_WRITE_AFTER=$after \
                $launch -x LD_PRELOAD -x REGDAE_FAIL_WRITE_PATH -x REGDAE_FAIL_WRITE_AFTER \
                "$bin/sweep" table="$tmp/table.txt" out="$out" progress=0 >/dev/null 2>"$tmp/err"
            code=$?
            if [ "$code" = 0 ]; then early=$((early + 1)); break; fi
            faults=$((faults + 1))
            continue
        fi
        # the fault lands after a random number (1..15) of new result lines: mid-run, not while
        # the sweep still waits for the lock that the ranks of the last killed mpirun hold
        before=$(count "$out")
        lines=$(awk -v s="$seed" -v k="$k" 'BEGIN { srand(s * 1000 + k); print 1 + int(15 * rand()) }')
        $launch "$bin/sweep" table="$tmp/table.txt" out="$out" progress=0 >/dev/null 2>"$tmp/err" &
        pid=$!
        i=0
        while [ "$(count "$out")" -lt $((before + lines)) ] && kill -0 "$pid" 2>/dev/null && [ "$i" -lt 3000 ]; do
            sleep 0.02
            i=$((i + 1))
        done
        if ! kill -0 "$pid" 2>/dev/null; then
            wait "$pid"
            early=$((early + 1))
            break   # the sweep finished before the fault
        fi
        if [ "$kind" = mpirun ]; then
            kill -KILL "$pid" 2>/dev/null
        else
            ranks=$(ps -o pid= --ppid "$pid" | tr -d ' ')
            pick=$(awk -v s="$seed" -v k="$k" 'BEGIN { srand(s * 1000 + k); print 1 + int(2 * rand()) }')
            victim=$(echo "$ranks" | sed -n "${pick}p")
            [ -n "$victim" ] || victim=$(echo "$ranks" | head -n 1)
            kill -KILL "$victim" 2>/dev/null
        fi
        wait "$pid" 2>/dev/null
        faults=$((faults + 1))
    done
    $launch "$bin/sweep" table="$tmp/table.txt" out="$out" progress=0 >/dev/null 2>"$tmp/err"
    echo "final resume of $kind: exit $?" >&2
    rows "$tmp/reference.txt" >"$tmp/a"
    rows "$out" >"$tmp/b"
    lost=$(awk '{ print $1 }' "$tmp/a" | sort -u >"$tmp/ida"; awk '{ print $1 }' "$tmp/b" | sort -u >"$tmp/idb"
           comm -23 "$tmp/ida" "$tmp/idb" | wc -l | tr -d ' ')
    duplicated=$(awk '{ print $1 }' "$tmp/b" | sort | uniq -d | wc -l | tr -d ' ')
    different=$(comm -3 "$tmp/a" "$tmp/b" | awk '{ print $1 }' | sort -u | wc -l | tr -d ' ')
    echo "campaign $kind faults=$faults finished_early=$early lost=$lost duplicated=$duplicated different=$different rows=$(count "$out")"
done
