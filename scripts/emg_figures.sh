#!/usr/bin/env bash
# The prediction figures of docs/emg.md: each of the six CEINMS trials driven by a calibrated
# subject with the Hill model and drawn by `predict --plot` (src/figures/subject_plot.rs):
#   docs/figures/emg/<trial>.png         measured vs predicted moment, one panel per degree of
#                                        freedom, R2 and RMSE in each panel's title
#   docs/figures/emg/<trial>_forces.png  the units' tendon forces through the trial
# each with an SVG beside it; the rating table of each trial on standard output.
#   scripts/emg_figures.sh CALIBRATED_SUBJECT   (a subject file `calibrate --out` wrote, or a
#                                               CEINMS XML subject with a calibration)
# MUSCLE_ACTUATOR_BIN names the binary (default target/release/muscle_actuator, built if absent).
set -euo pipefail
usage="usage: scripts/emg_figures.sh CALIBRATED_SUBJECT"
subject=$(readlink -f "${1:?$usage}")
[ -f "$subject" ] || { echo "$1: no such file" >&2; exit 2; }
# The uncalibrated subject's figures are not the ones docs/emg.md shows.
case "$subject" in
    *.xml) ! grep -q '<uncalibrated' "$subject" ;;
    *) grep -q '^\[calibration\]' "$subject" ;;
esac || { echo "$1: not a calibrated subject (calibrate one: docs/emg.md \"Calibration\")" >&2; exit 2; }
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bin=${MUSCLE_ACTUATOR_BIN:-target/release/muscle_actuator}
[ -x "$bin" ] || cargo build --release --quiet
data=data/ceinms
out=docs/figures/emg
trials=(_FastWalking_ _FastWalking1_ _FastWalking9_ _CrossOvers1_ _CrossOvers6_ _CrossOvers7_)
csv=$(mktemp -d)
trap 'rm -rf "$csv"' EXIT
mkdir -p "$out"
for t in "${trials[@]}"; do
    "$bin" predict --subject "$subject" --excitations "$data/emgGenerator-16To34.xml" \
        --trial "$data/$t" --model hill --csv "$csv/$t.csv" --plot "$out/$t.png"
done
