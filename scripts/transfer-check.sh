#!/usr/bin/env bash
# The transfer experiment: how well a force model identified from straight cutting tests on one machine
# predicts the forces of real cycles on the SAME machine.
#
# On a fresh temporary database it
#   1. runs the straight cutting tests of the sample database's grid (scripts/build-sample-db.sh:
#      a_e = 0.05 … 0.3 × D, f_z = 0.5 … 2.5 × 0.004 mm/mm × D, a_p = D, 2546 rpm) for the samples' tool
#      SC EM D10 Z4 in S50C on MACHINE (`feedplan simulate --cutting-test --machine`), imports each log
#      and fits both kinds of model from them (`feedplan db fit --kind both`: the response surface on the
#      peaks, the mechanistic model — coefficients, runout, helix — on the force over a revolution);
#   2. plans samples/trochoid.yaml (R 5), trochoid_r15.yaml (R 15), spiral.yaml and corner.yaml with
#      each kind (`feedplan plan --model-kind`), and runs each program on the same machine (`feedplan
#      simulate PROGRAM --spec SPEC --machine MACHINE --peaks PEAKS.csv`);
#   3. prints a table per cycle from the per-revolution peaks of the true force (the peaks CSV):
#        in_cut      revolutions with a peak above 5 % of the target;
#        max_peak_n  the largest per-revolution peak, and max_err_pct its error vs the target;
#        p50_err_pct the median error of the revolutions cutting at more than half the target (steady cut);
#        fronts      (trochoids only) loop fronts: a front is the first 3 in-cut revolutions after an air gap (a revolution
#                    at or below 5 % of the target); each front's error is its largest peak vs the target;
#                    worst_front_pct is the front error largest in magnitude, mean_front_pct their mean.
#   A cycle the model cannot plan at its target (the model predicts more than the target even at the
#   lowest feed) gets a row saying so; the plan's message goes to stderr.
#   Errors are signed: + the machine cut harder than the target, − softer.
#   A line above the table gives each kind's leave-one-engagement-out error on the tests and the kind
#   `feedplan plan` chooses by it when --model-kind is not given.
#
# The planner knows only the catalogue tool: the machine's helix offset, runout and size effect reach
# the model only through what the cutting tests measured.
#
# With --check-fronts it is a test too: for every trochoid whose worst loop front the response surface misses by
# more than ±10 %, the mechanistic kind's worst front must lie within ±5 %; it fails (exit 1) otherwise, or when no
# trochoid has such a front (the machine then shows nothing about the kinds).
#
# Usage: scripts/transfer-check.sh MACHINE.yaml [--check-fronts]   (runs build/cli/feedplan, or $FEEDPLAN_BIN)
# Takes about 30 s on steel-eccentric (25 cutting tests, the mechanistic identification, 8 plans, 8 programs on the
# virtual machine).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
feedplan=${FEEDPLAN_BIN:-"$root/build/cli/feedplan"}
check_fronts=no
if [[ $# -eq 2 && $2 == --check-fronts ]]; then
  check_fronts=yes
elif [[ $# -ne 1 ]]; then
  echo "usage: $0 MACHINE.yaml [--check-fronts]" >&2
  exit 2
fi
machine=$1
if [[ ! -r $machine ]]; then
  echo "$0: MACHINE.yaml = $machine: not a readable file" >&2
  exit 2
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
db="$work/transfer.db"

run() {  # prints the command (quoted so it can be pasted), then runs it with its output discarded
  echo "+ $(printf '%q ' "$@")" >&2
  "$@" > /dev/null
}

tool="SC EM D10 Z4" d=10 z=4 helix=30 material=S50C rpm=2546 fzd=0.004
run "$feedplan" db init --db "$db"
run "$feedplan" db add-tool "$tool" --db "$db" --diameter-mm $d --flutes $z --helix-deg $helix \
    --tool-material "solid carbide" --coating TiAlN
run "$feedplan" db add-material $material --db "$db" --iso-group P --hardness "200 HB"

seed=1
for aef in 0.05 0.1 0.15 0.2 0.3; do
  for fzf in 0.5 1.0 1.5 2.0 2.5; do
    ae=$(awk -v a="$aef" -v d="$d" 'BEGIN { print a * d }')
    fz=$(awk -v f="$fzf" -v k="$fzd" -v d="$d" 'BEGIN { printf "%.4f", f * k * d }')
    feed=$(awk -v fz="$fz" -v z="$z" -v n="$rpm" 'BEGIN { printf "%.3f", fz * z * n }')
    run "$feedplan" simulate --cutting-test --machine "$machine" \
        --tool "diameter_mm=$d,flutes=$z,helix_deg=$helix,name=$tool" --radial-depth-mm "$ae" --axial-depth-mm $d \
        --feed-mm-per-min "$feed" --spindle-rpm $rpm --cut-length-mm $((3 * d)) --seed $((seed++)) --log-rate 20000 \
        --log "$work/cut.csv"
    run "$feedplan" db import-test "$work/cut.csv" --db "$db" --tool "$tool" --material $material --spindle-rpm $rpm \
        --feed-mm-per-min "$feed" --radial-depth-mm "$ae" --axial-depth-mm $d --mode down
  done
done
run "$feedplan" db fit --db "$db" --tool "$tool" --material $material --kind both --note "transfer check on $machine"

# Table of one cycle from its peaks CSV (revolution,t_start_s,t_end_s,t_peak_s,peak_xy_n,mean_xy_n).
table_row() {  # name target peaks.csv loops(yes/no)
  awk -F, -v name="$1" -v target="$2" -v loops="$4" -v fronts_file="$work/fronts.txt" '
    NR == 1 { next }
    {
      peak = $5; air = peak <= 0.05 * target
      if (air) { gap = 1; next }
      n++; if (peak > max) max = peak
      if (peak > 0.5 * target) steady[++ns] = 100 * (peak - target) / target
      if (gap || n == 1) { fronts++; left = 3; front_max[fronts] = 0 }
      gap = 0
      if (left > 0) { if (peak > front_max[fronts]) front_max[fronts] = peak; left-- }
    }
    END {
      # median of the steady errors (insertion sort: a few thousand revolutions at most)
      for (i = 2; i <= ns; i++) { v = steady[i]; for (j = i - 1; j >= 1 && steady[j] > v; j--) steady[j + 1] = steady[j]; steady[j + 1] = v }
      p50 = ns ? (ns % 2 ? steady[(ns + 1) / 2] : (steady[ns / 2] + steady[ns / 2 + 1]) / 2) : 0
      worst = 0; sum = 0
      for (f = 1; f <= fronts; f++) {
        e = 100 * (front_max[f] - target) / target; sum += e
        if (f == 1 || (e < 0 ? -e : e) > (worst < 0 ? -worst : worst)) worst = e
      }
      printf "%-22s %8.0f %7d %10.1f %11.1f %11.1f", name, target, n, max, 100 * (max - target) / target, p50
      if (loops == "yes") printf " %6d %15.1f %14.1f\n", fronts, worst, fronts ? sum / fronts : 0
      else printf " %6s %15s %14s\n", "-", "-", "-"
      if (loops == "yes") printf "%s %.2f\n", name, worst >> fronts_file
    }' "$3"
}

rows=()
for spec in trochoid trochoid_r15 spiral corner; do
  for kind in response-surface mechanistic; do
    specfile="$root/samples/$spec.yaml"
    target=$(awk -F: '/^target_force_n:/ { gsub(/[ ]/, "", $2); print $2 }' "$specfile")
    name="$spec ${kind%%-*}"
    out="$work/$spec.$kind"
    # Blocks that follow the feed limits closely (--feed-step 0): the figures judge the model, and F levels
    # rounded down would add their own few per cent under the target.
    echo "+ $(printf '%q ' "$feedplan" plan "$specfile" --db "$db" --model-kind "$kind" --feed-step 0 -o "$out.nc")" >&2
    if ! "$feedplan" plan "$specfile" --db "$db" --model-kind "$kind" --feed-step 0 -o "$out.nc" > /dev/null 2> "$work/plan.err"; then
      cat "$work/plan.err" >&2
      rows+=("$(printf '%-22s %8.0f  no plan: %s' "$name" "$target" "$(grep -o 'raise the target to at least [0-9.]* N' "$work/plan.err" || echo 'feedplan plan failed, see above')")")
      continue
    fi
    cat "$work/plan.err" >&2
    run "$feedplan" simulate "$out.nc" --spec "$specfile" --machine "$machine" --log "$out.log.csv" --peaks "$out.peaks.csv"
    loops=no
    [[ $spec == trochoid* ]] && loops=yes
    rows+=("$(table_row "$name" "$target" "$out.peaks.csv" $loops)")
  done
done

# The figure `feedplan plan` chooses its default kind by: each kind's leave-one-engagement-out error on the tests.
engagement_cv() {  # kind
  "$feedplan" db show --db "$db" --tool "$tool" --material $material --kind "$1" --json |
    awk -F: '/"engagement_cv_rmse_n"/ { gsub(/[ ,]/, "", $2); printf "%.1f", $2 }'
}
cv_rs=$(engagement_cv response-surface) cv_mech=$(engagement_cv mechanistic)
default_kind=$(awk -v rs="$cv_rs" -v m="$cv_mech" 'BEGIN { print (rs > 0 && m > 0 && m < rs) ? "mechanistic" : "response surface" }')

echo "machine $machine: both kinds of model fitted on 25 straight cutting tests, cycles planned with each and cut on the same machine"
echo "leave-one-engagement-out error on the tests: response surface $cv_rs N, mechanistic $cv_mech N; plan's default kind: $default_kind"
printf '%-22s %8s %7s %10s %11s %11s %6s %15s %14s\n' cycle target_n in_cut max_peak_n max_err_pct p50_err_pct \
    fronts worst_front_pct mean_front_pct
printf '%s\n' "${rows[@]}"

if [[ $check_fronts == yes ]]; then
  # fronts.txt: "<spec> <kind> <worst front %>" per trochoid planned (a kind that could not plan has no line).
  awk -v machine="$machine" '
    { worst[$1 " " $2] = $3; specs[$1] = 1 }
    END {
      for (spec in specs) {
        rs = spec " response"; mech = spec " mechanistic"
        if (!(rs in worst)) continue
        if (worst[rs] <= 10 && worst[rs] >= -10) continue
        compared++
        if (!(mech in worst)) { printf "FAIL %s: the response surface misses its worst front by %+.1f %% and the mechanistic kind did not plan\n", spec, worst[rs]; failed++; continue }
        ok = worst[mech] <= 5 && worst[mech] >= -5
        printf "%s %s: worst front response surface %+.1f %%, mechanistic %+.1f %%\n", ok ? "ok" : "FAIL", spec, worst[rs], worst[mech]
        if (!ok) failed++
      }
      if (!compared) { printf "FAIL: on %s no trochoid front is missed by more than ±10 %% by the response surface: nothing to compare\n", machine; exit 1 }
      exit failed ? 1 : 0
    }' "$work/fronts.txt"
fi
