#!/bin/sh
# Are the results of two builds the same, digit for digit? Runs a set of driver
# runs and unit suites with the programs of build A and of build B and compares
# their standard output and standard error and exit statuses; the wall-clock and
# memory fields (seconds=, output_seconds=, seconds_per_step=, peak_rss_kb=, and
# the seconds column of the trust driver's rows) are filtered out. For a
# refactoring that must leave every result bitwise unchanged.
# Usage: check_unchanged.sh BUILD_A BUILD_B   (each with bin/ and test/regdae_tester,
#        test/capi_tester, e.g. a copy of main's release build and the worktree's)
# Prints one line per run and "N of N identical"; exit status 1 if any differs.
a=${1:?usage: check_unchanged.sh BUILD_A BUILD_B}
b=${2:?usage: check_unchanged.sh BUILD_A BUILD_B}
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT

runs='bin/ex52
bin/ex52 rtol=1e-4 atol=1e-4
bin/ex52 rtol=1e-8 atol=1e-8
bin/ex52 rtol=1e-10 atol=1e-10
bin/ex52 integrator=ida
bin/ex52 integrator=ida rtol=1e-8 atol=1e-8
bin/ex52 integrator=dopri5
bin/ex52 integrator=dopri5 gamma1=20 gamma0=200 eps=1e-14 stop_at_output=no nout=200
bin/ex52 formulation=augmented
bin/ex52 formulation=augmented linear_solver=dense rtol=1e-7 atol=1e-7
bin/ex52 formulation=multiplier excluded=vy tf=3 nout=100
bin/ex52 formulation=multiplier
bin/ex52 formulation=eliminated integrator=ida
bin/ex52 index=2
bin/ex52 index=2 gamma=1e6 rtol=1e-6 atol=1e-6 nout=100 tf=3
bin/ex52 index=2 gamma=1e6 rtol=1e-6 atol=1e-6 nout=100
bin/ex52 index=3 gamma1=100 gamma0=5000 eps=1e-14 rtol=1e-5 atol=1e-5 nout=50
bin/ex52 th1=1e-8 w1=0 rtol=1e-5 atol=1e-5 nout=100
bin/ex52 th1=1.5707963267948966 w1=1
bin/ex52 th1=1.5707963267948966 w1=1 formulation=augmented
bin/ex52 rtol=1e-5 atol=1e-5 nout=100 error_estimate=yes pass_tol=5
bin/ex52 invariant_tol=1 drift_tol=1e-3 tf=3 nout=100
bin/ex52 method=direct index=2 gamma=1e3 eps=1e-6 nout=200 integrator=ida pass_check=no
bin/ex52 index=2 gamma=1e3 eps=1e-6 rtol=1e-7 atol=1e-7 nout=200 pass_check=no
bin/ex52 tf=4.9e-324
bin/ex52 gamma0=1e300
bin/ex51
bin/ex51 method=baumgarte integrator=ida nout=50
bin/ex51 method=baumgarte nout=50
bin/ex51 method=direct formulation=multiplier lsq=normal nout=50
bin/ex51 formulation=eliminated lsq=stacked exclusion=weights nout=50
bin/ex51 integrator=dopri5 gamma=10 nout=50
bin/ex51 exclusion=off stop_at_output=no nout=50
bin/pendulum tf=3 nout=100
bin/pendulum integrator=dopri5 tf=3 nout=100
bin/pendulum curvature=no method=baumgarte tf=3 nout=100
bin/chain n_links=4 mass=1e-2 stiffness=1e4 damping=10
bin/chain n_links=4 mass=1e-2 stiffness=1e4 damping=10 formulation=eliminated
bin/chain n_links=64
bin/chain n_links=64 integrator=ida
bin/chain n_links=16 linear_solver=band check_jacobians=yes
bin/chain n_links=8 slider=yes linear_solver=sparse nout=10
bin/chain n_links=8 formulation=augmented linear_solver=dense method=direct
bin/chain n_links=2 slider=yes
bin/ex52 integrator=radau
bin/ex52 integrator=radau rtol=1e-8 atol=1e-8
bin/ex52 integrator=radau formulation=augmented
bin/chain n_links=4 mass=1e-2 stiffness=1e4 damping=10 integrator=radau formulation=eliminated
bin/chain n_links=4 mass=1e-2 stiffness=1e4 damping=10 integrator=radau formulation=augmented rtol=1e-6 atol=1e-6
bin/car_axis
bin/car_axis_index3
bin/order3 eps=1e-9 rtol=1e-8 atol=1e-8
bin/order3
bin/redundant tf=3 nout=100
bin/singular_mass tf=2 nout=100
bin/singular_mass carrier=follower tf=2 nout=100
bin/trust family=crank cell=1
bin/trust family=crank cell=5
bin/trust family=crank cell=17
bin/trust family=crank cell=40
bin/trust family=crank cell=80
bin/example_circle
bin/example_circle_c
bin/example_ex51_f77
test/regdae_tester solver
test/regdae_tester api
test/regdae_tester mechanics
test/regdae_tester structure
test/regdae_tester defaults
test/regdae_tester hardening
test/regdae_tester lsq
test/regdae_tester residuals
test/regdae_tester theory
test/regdae_tester radau
test/regdae_tester radau_solver
test/capi_tester'

filter() {   # FILE RUN
    case $2 in
    bin/trust*) awk '/^ +[0-9]+ /{$14 = "X"} {print}' "$1" ;;   # column 14: seconds
    bin/car_axis*) awk '/^car_axis /{$6 = "X"; $15 = "X"} {print}' "$1" ;;   # seconds, x_radau5_time
    *) sed -E 's/(seconds|output_seconds|seconds_per_step|peak_rss_kb)=[^ ]*/\1=X/g' "$1" ;;
    esac
}

same=0
total=0
echo "$runs" | {
    while IFS= read -r run; do
        total=$((total + 1))
        (cd "$a" && $run >"$dir/a.out" 2>"$dir/a.err"; echo "exit $?" >>"$dir/a.err")
        (cd "$b" && $run >"$dir/b.out" 2>"$dir/b.err"; echo "exit $?" >>"$dir/b.err")
        filter "$dir/a.out" "$run" >"$dir/a.f"
        filter "$dir/b.out" "$run" >"$dir/b.f"
        if cmp -s "$dir/a.f" "$dir/b.f" && cmp -s "$dir/a.err" "$dir/b.err"; then
            same=$((same + 1))
            echo "same     $run ($(wc -l <"$dir/a.f") lines)"
        else
            echo "DIFFERS  $run"
            diff "$dir/a.f" "$dir/b.f" | head -6
            diff "$dir/a.err" "$dir/b.err" | head -4
        fi
    done
    echo "$same of $total identical"
    [ "$same" -eq "$total" ]
}
