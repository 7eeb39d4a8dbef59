#!/usr/bin/env bash
# scripts/outputs.sh BIN OUTDIR: every offline output of the CLI for a fixed set of inputs, every
# model, curve set, fibre, tendon and activation kind among them (to compare two builds:
# diff -r DIR1 DIR2). Recordings become canonical text (scripts/mcap_canon.py):
# the run's wall-clock start time masked, the chunk layout (the writer thread's timing) not compared.
set -uo pipefail
BIN="$(readlink -f "$1")"; OUT="$2"; REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rm -rf "$OUT"; mkdir -p "$OUT"; cd "$OUT"
BD="$(mktemp -d)"; trap 'rm -rf "$BD"' EXIT; ln -s "$BIN" "$BD/muscle_actuator"; BIN="$BD/muscle_actuator"
S="$REPO/scenarios"; C="$REPO/configs"
run() { local n="$1"; shift; "$BIN" "$@" > "$n.stdout" 2>&1; echo "rc=$?" >> "$n.stdout"; sed -i "s#$REPO/##g" "$n.stdout"; }
for m in hill huxley huxley-pde; do
  run pulse_$m simulate pulse --model $m --csv pulse_$m.csv --out pulse_$m.mcap
  run e10_$m simulate energy-10hz --model $m --csv e10_$m.csv --out e10_$m.mcap
  run e100_$m simulate energy-100hz --model $m --csv e100_$m.csv --out e100_$m.mcap
  run example_$m simulate "$S/example.toml" --model $m --csv example_$m.csv --out example_$m.mcap
  run four_$m simulate "$S/four_joints.toml" --model $m --config "$C/four_joints.toml" --csv four_$m.csv --out four_$m.mcap
  run driven_$m simulate "$S/driven_elbow.toml" --model $m --csv driven_$m.csv --out driven_$m.mcap
done
for m in hill huxley; do
  run armco_$m simulate "$S/arm_cocontraction.toml" --model $m --config arm --csv armco_$m.csv --out armco_$m.mcap
  run armbi_$m simulate "$S/arm_biceps.toml" --model $m --config arm --csv armbi_$m.csv --out armbi_$m.mcap
done
# Every curve set and fibre and tendon kind of OpenSim's muscles (crates/core/tests/opensim/), the
# elbow's other fibre, tendon and activation kinds (scripts/outputs/), and a person's units
# (tabulated curves, Lloyd & Besier activation, driven lengths: `predict`).
O="$REPO/crates/core/tests/opensim"
for c in "$O"/*.config.toml; do
  n=$(basename "$c" .config.toml)
  for m in hill huxley; do
    run os_${n}_$m simulate "$O/pulse.scenario.toml" --model $m --config "$c" --csv os_${n}_$m.csv
  done
done
for c in equilibrium rigid lloyd_besier; do
  for m in hill huxley; do
    run elbow_${c}_$m simulate pulse --model $m --config "$REPO/scripts/outputs/$c.toml" \
      --csv elbow_${c}_$m.csv --out elbow_${c}_$m.mcap
  done
done
D="$REPO/data/ceinms"
for m in hill huxley; do
  run predict_$m predict --subject "$D/uncalibratedSubject.xml" --excitations "$D/emgGenerator-16To34.xml" \
    --trial "$D/_FastWalking_" --model $m --csv predict_$m.csv --muscles-csv predict_units_$m.csv
done
run sub4 simulate pulse --model hill --substeps 4 --csv pulse_hill_sub4.csv
run rate500 simulate pulse --model huxley --rate-hz 500 --csv pulse_huxley_500.csv
run stdout_csv simulate pulse --model hill --csv -
run replay1 replay pulse_hill.mcap --model huxley --out replay1.mcap
run replay2 replay example_huxley.mcap --out replay2.mcap
run replay3 replay driven_hill.mcap --out replay3.mcap
run replay4 replay armbi_huxley.mcap --model hill --out replay4.mcap
run replay5 replay four_huxley-pde.mcap --out replay5.mcap
run export1 export replay1.mcap --csv export1.csv
run export2 export armco_hill.mcap --csv export2.csv
run compare1 compare pulse_hill.mcap pulse_huxley.mcap
run compare2 compare pulse_hill.mcap pulse_huxley-pde.mcap --json
run compare3 compare armco_hill.mcap armco_huxley.mcap --plot cmp_arm.png
run compare4 compare replay2.mcap example_huxley.mcap --json
head -c $(( $(stat -c%s pulse_hill.mcap) / 2 )) pulse_hill.mcap > cut.mcap
run recover1 recover cut.mcap recovered.mcap; rm -f cut.mcap
run figures figures --out figures
for c in "" simulate replay compare recover export figures node; do run "help_${c:-top}" $c --help; done
run node_bogus node --ros-args --bogus
run bad_model simulate pulse --model nope
run bad_scenario simulate nope.toml
run bad_config simulate pulse --config nope.toml
"$REPO/.venv/bin/python" "$REPO/scripts/mcap_canon.py" *.mcap
