#!/bin/sh
# Driver-level checks of the chain (issue 10): every linear solver, with and
# without the sliders, the slider crank case against its reduced ODE, the peer.
# Usage: check_chain.sh path/to/chain
driver=${1:?usage: check_chain.sh path/to/chain}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
. "$(dirname "$0")/check_lib.sh"

# 1. N = 2 with the slider is Example 5.2's slider crank in Cartesian coordinates: joint 1's angle
#    against the reduced ODE (CVODE at 1e-13) through the singular configuration (t ~ 0.85).
#    Measured 4.2e-7 at rtol = 1e-8 and eps = 1e-10 (eps = 1e-6: 3.4e-6, the regularization's floor).
run crank n_links=2 slider=yes rtol=1e-8 atol=1e-8 eps=1e-10
[ "$(rc crank)" = 0 ] && le "$(field crank max_err_th)" 1e-6
check "slider crank (N = 2): max_err_th=$(field crank max_err_th) <= 1e-6" $?

# 2. Dense, band and sparse (augmented formulation), N = 8, with and without the sliders: all ok,
#    the constraint kept (max |g| <= 10 rtol) and the same end position (to 10 rtol times |x| <= 8).
for slider in no yes; do
    for ls in dense band sparse; do
        run "${slider}_$ls" n_links=8 slider=$slider formulation=augmented linear_solver=$ls rtol=1e-7 atol=1e-7
        [ "$(rc "${slider}_$ls")" = 0 ] && [ "$(field "${slider}_$ls" engine)" = "augmented/$ls" ] && \
            le "$(field "${slider}_$ls" max_drift)" 1e-6
        check "N = 8 slider=$slider $ls: ok, max_drift=$(field "${slider}_$ls" max_drift) <= 1e-6" $?
    done
    end_dense=$(grep -v '^#' "$tmp/${slider}_dense.out" | grep -v '^summary' | tail -n 1)
    for ls in band sparse; do
        end_other=$(grep -v '^#' "$tmp/${slider}_$ls.out" | grep -v '^summary' | tail -n 1)
        echo "$end_dense $end_other" | awk '{ exit !((($2 - $8)^2 + ($3 - $9)^2) <= (8e-6)^2) }'   # rows of 6 columns
        check "N = 8 slider=$slider: $ls ends where dense does" $?
    done
done

# 3. The defaults choose the augmented formulation and the sparse (KLU) solver from 16 coordinates on.
run defaults n_links=32
[ "$(rc defaults)" = 0 ] && case $(field defaults engine) in augmented/sparse) true ;; *) false ;; esac
check "N = 32 defaults: engine=$(field defaults engine)" $?

# 4. The plain IDA peer runs on the same chain.
run peer n_links=8 slider=yes peer=yes
[ "$(rc peer)" = 0 ] && [ "$(field peer engine)" = peer/band ]
check "peer: ok" $?

# 5. Memory from init on grows with the nonzeros (issue 20): a structured chain of 20000 links
#    (n = 40000, m = 20000) within 1 GB of address space. Before, init built a dense m x n G
#    (6.4 GB) and failed under this limit; measured 0.17 GB resident at 20000 links.
#    Skipped under the sanitizers, whose shadow memory needs terabytes of address space.
if [ -z "${REGDAE_SANITIZE:-}" ]; then
    (ulimit -v 1048576 && "$driver" n_links=20000 tf=0.001 nout=1) >"$tmp/big.out" 2>"$tmp/big.err"
    echo $? >"$tmp/big.rc"
    [ "$(rc big)" = 0 ] && [ "$(field big status)" = ok ] && [ "$(field big engine)" = augmented/sparse ]
    check "N = 20000 under ulimit -v 1 GB: exit $(rc big), status=$(field big status)" $?
    # the dense formulation of the same chain does not fit: a status and a message, not a signal
    (ulimit -v 1048576 && "$driver" n_links=20000 tf=0.001 nout=1 formulation=eliminated) >"$tmp/dense.out" 2>"$tmp/dense.err"
    echo $? >"$tmp/dense.rc"
    [ "$(rc dense)" = 1 ] && [ "$(field dense status)" = failed ] && grep -q '^# error: out of memory' "$tmp/dense.out"
    check "N = 20000 eliminated under ulimit -v 1 GB: exit $(rc dense), says out of memory" $?
fi

# 7. The stiff chain (light joints on stiff springs, omega = 1000 rad/s) on Radau IIA and the
#    augmented formulation, against IDA on the same formulation at 1e-11: the run must end ok, the
#    free end (the table's x_end, y_end at the 101 outputs) within 10 (R |x| + R) of the reference
#    in x, and in y within 100 R of the motion's amplitude (max |y_end| at the outputs, 9.8e-6:
#    atol = R would not measure it).
#    rtol 1e-6 (issue 19 item 4): its first step (omega h = 1.16) stopped the run with
#    regdae_err_work at t = 1.16e-3 (defect 0.115): the trapezoid through the step's ends gave the
#    forces' work as 3.3e-8 where the kinetic energy reached 5.73e-7; the augmented samples now
#    refine such an interval on the integrator's motion. Measured |dy| 2.6e-10 of 9.8e-10.
#    rtol 3.16e-9, 1e-9, 1e-10 (issue 21): Radau's step size collapsed to 1e-17 ... 1e-19 (the
#    Newton increments of the accelerations and multipliers stalled at the rounding floor of the
#    Baumgarte rows, 1e-8, far above kappa times their weights); now measured |dy| 4.9e-13 of
#    3.1e-12, 4.6e-13 of 9.8e-13, 3.3e-14 of 9.8e-14.
stiff='n_links=4 mass=1e-2 stiffness=1e4 damping=10 tf=1 nout=100 formulation=augmented'
# shellcheck disable=SC2086
run stiff_ref $stiff integrator=ida rtol=1e-11 atol=1e-11
grep -v '^#' "$tmp/stiff_ref.out" | grep -v '^summary' >"$tmp/stiff_ref.tab"
for r in 1e-6 3.16e-9 1e-9 1e-10; do
    # shellcheck disable=SC2086
    run "stiff_$r" $stiff integrator=radau rtol=$r atol=$r
    [ "$(rc "stiff_$r")" = 0 ] && [ "$(field "stiff_$r" status)" = ok ] && [ "$(field stiff_ref status)" = ok ]
    check "stiff chain on Radau, rtol $r: status=$(field "stiff_$r" status) (reference $(field stiff_ref status))" $?
    grep -v '^#' "$tmp/stiff_$r.out" | grep -v '^summary' >"$tmp/stiff_$r.tab"
    paste "$tmp/stiff_$r.tab" "$tmp/stiff_ref.tab" | awk -v r="$r" '
        function abs(u) { return u < 0 ? -u : u }
        { rows++; if (abs($9) > amp) amp = abs($9); dx = abs($2 - $8); dy = abs($3 - $9)
          if (dx > 10 * (r * abs($8) + r)) bad = 1; if (dy > my) my = dy }
        END { printf "max |dy| %.2e, bound %.2e\n", my, 100 * r * amp; exit !(rows == 101 && !bad && amp > 0 && my <= 100 * r * amp) }'
    check "stiff chain on Radau, rtol $r: the free end at the 101 outputs as IDA's at 1e-11" $?
done

# 8. A light 2-chain on stiff springs (omega = sqrt(k/m) = 2566 rad/s) from rest with the
#    defaults at rtol 1e-4 (cell 5 of `stiff_chain_grid.sh BIN 6363`), against the plain IDA peer at
#    1e-10: Radau's first step (6.0e-4 s, a quarter of the period: from rest to the spring's
#    equilibrium) stopped the run with regdae_err_work at t = 6.0e-4 (defect 0.52 of S): the power
#    is 0 at both ends of the step (rest, the kinetic energy's peak), the trapezoid gave -9.2e-11
#    of work where the kinetic energy gained 1.06e-7, and its estimate h |dP|/2 (9.2e-11) stayed
#    below the refinement's threshold; now an interval whose own balance is off is refined too
#    (doc/methods.md, work-energy balance). Measured |dy| 1.34e-7 of an amplitude of 1.51e-6 (the
#    peer at rtol 1e-4: 5.8e-7).
quarter='n_links=2 mass=8.002e-03 stiffness=5.267e+04 damping=1.306 tf=1 nout=100'
# shellcheck disable=SC2086
run quarter_ref $quarter peer=yes rtol=1e-10 atol=1e-10
grep -v '^#' "$tmp/quarter_ref.out" | grep -v '^summary' >"$tmp/quarter_ref.tab"
for a in integrator=auto integrator=radau; do
    # shellcheck disable=SC2086
    run "quarter_$a" $quarter rtol=1e-4 atol=1e-4 $a
    [ "$(rc "quarter_$a")" = 0 ] && [ "$(field "quarter_$a" status)" = ok ] && [ "$(field quarter_ref status)" = ok ]
    check "stiff 2-chain, quarter-period first step, $a: status=$(field "quarter_$a" status)" $?
    grep -v '^#' "$tmp/quarter_$a.out" | grep -v '^summary' >"$tmp/quarter_$a.tab"
    paste "$tmp/quarter_$a.tab" "$tmp/quarter_ref.tab" | awk '
        function abs(u) { return u < 0 ? -u : u }
        { rows++; if (abs($9) > amp) amp = abs($9); if (abs($2 - $8) > 1e-3 * (abs($8) + 1)) bad = 1
          dy = abs($3 - $9); if (dy > my) my = dy }
        END { printf "max |dy| %.2e, bound %.2e\n", my, 0.2 * amp; exit !(rows == 101 && !bad && amp > 0 && my <= 0.2 * amp) }'
    check "stiff 2-chain, $a: the free end at the 101 outputs as the IDA peer's at 1e-10" $?
done

# 6. Bad arguments.
run odd n_links=3 slider=yes
[ "$(rc odd)" = 2 ] && grep -q 'even n_links' "$tmp/odd.err"
check "slider=yes with odd n_links: exit 2, says why" $?
run zero n_links=0
[ "$(rc zero)" = 2 ] && grep -q n_links "$tmp/zero.err"
check "n_links=0: exit 2, names n_links" $?
finish
