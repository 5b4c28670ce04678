# Values at matched accuracy: two curves, each a file of rows "rtol error value" in
# decreasing rtol; for k = from ... to prints "k value_1 value_2", each curve's value at
# error 10^-k by log-log interpolation between the first pair of neighbouring rows whose
# errors bracket it (-1 where the curve never reaches it).
# Usage: awk -v from=K1 -v to=K2 -f tools/matched.awk curve_1.txt curve_2.txt
FNR == 1 { f++ }
f == 1 { n1++; e1[n1] = $2; s1[n1] = $3 }
f == 2 { n2++; e2[n2] = $2; s2[n2] = $3 }
function at(n, e, s, target,   i, lo, hi) {
    for (i = 1; i < n; i++) {
        lo = e[i]; hi = e[i + 1]
        if ((lo - target) * (hi - target) <= 0 && lo != hi)
            return exp(log(s[i]) + (log(target) - log(lo)) * (log(s[i + 1]) - log(s[i])) / (log(hi) - log(lo)))
    }
    return -1
}
END { for (k = from; k <= to; k++) print k, at(n1, e1, s1, 10 ^ (-k)), at(n2, e2, s2, 10 ^ (-k)) }
