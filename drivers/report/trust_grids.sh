#!/bin/sh
# The trust grids (drivers/trust.f90): every family in two parts run side by side (two cores),
# the rows merged by cell number into BUILD/report/trust/<family>.txt, the summary line of each
# family (the two parts' counts added) with its wall time, the silent, false-alarm and undecided
# cells in BUILD/report/trust/baseline.txt, and gnuplot heat maps in BUILD/report/trust/*.png.
# Builds nothing.
#
# Usage: trust_grids.sh [--report-only] BUILD_DIR [FAMILY ...]   (default: crank chain chain_long fourbar linear)
#   --report-only: run nothing; baseline.txt and the figures again from the rows and summaries.txt there.
set -eu
run=yes
if [ "${1:-}" = --report-only ]; then
    run=no
    shift
fi
build=${1:?usage: trust_grids.sh [--report-only] BUILD_DIR [FAMILY ...]}
shift
families=${*:-crank chain chain_long fourbar linear}
bin=$build/bin/trust
out=$build/report/trust
summaries=$out/summaries.txt
if [ $run = yes ]; then
    [ -x "$bin" ] || { echo "trust_grids.sh: $bin not found (build it first)" >&2; exit 2; }
    mkdir -p "$out"
    echo "# run at commit $(git -C "$(dirname "$0")" rev-parse --short HEAD 2>/dev/null || echo '?'), $(date -u +%Y-%m-%dT%H:%MZ)" \
        > "$summaries"
fi

# merge PART1 PART2 > FAMILY.txt: part 1's header, both parts' '# reference' lines (tagged
# with their part), then the rows in cell order, each with the '#   ' lines that follow it.
# (Sort keys: the header lines -2000000 + line number, the reference lines -1000000 + their
# number, a row its cell: unique, so the order is kept without a stable sort.)
merge() {
    awk -v sep="$(printf '\001')" '
        function flush() { if (key != "") print key "\t" rec; key = "" }
        FNR == 1 { part++ }
        /^ *[0-9]+ / { flush(); key = $1; rec = $0; next }
        /^#   / && key != "" { rec = rec sep $0; next }
        /^# reference/ { flush(); print (-1000000 + (++nref)) "\t# [part " part "] " substr($0, 3); next }
        /^summary/ { flush(); next }
        /^#/ { flush(); if (part == 1) print (-2000000 + FNR) "\t" $0; next }
        END { flush() }
    ' "$1" "$2" | sort -t "$(printf '\t')" -k1,1n | cut -f2- | tr '\001' '\n'
}

# add_summaries PART1 PART2: one summary line with the two parts' counts added.
add_summaries() {
    grep -h '^summary ' "$1" "$2" | awk '
        { for (i = 2; i <= NF; i++) { split($i, kv, "="); if (kv[1] == "family") fam = kv[2];
          else { if (!(kv[1] in sum)) order[++n] = kv[1]; sum[kv[1]] += kv[2] } } }
        END { line = "summary family=" fam; for (i = 1; i <= n; i++) line = line " " order[i] "=" sum[order[i]]; print line }'
}

for fam in $families; do
    [ $run = yes ] || break
    start=$(date +%s)
    "$bin" family="$fam" part=1/2 > "$out/$fam.part1" 2>&1 &
    pid1=$!
    "$bin" family="$fam" part=2/2 > "$out/$fam.part2" 2>&1 &
    pid2=$!
    rc1=0
    rc2=0
    wait "$pid1" || rc1=$?
    wait "$pid2" || rc2=$?
    stop=$(date +%s)
    merge "$out/$fam.part1" "$out/$fam.part2" > "$out/$fam.txt"
    # the machine's load average at the end (1 min): the wall time is only comparable on an idle machine
    load=$(cut -d ' ' -f 1 /proc/loadavg 2>/dev/null || echo '?')
    line="$(add_summaries "$out/$fam.part1" "$out/$fam.part2") wall_seconds=$((stop - start)) load=$load"
    [ "$rc1" -eq 0 ] && [ "$rc2" -eq 0 ] || line="$line exit_status=$rc1,$rc2"
    echo "$line" | tee -a "$summaries"
    rm -f "$out/$fam.part1" "$out/$fam.part2"
done

# baseline.txt: the summaries (with the wall time of each family), the reference-method
# anomalies, the chain references' convergence checks, and the cells to look at (silent,
# false_alarm, undecided, warned, no_reference), one compact line each: the row's columns
# but the seconds, then the family's columns, and for a false alarm the checks-off run.
{
    echo "# trust grids (drivers/report/trust_grids.sh): the summaries, the references, the cells to look at"
    echo "# wall_seconds: both parts side by side on two cores; load: the 1-minute load average at the end"
    cat "$summaries"
    echo
    echo "# reference method (Dormand-Prince) per family: cells by its outcome"
    for fam in crank fourbar; do
        [ -f "$out/$fam.txt" ] || continue
        awk -v fam="$fam" '$1 ~ /^[0-9]+$/ { n[$NF]++ }
            END { line = "#   " fam ":"; for (k in n) line = line " " k "=" n[k]; print line }' "$out/$fam.txt"
    done
    [ -f "$out/chain.txt" ] && awk '$1 ~ /^[0-9]+$/ && $3 == "plain" { n[$NF == 0 ? "ok" : "status_" $NF]++ }
        END { line = "#   chain (plain; the peer at R):"; for (k in n) line = line " " k "=" n[k]; print line }' "$out/chain.txt"
    for fam in chain chain_long; do
        [ -f "$out/$fam.txt" ] || continue
        echo
        echo "# $fam references (part 1's; the two parts compute the same ones):"
        grep '^# \[part 1\] reference' "$out/$fam.txt" | sed 's/^# \[part 1\] reference /#   /'
    done
    for cls in silent false_alarm undecided warned no_reference; do
        echo
        echo "# $cls cells: family cell case p1 p2 R status err err_ref bound t_end steps [family columns]"
        for fam in $families; do
            [ -f "$out/$fam.txt" ] || continue
            awk -v cls="$cls" '
                function flush() { if (line != "") print line; line = "" }
                $1 ~ /^[0-9]+$/ { flush(); if ($8 != cls) next
                    line = sprintf("%-10s %5d %-18s %13s %13s %8s %6s %11s %11s %11s %12s %8s", $2, $1, $3, $4, $5, $6, $7,
                                   $9, $10, $11, $12, $13)
                    for (i = 15; i <= NF; i++) line = line " " $i
                    next }
                /^#   checks off: / && line != "" { line = line "  | checks off: " substr($0, 17); next }
                END { flush() }' "$out/$fam.txt"
        done
    done
} > "$out/baseline.txt"
echo "wrote $out/baseline.txt"

command -v gnuplot > /dev/null 2>&1 || { echo "trust_grids.sh: no gnuplot, no figures" >&2; exit 0; }

# The classes as numbers for the colour maps.
class_code='BEGIN { ncls = split("ok warned silent false_alarm failed refused undecided no_reference", names, " ")
                  for (i = 1; i <= ncls; i++) code[names[i]] = i }'
palette="set palette maxcolors 8; set palette defined (1 '#1a9850', 2 '#fee08b', 3 '#d73027', 4 '#4575b4', \
5 '#636363', 6 '#c2a5cf', 7 '#fdae61', 8 '#ffffff'); set cbrange [0.5:8.5]; \
set cbtics ('ok' 1, 'warned' 2, 'silent' 3, 'false alarm' 4, 'failed' 5, 'refused' 6, 'undecided' 7, 'no ref' 8)"

if [ -f "$out/crank.txt" ]; then
    # crank.dat: th1 index, w1 index, R index, log10(err/bound), class code (cell = ((i-1) 6 + r-1) 13 + j),
    # one block per R (gnuplot's index r - 1)
    awk "$class_code"'
        $1 ~ /^[0-9]+$/ { c = $1 - 1; j = c % 13 + 1; r = int(c / 13) % 6 + 1; i = int(c / 78) + 1
            e = $9 > 0 ? log($9 / $11) / log(10) : -3; if (e < -3) e = -3
            line[r, i, j] = i " " j " " r " " e " " code[$8] }
        END { for (r = 1; r <= 6; r++) { for (i = 1; i <= 25; i++) for (j = 1; j <= 13; j++)
                  if ((r, i, j) in line) print line[r, i, j]
              print ""; print "" } }' "$out/crank.txt" > "$out/crank.dat"
    for kind in err class; do
        if [ "$kind" = err ]; then
            col=4
            maps="set palette defined (-3 '#1a9850', 0 '#ffffbf', 0.001 '#fdae61', 3 '#d73027', 6 '#67001f'); \
set cbrange [-3:6]; set cblabel 'log10(err/bound)'"
            title='slider crank: log10(err / bound) (> 0: beyond the bound)'
        else
            col=5
            maps=$palette
            title='slider crank: class per cell'
        fi
        gnuplot <<EOF
set terminal pngcairo size 1500,900 font ',9'
set output '$out/crank_$kind.png'
$maps
set multiplot layout 2,3 title '$title'
set xrange [0.5:25.5]; set yrange [0.5:13.5]
set xlabel 'th1 index (ascending, 1 = 1e-8, 25 = pi - 1e-8)'
set ytics ('0' 1, '1e-6' 2, '1e-5' 3, '1e-4' 4, '1e-3' 5, '1e-2' 6, '0.1' 7, '0.5' 8, '1' 9, '2' 10, '5' 11, '10' 12, '20' 13)
set ylabel 'w1 (rad/s)'
do for [r = 1:6] {
    set title sprintf('R = 1e-%d', r + 2)
    plot '$out/crank.dat' index (r - 1) using 1:2:$col with image notitle
}
unset multiplot
EOF
    done
    echo "wrote $out/crank_err.png $out/crank_class.png"
fi

# family_map DAT PNG MAPS TITLE: a family's heat map over (case, R) from DAT's 'case R value'
# rows (ncols, ymax and xtics of the family in force), the colours set by MAPS
family_map() {
    gnuplot <<EOF
set terminal pngcairo size 1400,600 font ',9'
set output '$2'
$3
set title '$4'
set xrange [0.5:$((ncols)).5]; set yrange [2.5:$ymax.5]
set xtics ($xtics) rotate by 60 right
set ylabel '-log10(R)'
plot '$1' using 1:2:3 with image notitle
EOF
}

# The other families: the class per cell over (case, R), and log10(err/bound).
for fam in chain chain_long fourbar linear; do
    [ -f "$out/$fam.txt" ] || continue
    # FAMILY.dat: case ordinal (in order of first appearance), -log10(R), class code, sorted
    awk "$class_code"'
        $1 ~ /^[0-9]+$/ { key = $3 " " $4; if (!(key in col)) { col[key] = ++n
                              print n, $3 (($2 ~ /chain/) ? "/" ($4 + 0) : "") > labels }
            printf "%d %d %d\n", col[key], -log($6) / log(10) + 0.5, code[$8] }' labels="$out/$fam.labels" \
        "$out/$fam.txt" | sort -n -k1,1 -k2,2 > "$out/$fam.dat"
    ncols=$(wc -l < "$out/$fam.labels")
    ymax=$(awk 'NR == 1 || $2 > m { m = $2 } END { print m + 0 }' "$out/$fam.dat")
    xtics=$(awk '{ printf "%s\"%s\" %d", (NR > 1 ? ", " : ""), $2, $1 }' "$out/$fam.labels")
    family_map "$out/$fam.dat" "$out/${fam}_class.png" "$palette" "$fam: class per cell"
    # FAMILY_err.dat: the same cells' log10(err/bound) in [-3, 6] (NaN, no colour, where a cell has no
    # error or no bound: refused, no reference)
    awk '$1 ~ /^[0-9]+$/ { key = $3 " " $4; if (!(key in col)) col[key] = ++n
            if ($9 < 0 || $11 <= 0) e = "NaN"
            else { e = ($9 > 0) ? log($9 / $11) / log(10) : -3; if (e < -3) e = -3; if (e > 6) e = 6 }
            printf "%d %d %s\n", col[key], -log($6) / log(10) + 0.5, e }' "$out/$fam.txt" |
        sort -n -k1,1 -k2,2 > "$out/${fam}_err.dat"
    family_map "$out/${fam}_err.dat" "$out/${fam}_err.png" "set palette defined (-3 '#1a9850', 0 '#ffffbf', \
0.001 '#fdae61', 3 '#d73027', 6 '#67001f'); set cbrange [-3:6]; set cblabel 'log10(err/bound)'" \
        "$fam: log10(err / bound) per cell (> 0: beyond the bound)"
    echo "wrote $out/${fam}_class.png $out/${fam}_err.png"
done
