#!/usr/bin/env bash
# The person's knee, calibrated and predicted with the command line (docs/emg.md "Validation"):
#   1. calibrated on all six trials (what a user would hand on), per model;
#   2. calibrated on three trials (two walks, one cut) and the other three predicted, and the
#      halves swapped: every trial once predicted by a subject that never saw it.
# Prints one line per (model, calibration, trial): R2, r2, RMSE, RMSE/peak of R_knee_fe.
#   scripts/emg_validation.sh OUT_DIR [EVALUATIONS] [MODEL...]   (defaults: 1000, hill huxley)
# SUBJECT names another subject file to start from (default: the uncalibrated CEINMS subject),
# e.g. one `muscle_actuator subject` wrote with its [bounds] edited.
set -euo pipefail
usage="usage: scripts/emg_validation.sh OUT_DIR [EVALUATIONS] [MODEL...]"
mkdir -p "${1:?$usage}"
out=$(readlink -f "$1")
subject=$(readlink -f "${SUBJECT:-$(dirname "${BASH_SOURCE[0]}")/../data/ceinms/uncalibratedSubject.xml}")
[ -z "${MUSCLE_ACTUATOR_BIN:-}" ] || MUSCLE_ACTUATOR_BIN=$(readlink -f "$MUSCLE_ACTUATOR_BIN")
cd "$(dirname "${BASH_SOURCE[0]}")/.."
evaluations=${2:-1000}
shift $(( $# > 1 ? 2 : 1 ))
models=("$@")
[ $# -eq 0 ] && models=(hill huxley)
bin=${MUSCLE_ACTUATOR_BIN:-target/release/muscle_actuator}
[ -x "$bin" ] || cargo build --release --quiet
data=data/ceinms
map=$data/emgGenerator-16To34.xml
all=(_FastWalking_ _FastWalking1_ _FastWalking9_ _CrossOvers1_ _CrossOvers6_ _CrossOvers7_)
half_a=(_FastWalking_ _FastWalking9_ _CrossOvers1_)
half_b=(_FastWalking1_ _CrossOvers6_ _CrossOvers7_)
calibrate() { # model name trials...
    local model=$1 name=$2; shift 2
    local dirs=(); for t in "$@"; do dirs+=("$data/$t"); done
    "$bin" calibrate --subject "$subject" --excitations "$map" --trials "${dirs[@]}" \
        --dofs R_knee_fe --model "$model" --seed 1 --evaluations "$evaluations" \
        --out "$out/$name.toml" 2>&1 | tail -1 >&2
}
predict() { # model subject-name role trial
    local model=$1 name=$2 role=$3 trial=$4
    "$bin" predict --subject "$out/$name.toml" --excitations "$map" --trial "$data/$trial" \
        --model "$model" --csv "$out/$name$trial.csv" --muscles-csv "$out/$name${trial}_units.csv" 2>/dev/null |
        awk -v m="$model" -v n="$name" -v r="$role" -v t="$trial" \
            '$1 == "R_knee_fe" { printf "%-7s %-12s %-10s %-16s R2 %6.3f  r2 %5.3f  RMSE %6.1f N m  RMSE/peak %5.3f\n", m, n, r, t, $2, $3, $4, $5 }'
}
for model in "${models[@]}"; do
    calibrate "$model" "$model-all" "${all[@]}"
    for t in "${all[@]}"; do predict "$model" "$model-all" calibration "$t"; done
    calibrate "$model" "$model-a" "${half_a[@]}"
    calibrate "$model" "$model-b" "${half_b[@]}"
    for t in "${half_b[@]}"; do predict "$model" "$model-a" predicted "$t"; done
    for t in "${half_a[@]}"; do predict "$model" "$model-b" predicted "$t"; done
done
