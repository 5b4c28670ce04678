# Errors and median seconds of chain-driver runs against a reference run, for
# drivers/report/chain_bench.sh and defaults_bench.sh. Input: a raw file of runs, each a
# line 'run engine=E tol=T rep=R ...' followed by the chain driver's output. Output: rows
# 'engine tol err seconds steps status', one per (engine, tol) in the order of the file: err
# the largest distance of (x_end, y_end) from the run 'engine=reference tol=1e-11' over the
# outputs (-1 for a run that stopped early), seconds the median of the repetitions' summary
# seconds, steps and status those of repetition 1.
/^run / { for (i = 2; i <= NF; i++) { split($i, kv, "="); h[kv[1]] = kv[2] } key = h["engine"] " " h["tol"]; row = 0; next }
/^#/ { next }
/^summary / { split("", f); for (i = 2; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
              if (h["rep"] == 1) { st[key] = f["status"]; steps[key] = f["steps"]; order[++nk] = key }
              c[key]++; sec[key, c[key]] = f["seconds"]; next }
h["rep"] == 1 && NF >= 3 { row++; x[key, row] = $2; y[key, row] = $3; rows[key] = row }
END {
    ref = "reference 1e-11"
    for (j = 1; j <= nk; j++) {
        k = order[j]; e = 0
        for (r = 1; r <= rows[k]; r++) { d = sqrt((x[k, r] - x[ref, r]) ^ 2 + (y[k, r] - y[ref, r]) ^ 2); if (d > e) e = d }
        if (rows[k] != rows[ref]) e = -1   # a run that stopped early (its status says so)
        n = c[k]; for (a = 1; a <= n; a++) v[a] = sec[k, a]
        for (a = 2; a <= n; a++) { t = v[a]; b = a - 1; while (b >= 1 && v[b] + 0 > t + 0) { v[b + 1] = v[b]; b-- } v[b + 1] = t }
        split(k, kk, " ")
        printf "%s %s %.4e %s %s %s\n", kk[1], kk[2], e, v[int((n + 1) / 2)], steps[k], st[k]
    }
}
