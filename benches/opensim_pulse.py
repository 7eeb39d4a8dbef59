"""OpenSim's muscles through the `pulse` scenario (docs/model.md §9), one 1 ms call at a time.

One muscle of the default parameters (F_max 3913 N, l_opt 0.0959 m, tendon slack 0.3185 m, no
pennation) between two points on the ground, so its whole length stays at l_opt + l_ts (the
clamped MTU of `pulse`); excitation 1 from 1 s to 2 s, 0 otherwise; 3 s. The muscles are
OpenSim's Thelen2003Muscle, Millard2012EquilibriumMuscle and DeGrooteFregly2016Muscle (elastic
tendon, explicit mode) with their default curves, and the Manager (OpenSim's default integrator
and accuracy, and 1e-6 for DeGrooteFregly2016Muscle as `degroote-1e-6`) is asked to integrate to each 1 ms tick in
turn, as a user stepping it beside a controller would. Logging is off.

    python benches/opensim_pulse.py ROUNDS PULSE_TIME     (run by benches/opensim_pulse.sh)

Each round runs this project's `pulse` (PULSE_TIME: the executable of examples/pulse_time.rs,
in a process of its own with two rounds of Hill and DM, each as `Scenario::run`, as its runner's
steps alone and as the runner's set-up; the first round's names end in `-first`) and then
OpenSim's two muscles, so the machine's drifting load weighs on all of them alike. Prints each
run (`MUSCLE µs_per_tick tendon_force_at_2s_N`), then the median µs per muscle-tick of each and
OpenSim's over this project's.
"""

import statistics
import subprocess
import sys
import time

import opensim as osim

F_MAX, L_OPT, L_TS = 3913.0, 0.0959, 0.3185
#: OpenSim's muscles timed: Thelen2003, Millard2012 (default accuracy), DeGrooteFregly2016 with
#: an elastic tendon at the default accuracy and at 1e-6.
OPENSIM_KINDS = ["thelen", "millard", "degroote", "degroote-1e-6"]
TICKS, DT = 3000, 1e-3


def model_with(kind):
    model = osim.Model()
    model.setName(f"pulse_{kind}")
    if kind == "thelen":
        muscle = osim.Thelen2003Muscle("muscle", F_MAX, L_OPT, L_TS, 0.0)
    elif kind.startswith("degroote"):
        # Its elastic tendon in the explicit mode (the default), its own activation dynamics.
        muscle = osim.DeGrooteFregly2016Muscle()
        muscle.setName("muscle")
        muscle.setMaxIsometricForce(F_MAX)
        muscle.setOptimalFiberLength(L_OPT)
        muscle.setTendonSlackLength(L_TS)
        muscle.set_ignore_tendon_compliance(False)
    else:
        muscle = osim.Millard2012EquilibriumMuscle("muscle", F_MAX, L_OPT, L_TS, 0.0)
    ground = model.getGround()
    muscle.addNewPathPoint("origin", ground, osim.Vec3(0, 0, 0))
    muscle.addNewPathPoint("insertion", ground, osim.Vec3(L_OPT + L_TS, 0, 0))
    model.addForce(muscle)
    excitation = osim.PiecewiseLinearFunction()
    # DeGrooteFregly2016Muscle's explicit mode divides by the activation: its excitation stays
    # at 0.01 or more (the others' at 0 or more, as `pulse`).
    base = 0.01 if kind.startswith("degroote") else 0.0
    for t, u in [(0.0, base), (1.0, base), (1.0 + 1e-9, 1.0), (2.0, 1.0), (2.0 + 1e-9, base),
                 (3.0, base)]:
        excitation.addPoint(t, u)
    controller = osim.PrescribedController()
    controller.addActuator(muscle)
    controller.prescribeControlForActuator("muscle", excitation)
    model.addController(controller)
    return model


def run(kind):
    model = model_with(kind)
    state = model.initSystem()
    muscle = osim.Muscle.safeDownCast(model.getForceSet().get("muscle"))
    muscle.setActivation(state, 0.01)
    model.equilibrateMuscles(state)
    manager = osim.Manager(model)
    if kind.endswith("-1e-6"):
        manager.setIntegratorAccuracy(1e-6)
    manager.initialize(state)
    force_at_2s = float("nan")
    t0 = time.perf_counter()
    for k in range(1, TICKS + 1):
        state = manager.integrate(k * DT)
        if k == 2000:
            model.realizeDynamics(state)
            force_at_2s = muscle.getTendonForce(state)
    elapsed = time.perf_counter() - t0
    return elapsed * 1e6 / TICKS, force_at_2s


def main():
    osim.Logger.setLevelString("off")
    rounds, ours = int(sys.argv[1]), sys.argv[2]
    times = {}
    for _ in range(rounds):
        lines = subprocess.run([ours, "2"], check=True, capture_output=True, text=True).stdout
        runs = [line.split() for line in lines.splitlines()]
        runs += [[kind, *map(str, run(kind))] for kind in OPENSIM_KINDS]
        for name, us, force in runs:
            print(f"{name} {float(us):.2f} µs per tick, force at 2 s {float(force):.1f} N", flush=True)
            times.setdefault(name, []).append(float(us))
    median = {k: statistics.median(v) for k, v in times.items()}
    print(f"median of {rounds} rounds, µs per muscle-tick: "
          + ", ".join(f"{k} {v:.2f}" for k, v in median.items()))
    for osim_name in OPENSIM_KINDS:
        for ours_name in [k for k in median if k not in OPENSIM_KINDS and "setup" not in k]:
            print(f"{osim_name} / {ours_name}: {median[osim_name] / median[ours_name]:.0f}x")


if __name__ == "__main__":
    main()
