#!/usr/bin/env bash
# Builds the bundled sample model database, reproducibly, the way a user builds one on a real
# machine: register tools and materials, run cutting tests over a designed grid of radial depth ×
# feed per tooth (here on the virtual machine, `feedplan simulate --cutting-test`), import each log,
# and fit one response-surface model per tool and material. Then checks every model on cutting tests
# NOT used in the fit and prints the table (prediction vs simulated per-revolution peak).
#
# Usage: scripts/build-sample-db.sh [OUT.db]   (default: build/sample.db; runs build/cli/feedplan,
# or $FEEDPLAN_BIN)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
feedplan=${FEEDPLAN_BIN:-"$root/build/cli/feedplan"}
out=${1:-"$root/build/sample.db"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
db="$work/sample.db"

"$feedplan" db init --db "$db" > /dev/null

# name, diameter mm, flutes, helix deg
tools=("SC EM D10 Z4:10:4:30" "SC EM D6 Z3:6:3:35" "SC EM D12 Z4:12:4:30")
for t in "${tools[@]}"; do
  IFS=: read -r name d z helix <<< "$t"
  "$feedplan" db add-tool "$name" --db "$db" --diameter-mm "$d" --flutes "$z" --helix-deg "$helix" \
      --tool-material "solid carbide" --coating TiAlN > /dev/null
done

# name, ISO group, hardness, cutting speed m/min, feed per tooth per mm of diameter (mm)
materials=("S50C:P:200 HB:80:0.004" "Al7075-T6:N:150 HB:300:0.008" "Ti6Al4V:S:330 HB:50:0.003" "SUS304:M:180 HB:70:0.003")
for m in "${materials[@]}"; do
  IFS=: read -r name iso hardness vc fzd <<< "$m"
  "$feedplan" db add-material "$name" --db "$db" --iso-group "$iso" --hardness "$hardness" > /dev/null
done

# One cutting test: simulate, then import (or only measure, for the held-out checks).
cut() {  # tool d z helix material rpm fz ae seed store(yes/no)
  local tool=$1 d=$2 z=$3 helix=$4 material=$5 rpm=$6 fz=$7 ae=$8 seed=$9 store=${10}
  local feed mode log="$work/cut.csv"
  feed=$(awk -v fz="$fz" -v z="$z" -v n="$rpm" 'BEGIN { printf "%.3f", fz * z * n }')
  mode=$(awk -v ae="$ae" -v d="$d" 'BEGIN { print (ae >= d ? "slot" : "down") }')
  "$feedplan" simulate --cutting-test --tool "diameter_mm=$d,flutes=$z,helix_deg=$helix,name=$tool" \
      --material "$material" --radial-depth-mm "$ae" --axial-depth-mm "$d" --feed-mm-per-min "$feed" \
      --spindle-rpm "$rpm" --cut-length-mm "$(awk -v d="$d" 'BEGIN { print 3 * d }')" \
      --noise-n 2 --seed "$seed" --log-rate 20000 --log "$log" > /dev/null
  local extra=()
  [[ $store == no ]] && extra=(--no-store)
  "$feedplan" db import-test "$log" --db "$db" --tool "$tool" --material "$material" --spindle-rpm "$rpm" \
      --feed-mm-per-min "$feed" --radial-depth-mm "$ae" --axial-depth-mm "$d" --mode "$mode" "${extra[@]}" --json
}

printf '%-14s %-10s %8s %8s %10s %10s %8s\n' tool material ae_mm fz_mm predicted_n simulated_n error_pct
seed=1
for t in "${tools[@]}"; do
  IFS=: read -r tool d z helix <<< "$t"
  for m in "${materials[@]}"; do
    IFS=: read -r material iso hardness vc fzd <<< "$m"
    rpm=$(awk -v vc="$vc" -v d="$d" 'BEGIN { printf "%.0f", vc * 1000 / (3.14159265 * d) }')
    # The fitting grid: a_e = 0.05, 0.1, 0.15, 0.2 and 0.3 × D (engagement 26°–66°, the range of the
    # trochoid, spiral and corner cycles); f_z = 0.5, 1, 1.5, 2, 2.5 × the material's feed per tooth per
    # mm of diameter × D. One quadratic in (t_m, L) does not cover slotting too (errors to 8 % when
    # a_e runs up to D): a slotting model would be a model of its own.
    for aef in 0.05 0.1 0.15 0.2 0.3; do
      for fzf in 0.5 1.0 1.5 2.0 2.5; do
        ae=$(awk -v a="$aef" -v d="$d" 'BEGIN { print a * d }')
        fz=$(awk -v f="$fzf" -v k="$fzd" -v d="$d" 'BEGIN { printf "%.4f", f * k * d }')
        cut "$tool" "$d" "$z" "$helix" "$material" "$rpm" "$fz" "$ae" $((seed++)) yes > /dev/null
      done
    done
    # Both kinds for the samples' tool and material (the mechanistic identification takes about a minute
    # per pair); the response surface for the others.
    kind=response-surface
    [[ $tool == "SC EM D10 Z4" && $material == S50C ]] && kind=both
    "$feedplan" db fit --db "$db" --tool "$tool" --material "$material" --kind "$kind" \
        --note "sample: virtual cutting tests, a_p = D, $rpm rpm" > /dev/null
    # Held-out checks inside the fitted range.
    for aef in 0.075 0.125 0.25; do
      for fzf in 0.75 1.75; do
        ae=$(awk -v a="$aef" -v d="$d" 'BEGIN { print a * d }')
        fz=$(awk -v f="$fzf" -v k="$fzd" -v d="$d" 'BEGIN { printf "%.4f", f * k * d }')
        simulated=$(cut "$tool" "$d" "$z" "$helix" "$material" "$rpm" "$fz" "$ae" $((seed++)) no |
                    awk -F: '/"peak_mean_n"/ { gsub(/[ ,]/, "", $2); print $2 }')
        predicted=$("$feedplan" db predict --db "$db" --tool "$tool" --material "$material" --radial-depth-mm "$ae" \
                    --feed-per-tooth-mm "$fz" --json | awk -F: '/"force_n"/ { gsub(/[ ,]/, "", $2); print $2 }')
        awk -v t="$tool" -v m="$material" -v ae="$ae" -v fz="$fz" -v p="$predicted" -v s="$simulated" \
            'BEGIN { printf "%-14s %-10s %8.2f %8.4f %10.1f %10.1f %8.2f\n", t, m, ae, fz, p, s, 100 * (p - s) / s }'
      done
    done
  done
done

# The cutting mechanics of the small cutter in aluminium, fitted last so that the versions above keep their
# ids: the kind `optimize` plans CAM programs with where they slot or plunge (outside every response
# surface's fitted engagement), transferred to end mills of other diameters and flute counts.
"$feedplan" db fit --db "$db" --tool "SC EM D6 Z3" --material Al7075-T6 --kind mechanistic \
    --note "sample: virtual cutting tests, a_p = D" > /dev/null

mkdir -p "$(dirname "$out")"
mv "$db" "$out.tmp" && mv "$out.tmp" "$out"
echo "sample database written to $out"
