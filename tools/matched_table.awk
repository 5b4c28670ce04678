# Markdown table of values at matched accuracy, for tools/benchmark.sh and
# drivers/report/chain_bench.sh: input rows "k value_1 value_2" (tools/matched.awk's output;
# -1: not reached), a header with the two labels, and the ratio value_1 / value_2.
# Usage: awk -v left=LABEL -v right=LABEL [-v fmt=%.1f] -f tools/matched_table.awk ROWS
BEGIN {
    if (fmt == "") fmt = "%.2f"
    print "| accuracy | " left " | " right " | ratio |"
    print "|---|---|---|---|"
}
{
    if ($2 > 0 && $3 > 0) printf "| 1e-%d | %.2e | %.2e | " fmt " |\n", $1, $2, $3, $2 / $3
    else printf "| 1e-%d | %s | %s | - |\n", $1, ($2 > 0 ? sprintf("%.2e", $2) : "not reached"), \
        ($3 > 0 ? sprintf("%.2e", $3) : "not reached")
}
