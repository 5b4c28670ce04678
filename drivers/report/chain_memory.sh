#!/bin/sh
# Issue 20's memory benchmark, for tools/benchmark.sh: the chain (drivers/chain.f90, the defaults:
# the augmented formulation on KLU) from 1024 to 100000 links on t in [0, 0.01], its peak resident
# memory (the driver's peak_rss_kb: getrusage, the whole process) and time against N.
# Usage: chain_memory.sh run BINDIR RAWFILE [NS]   runs the chain driver once per N (one process at
#                                                  a time); NS defaults to 1024 ... 100000
#        chain_memory.sh report RAWFILE OUTDIR     draws OUTDIR/perf_chain_memory.png and writes the
#                                                  Markdown section on stdout
# Raw file: one summary line per run, prefixed by 'run n=N rc=EXIT'.
set -eu
mode=${1:?usage: chain_memory.sh run BINDIR RAWFILE [NS] | report RAWFILE OUTDIR}
common="tf=0.01 nout=1"

case $mode in
run)
    bindir=${2:?BINDIR}
    out=${3:?RAWFILE}
    ns=${4:-"1024 2048 4096 8192 16384 32768 65536 100000"}
    : >"$out.new"
    for n in $ns; do
        # shellcheck disable=SC2086
        rc=0; line=$("$bindir/chain" n_links="$n" $common 2>/dev/null | tail -n 1) || rc=$?
        echo "run n=$n rc=$rc $line" >>"$out.new"
    done
    mv "$out.new" "$out"
    ;;
report)
    raw=${2:?RAWFILE}
    outdir=${3:?OUTDIR}
    dat=$outdir/chain_memory.dat
    # n, peak RSS in MB, seconds, steps, seconds per step, companion steps, status
    awk '{ delete f; for (i = 1; i <= NF; i++) if (split($i, kv, "=") == 2 && !(kv[1] in f)) f[kv[1]] = kv[2]
           print f["n"], f["peak_rss_kb"] / 1024, f["seconds"], f["steps"], f["seconds_per_step"], f["companion_steps"], f["status"] }' \
        "$raw" >"$dat"
    # least-squares exponent of RSS against N (log-log), from 1024 links on, and on the runs with and
    # without a pass check's companion solver (a second solver of the same size, alive during the pass)
    fit() { awk -v sel="$1" '$1 >= 1024 && (sel == "all" || (sel == "with") == ($6 > 0)) {
                x = log($1); y = log($2); n++; sx += x; sy += y; sxx += x * x; sxy += x * y }
            END { if (n < 2) { print "-"; exit } printf "%.2f", (n * sxy - sx * sy) / (n * sxx - sx * sx) }' "$dat"; }
    all=$(fit all); without=$(fit without); with=$(fit with)
    gnuplot <<EOF
set terminal pngcairo size 800,500
set output '$outdir/perf_chain_memory.png'
set logscale xy
set xlabel 'links N'
set ylabel 'peak resident memory (MB)'
set y2label 'seconds per step'
set logscale y2
set ytics nomirror
set y2tics
set key top left
set grid
set title 'Chain on t in [0, 0.01], defaults: memory and time per step against N'
plot '$dat' using 1:2 with linespoints title 'peak RSS (MB)', \
     '$dat' using 1:(8.5 * \$1 / 1024) with lines dashtype 2 title '8.5 kB x N', \
     '$dat' using 1:5 axes x1y2 with linespoints title 'seconds per step (right axis)'
EOF
    echo "## Chain: memory against the number of bodies"
    echo
    echo "Issue 20. \`sh drivers/report/chain_memory.sh run build/bin RAW\` runs \`chain n_links=N $common\` with"
    echo "every option at its default (the augmented formulation on KLU) once per N; peak_rss_kb is the process's"
    echo "peak resident memory (getrusage: the problem's set-up, the solver and the output); seconds is the solve"
    echo "alone (init and advances). companion steps > 0: the pass check ran a companion solver (a second solver"
    echo "of the same size) because the straight chain's sigma_min(GB) falls like N^-4 and crosses the singular"
    echo "threshold from about 32768 links on."
    echo
    echo "| N | peak RSS (MB) | kB per link | seconds | steps | seconds per step | companion steps | status |"
    echo "|---|---|---|---|---|---|---|---|"
    awk '{ printf "| %d | %.1f | %.2f | %.3g | %d | %.3g | %d | %s |\n", $1, $2, 1024 * $2 / $1, $3, $4, $5, $6, $7 }' "$dat"
    echo
    echo "Fitted exponent of the peak RSS against N (least squares on log-log, N >= 1024): $all over all runs,"
    echo "$without over the runs without a companion, $with over the runs with one (the target: <= 1.1)."
    echo
    echo "![chain memory](figures/perf_chain_memory.png)"
    echo
    ;;
*)
    echo "usage: chain_memory.sh run BINDIR RAWFILE [NS] | report RAWFILE OUTDIR" >&2
    exit 2
    ;;
esac
