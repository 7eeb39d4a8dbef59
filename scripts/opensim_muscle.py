#!/usr/bin/env python3
"""OpenSim's own simulation of one muscle whose muscle-tendon length l_mt(t) and activation a(t)
are prescribed: the reference the engine's muscle is compared against.

    .venv/bin/python scripts/opensim_muscle.py --inputs IN.csv --out OUT.csv \\
        --muscle degroote2016|thelen2003|millard2012 --tendon elastic|rigid --fmax N --lopt M --lts M \\
        --vmax M_PER_S [--pennation RAD] [--tendon-strain X] [--passive-strain X] [--damping B]

IN.csv: a header `t,activation,mtu_length`, then rows on a time grid (SI units); both inputs are
piecewise LINEAR in time between rows. OUT.csv: a comment line naming the OpenSim version and
this command, then `t,activation,mtu_length,tendon_force,fiber_length,fiber_velocity,
pennation_angle`, a row per input row (activation and mtu_length read back from the model),
numbers in Python's shortest round-trip form: N, m along the fibre, m/s lengthening positive, rad.

The model is that of scripts/opensim_curves.py: ground, a slider body, the muscle from ground's
origin to the body's, so the path length is the slider coordinate, prescribed
(`setPrescribedFunction`, `setDefaultIsPrescribed`). Activation comes from a PrescribedController.
Both functions are PiecewiseLinearFunctions holding only the current interval between two rows,
moved forward row by row: one function through all rows has an ambiguous slope at its knots
(its binary search returns either side's), and OpenSim's prescribed-motion constraint cannot
follow a jump of speed inside a step. `--vmax` is in m/s; OpenSim's max_contraction_velocity is in
optimal fibre lengths per second (vmax / lopt). `--tendon-strain` / `--passive-strain` set
tendon_strain_at_one_norm_force / passive_fiber_strain_at_one_norm_force (DeGrooteFregly2016Muscle)
or FmaxTendonStrain / FmaxMuscleStrain (Thelen2003Muscle); `--active-force-width-scale`
(DeGrooteFregly2016Muscle) and `--kshape-active`, `--kshape-passive`, `--af`, `--flen`
(Thelen2003Muscle) set those properties; `--damping` sets fiber_damping
(damping force along the fibre = fiber_damping Fmax v / vmax); Thelen2003Muscle has none.
For Millard2012EquilibriumMuscle `--tendon-strain` / `--passive-strain` set the
strain_at_one_norm_force of its TendonForceLengthCurve / FiberForceLengthCurve.

DeGrooteFregly2016Muscle: ignore_activation_dynamics, so activation = control. Elastic tendon:
the explicit tendon-compliance mode (the default); its one state is the normalised tendon force,
the fibre velocity follows from the force balance (without the damping term) through the inverse
force-velocity curve. Rigid tendon: ignore_tendon_compliance.

Millard2012EquilibriumMuscle: as DeGrooteFregly2016Muscle, ignore_activation_dynamics and, for
a rigid tendon, ignore_tendon_compliance; elastic, its state is the fibre length and, with
fiber_damping > 0, its fibre velocity solves the damped force balance by Newton's method.

Thelen2003Muscle refuses both flags in OpenSim 4.6 ("flag is not currently implemented"). Its
activation stays a state, da/dt = (u - a)/tau, tau = t_act (0.5 + 1.5 a) if u > a else
t_deact / (0.5 + 1.5 a), a clamped to [minimum_activation 0.01, 1], the control u not clamped.
Both time constants are set to THELEN_TAU and u is the exact inverse along the prescribed a(t),
u = a + tau(a) da/dt, sampled THELEN_SUB + 1 times per interval (checked against the muscle's
activation model); inputs need 0.01 <= a <= 1 and the activation read back must match within
1e-8. Its rigid tendon, not a mode of OpenSim, is assembled row by row from OpenSim's own
functions: the pennation model's fibre length at tendon slack length, then
calcInextensibleTendonActiveFiberForce (a fal fv Fmax cos(pennation), fv by inverting Thelen's
force-velocity relation) plus the passive multiplier times Fmax cos(pennation).

Initial state: the muscle equilibrated at the first row (`model.equilibrateMuscles`), as OpenSim
users do: DeGrooteFregly2016Muscle solves for the tendon force at zero tendon velocity (damping
included), Thelen2003Muscle shares the lengthening speed between fibre and tendon by stiffness.
The Manager (Runge-Kutta-Merson, `--accuracy`, default 1e-12: 1e-9 moves Thelen's tendon force
by up to ~1e-3 N, DeGroote's by ~3e-5 N) steps from row to row with its final time at the next
row, so every recorded state is a step's end and every kink is a step boundary. A rigid tendon
has no state: each row is evaluated at its length, activation and speed = the slope of the
interval ending at the row (the first row: the first interval's), as the engine's output after a
tick carries the speed the tick was stepped with. A watchdog ends the process after `--timeout` s of wall time.
"""

import argparse
import faulthandler
import shlex
import sys
import time

import opensim as osim

THELEN_TAU = 1e-3  # s, both Thelen activation time constants (the control inverts them)
THELEN_SUB = 256  # intervals of the Thelen control between two rows


def read_inputs(path):
    with open(path) as f:
        lines = [ln.strip() for ln in f if ln.strip() and not ln.startswith("#")]
    if lines[0].replace(" ", "") != "t,activation,mtu_length":
        sys.exit(f"{path}: the header must be `t,activation,mtu_length`")
    rows = [tuple(float(x) for x in ln.split(",")) for ln in lines[1:]]
    t, a, l = (list(c) for c in zip(*rows))
    if len(t) < 2 or any(t1 <= t0 for t0, t1 in zip(t, t[1:])):
        sys.exit(f"{path}: needs at least two rows with increasing times")
    return t, a, l


def linear(points):
    f = osim.PiecewiseLinearFunction()
    for x, y in points:
        f.addPoint(x, y)
    return f


def move(f, points):
    """Give the PiecewiseLinearFunction f these points (as many as it has), moving forward in
    time: the last point first, so that its times stay increasing."""
    for i in reversed(range(len(points))):
        f.setX(i, points[i][0])
        f.setY(i, points[i][1])


def control(t, a, k, act_model):
    """The control from row k to row k + 1: the activation itself (DeGrooteFregly2016Muscle), or
    Thelen's exact inverse u = a + tau(a) da/dt sampled THELEN_SUB + 1 times (Thelen2003Muscle,
    checked against its activation model)."""
    if act_model is None:
        return [(t[k], a[k]), (t[k + 1], a[k + 1])]
    dt, da = t[k + 1] - t[k], a[k + 1] - a[k]
    s, points = da / dt, []
    for j in range(THELEN_SUB + 1):
        aj = a[k] + da * j / THELEN_SUB
        tau = THELEN_TAU * (0.5 + 1.5 * aj) if s > 0 else THELEN_TAU / (0.5 + 1.5 * aj)
        u = aj + tau * s
        if abs(act_model.calcDerivative(aj, u) - s) > 1e-9 * max(1.0, abs(s)):
            sys.exit("the Thelen control does not invert OpenSim's activation model")
        points.append((t[k] + dt * j / THELEN_SUB if j < THELEN_SUB else t[k + 1], u))
    return points


def build(args, t, a, l, rigid_eval):
    """The model, its muscle, slider coordinate, control function (or None) and state; the
    slider prescribed (elastic tendon) or free, set row by row (rigid_eval)."""
    model = osim.Model()
    model.setGravity(osim.Vec3(0))
    body = osim.Body("slider_body", 1.0, osim.Vec3(0), osim.Inertia(1))
    model.addBody(body)
    joint = osim.SliderJoint("slider", model.getGround(), body)
    model.addJoint(joint)
    thelen = args.muscle == "thelen2003"
    if thelen:
        mu = osim.Thelen2003Muscle("muscle", args.fmax, args.lopt, args.lts, args.pennation)
        mu.set_activation_time_constant(THELEN_TAU)
        mu.set_deactivation_time_constant(THELEN_TAU)
        mu.setDefaultActivation(a[0])
        if args.tendon_strain is not None:
            mu.set_FmaxTendonStrain(args.tendon_strain)
        if args.passive_strain is not None:
            mu.set_FmaxMuscleStrain(args.passive_strain)
        for value, setter in ((args.kshape_active, mu.set_KshapeActive),
                              (args.kshape_passive, mu.set_KshapePassive),
                              (args.af, mu.set_Af), (args.flen, mu.set_Flen)):
            if value is not None:
                setter(value)
    elif args.muscle == "millard2012":
        mu = osim.Millard2012EquilibriumMuscle("muscle", args.fmax, args.lopt, args.lts,
                                               args.pennation)
        mu.set_fiber_damping(args.damping)
        # Its activation floor (minimum_activation, 0.01) is needed only by an undamped elastic
        # fibre; the engine's activation reaches 0 elsewhere. The floor reaches the activation
        # model (which clamps the control also when activation dynamics are ignored) only while
        # they are not ignored, hence the order.
        if args.damping > 0.0 or args.tendon == "rigid":
            mu.set_minimum_activation(0.0)
            mu.finalizeFromProperties()
        mu.set_ignore_activation_dynamics(True)
        mu.set_ignore_tendon_compliance(args.tendon == "rigid")
        if args.tendon_strain is not None:
            mu.upd_TendonForceLengthCurve().set_strain_at_one_norm_force(args.tendon_strain)
        if args.passive_strain is not None:
            mu.upd_FiberForceLengthCurve().set_strain_at_one_norm_force(args.passive_strain)
    else:
        mu = osim.DeGrooteFregly2016Muscle()
        mu.setName("muscle")
        mu.setMaxIsometricForce(args.fmax)
        mu.setOptimalFiberLength(args.lopt)
        mu.setTendonSlackLength(args.lts)
        mu.setPennationAngleAtOptimalFiberLength(args.pennation)
        mu.set_ignore_activation_dynamics(True)
        mu.set_ignore_tendon_compliance(args.tendon == "rigid")
        mu.set_tendon_compliance_dynamics_mode("explicit")
        mu.set_fiber_damping(args.damping)
        if args.tendon_strain is not None:
            mu.set_tendon_strain_at_one_norm_force(args.tendon_strain)
        if args.passive_strain is not None:
            mu.set_passive_fiber_strain_at_one_norm_force(args.passive_strain)
        if args.active_force_width_scale is not None:
            mu.set_active_force_width_scale(args.active_force_width_scale)
    mu.setMaxContractionVelocity(args.vmax / args.lopt)
    mu.addNewPathPoint("origin", model.getGround(), osim.Vec3(0))
    mu.addNewPathPoint("insertion", body, osim.Vec3(0))
    model.addForce(mu)
    coord = joint.updCoordinate()
    coord.setDefaultValue(l[0])
    if not rigid_eval:
        coord.setPrescribedFunction(linear(zip(t[:2], l[:2])))
        coord.setDefaultIsPrescribed(True)
    if not (thelen and rigid_eval):
        mu.finalizeFromProperties()
        controller = osim.PrescribedController()
        controller.setName("activation")
        controller.addActuator(mu)
        points = control(t, a, 0, mu.getActivationModel() if thelen else None)
        controller.prescribeControlForActuator("muscle", linear(points))
        model.addController(controller)
    state = model.initSystem()
    muscle = model.getMuscles().get("muscle")
    cast = {"thelen2003": osim.Thelen2003Muscle, "degroote2016": osim.DeGrooteFregly2016Muscle,
            "millard2012": osim.Millard2012EquilibriumMuscle}[args.muscle]
    muscle = cast.safeDownCast(muscle)
    fn = None
    if not (thelen and rigid_eval):
        controller = osim.PrescribedController.safeDownCast(
            model.updControllerSet().get("activation"))
        fn = osim.PiecewiseLinearFunction.safeDownCast(controller.upd_ControlFunctions().get(0))
    return model, muscle, model.updCoordinateSet().get("slider_coord_0"), fn, state


def sample(model, mu, s):
    model.realizeDynamics(s)
    return (s.getTime(), mu.getActivation(s), mu.getLength(s), mu.getTendonForce(s),
            mu.getFiberLength(s), mu.getFiberVelocity(s), mu.getPennationAngle(s))


def simulate(args, t, a, l):
    """Elastic tendon: equilibrate at the first row, then the Manager from row to row."""
    model, mu, coord, fn, state = build(args, t, a, l, rigid_eval=False)
    act = mu.getActivationModel() if args.muscle == "thelen2003" else None
    line = osim.PiecewiseLinearFunction.safeDownCast(coord.upd_prescribed_function())
    manager = osim.Manager(model)
    manager.setWriteToStorage(False)
    manager.setPerformAnalyses(False)
    manager.setRecordStatesTrajectory(False)
    manager.setIntegratorAccuracy(args.accuracy)
    manager.setIntegratorMinimumStepSize(1e-14)
    rows = []
    for k in range(len(t) - 1):
        # Path and control are this interval's own functions (a line through its two rows; the
        # control's samples), so both are unambiguous at the interval's ends.
        move(line, [(t[k], l[k]), (t[k + 1], l[k + 1])])
        move(fn, control(t, a, k, act))
        state.setTime(t[k])
        coord.setValue(state, l[k], False)
        coord.setSpeedValue(state, (l[k + 1] - l[k]) / (t[k + 1] - t[k]))
        if k == 0:
            model.equilibrateMuscles(state)
            rows.append(sample(model, mu, state))
        manager.setIntegratorFinalTime(t[k + 1])
        manager.initialize(state)
        end = manager.integrate(t[k + 1])
        if end.getTime() != t[k + 1]:
            sys.exit(f"the integration stopped at t = {end.getTime()!r}, not at {t[k + 1]!r}")
        state = osim.State(end)
        rows.append(sample(model, mu, state))
    return rows


def evaluate_rigid(args, t, a, l):
    """Rigid tendon: no state; every row evaluated at its length, speed and activation."""
    model, mu, coord, fn, s = build(args, t, a, l, rigid_eval=True)
    rows = []
    for k, tk in enumerate(t):
        j = max(k - 1, 0)
        s.setTime(tk)
        coord.setValue(s, l[k])
        coord.setSpeedValue(s, (l[j + 1] - l[j]) / (t[j + 1] - t[j]))
        if args.muscle != "thelen2003":
            move(fn, control(t, a, j, None))
            rows.append(sample(model, mu, s))
            continue
        pm = mu.getPennationModel()
        mu.setActivation(s, a[k])
        mu.setFiberLength(s, pm.calcFiberLength(l[k], args.lts))
        model.realizeVelocity(s)
        cos = mu.getCosPennationAngle(s)
        force = (mu.calcInextensibleTendonActiveFiberForce(s, a[k])
                 + args.fmax * mu.getPassiveForceMultiplier(s) * cos)
        vm = pm.calcFiberVelocity(cos, mu.getLengtheningSpeed(s), 0.0)
        rows.append((tk, mu.getActivation(s), mu.getLength(s), force, mu.getFiberLength(s), vm,
                     mu.getPennationAngle(s)))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--inputs", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--muscle", required=True,
                    choices=["degroote2016", "thelen2003", "millard2012"])
    ap.add_argument("--tendon", required=True, choices=["elastic", "rigid"])
    ap.add_argument("--fmax", type=float, required=True, help="N")
    ap.add_argument("--lopt", type=float, required=True, help="m")
    ap.add_argument("--lts", type=float, required=True, help="m")
    ap.add_argument("--vmax", type=float, required=True, help="m/s")
    ap.add_argument("--pennation", type=float, default=0.0, help="rad, at optimal length")
    ap.add_argument("--tendon-strain", type=float)
    ap.add_argument("--passive-strain", type=float)
    ap.add_argument("--damping", type=float, default=0.0,
                    help="degroote2016 and millard2012 (fiber_damping)")
    ap.add_argument("--active-force-width-scale", type=float, help="degroote2016 only")
    ap.add_argument("--kshape-active", type=float, help="thelen2003 only (KshapeActive)")
    ap.add_argument("--kshape-passive", type=float, help="thelen2003 only (KshapePassive)")
    ap.add_argument("--af", type=float, help="thelen2003 only (Af)")
    ap.add_argument("--flen", type=float, help="thelen2003 only (Flen)")
    ap.add_argument("--accuracy", type=float, default=1e-12)
    ap.add_argument("--timeout", type=float, default=900.0, help="s of wall time")
    args = ap.parse_args()
    osim.Logger.setLevelString("warn")
    faulthandler.dump_traceback_later(args.timeout, exit=True)
    t, a, l = read_inputs(args.inputs)
    if args.muscle == "thelen2003":
        if args.damping:
            sys.exit("Thelen2003Muscle has no fibre damping")
        if not all(0.01 <= x <= 1.0 for x in a):
            sys.exit("Thelen2003Muscle needs 0.01 <= activation <= 1 (its minimum_activation)")
    start = time.time()
    run = simulate if args.tendon == "elastic" else evaluate_rigid
    rows = run(args, t, a, l)
    wall = time.time() - start
    da = max(abs(r[1] - x) for r, x in zip(rows, a))
    dl = max(abs(r[2] - x) for r, x in zip(rows, l))
    dt = max(abs(r[0] - x) for r, x in zip(rows, t))
    limit = 1e-8 if args.muscle == "thelen2003" and args.tendon == "elastic" else 1e-12
    if da > limit or dl > 1e-12 or dt != 0.0:
        sys.exit(f"read-back differs from the inputs: activation {da:g}, length {dl:g}, "
                 f"time {dt:g}")
    command = " ".join(shlex.quote(x) for x in sys.argv[1:])
    with open(args.out, "w") as f:
        f.write(f"# OpenSim {osim.GetVersionAndDate()} (PyPI opensim==4.6); written by "
                f"`.venv/bin/python scripts/opensim_muscle.py {command}`\n")
        f.write("t,activation,mtu_length,tendon_force,fiber_length,fiber_velocity,"
                "pennation_angle\n")
        for r in rows:
            f.write(",".join(repr(x) for x in r) + "\n")
    print(f"{len(rows)} rows -> {args.out}; {wall:.2f} s wall, read-back "
          f"|activation| <= {da:.3g}, |mtu_length| <= {dl:.3g}", file=sys.stderr)


if __name__ == "__main__":
    main()
