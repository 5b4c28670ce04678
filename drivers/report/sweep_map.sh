#!/bin/sh
# Draw a slider-crank sweep (drivers/report/sweep_tables.sh crank_map, run by drivers/sweep) as a
# map: one square per start (th1, w1), coloured by the row's status (ok, failed, off_branch,
# bad_input). Needs gnuplot.
# Usage: sweep_map.sh TABLE RESULTS PNG
set -eu
table=${1:?usage: sweep_map.sh TABLE RESULTS PNG}
results=${2:?usage: sweep_map.sh TABLE RESULTS PNG}
png=${3:?usage: sweep_map.sh TABLE RESULTS PNG}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# the table's rows numbered as sweep numbers them (id), with their th1 and w1
awk '!/^[ \t]*(#|$)/ { id++; th = ""; w = ""
        for (i = 2; i <= NF; i++) { split($i, kv, "="); if (kv[1] == "th1") th = kv[2]; if (kv[1] == "w1") w = kv[2] }
        print id, th, w }' "$table" >"$tmp/starts"
awk 'NR == FNR { th[$1] = $2; w[$1] = $3; next } /^[0-9]/ { print th[$1], w[$1] >("'"$tmp"'/" $3 ".dat") }' \
    "$tmp/starts" "$results"
counts=$(awk '/^[0-9]/ { n[$3]++ } END { for (s in n) printf "%s %d, ", s, n[s] }' "$results")
clauses=""
for s in ok:#2ca02c failed:#d62728 off_branch:#ff7f0e bad_input:#7f7f7f; do
    name=${s%%:*}
    [ -s "$tmp/$name.dat" ] && clauses="$clauses'$tmp/$name.dat' using 1:2 with points pt 5 ps 0.45 lc rgb '${s#*:}' title '$name', "
done
gnuplot <<GP
set terminal png noenhanced size 900,640
set output '$png'
set title "Slider crank, index 3, defaults, t in [0, 10], from (th1, w1): ${counts%, }"
set xlabel 'th1 (rad)'; set ylabel 'w1 (rad/s)'; set xrange [0:pi]; set key outside right
plot ${clauses%, }
GP
