#!/usr/bin/env python3
"""Fit the built-in `arm` configuration (crates/core/configs/arm.toml) from OpenSim's arm26 model.

arm26 is the reduced Holzbaur et al. (2005) upper-limb model shipped by OpenSim: two
revolute coordinates (r_shoulder_elev, r_elbow_flex) and six Thelen2003 muscles (TRIlong,
TRIlat, TRImed, BIClong, BICshort, BRA) whose paths wrap over ellipsoids and cylinders.
This script asks OpenSim itself for every moment arm (so the wrapping is exact), fits
each moment-arm curve with a low-degree polynomial in the joint angle, derives the joint
inertias from the bodies and scales the project's reference muscle (Jovanović et al.
2015, Table 1) to each arm26 muscle. It prints what it computes and writes the TOML.

Getting the inputs
------------------
* OpenSim, in a throwaway venv (never the project's .venv):

      python3 -m venv /tmp/osim-venv
      /tmp/osim-venv/bin/pip install opensim numpy      # opensim 4.6 from PyPI

  The PyPI wheel ships no example models.
* arm26.osim: `Models/Arm26/arm26.osim` in the public GitHub repository
  opensim-org/opensim-models (OpenSim 4.0 format; it also ships with the OpenSim GUI
  under Models/Arm26/). Geometry (.vtp) files are not needed; OpenSim only warns
  about missing meshes.

Running
-------
      /tmp/osim-venv/bin/python scripts/fit_arm26.py --osim /tmp/arm26.osim \
          --out crates/core/configs/arm.toml

Conventions
-----------
SI units. A moment arm r is positive when the muscle's tension increases the joint angle
(OpenSim's computeMomentArm convention), so the path length obeys dL/dθ = -r. Each curve
is sampled over the coordinate's full range with the other coordinate at 0 rad.

Pure standard library + numpy + opensim.
"""

import argparse
import math
import sys

import numpy as np
import opensim as osim

# --------------------------------------------------------------------------- settings

# OpenSim coordinate -> joint name in the project's configuration.
JOINTS = {"r_shoulder_elev": "shoulder", "r_elbow_flex": "elbow"}

# Bodies carried by each coordinate (distal to it), for the joint inertias.
DISTAL_BODIES = {
    "r_shoulder_elev": ["r_humerus", "r_ulna_radius_hand"],
    "r_elbow_flex": ["r_ulna_radius_hand"],
}

MUSCLES = ["TRIlong", "TRIlat", "TRImed", "BIClong", "BICshort", "BRA"]

SAMPLES = 1001         # points per moment-arm sweep
GLITCH_WINDOW = 7      # samples in the running median used to spot wrap-solver glitches
GLITCH_THRESHOLD = 2e-3  # m: a sample this far from the running median is a glitch
JUMP_THRESHOLD = 2e-3  # m: a step this large between neighbouring samples is a discontinuity
MAX_DEGREE = 4         # highest polynomial degree tried
FIT_TOLERANCE = 1e-3   # m: accept the lowest degree whose max fit error is below this
SPAN_THRESHOLD = 5e-4  # m: a moment arm below this over the whole range is "no span"
COUPLING_GRID = 25     # grid points per coordinate for the cross-coupling check

# Joint mechanics not in the .osim: the project's defaults, written out explicitly.
JOINT_DAMPING = 0.05          # N m s/rad
JOINT_LIMIT_STIFFNESS = 500.0  # N m/rad
JOINT_LIMIT_DAMPING = 5.0      # N m s/rad
INITIAL_ANGLE = 0.0            # rad, every joint

# Reference muscle of Jovanović et al. 2015, Table 1 (the project's defaults).
F0, L0, LTS0 = 3913.0, 0.0959, 0.3185

DEFAULT_SOURCE = (
    "github.com/opensim-org/opensim-models, Models/Arm26/arm26.osim "
    "(commit 84b487c4e3245359a64381e01f01b9cf4772d457)"
)


# --------------------------------------------------------------------------- OpenSim

def set_pose(model, state, pose):
    """Sets every coordinate in `pose` (name -> rad) and realizes positions."""
    coords = model.getCoordinateSet()
    for name, value in pose.items():
        coords.get(name).setValue(state, value, False)
    model.assemble(state)
    model.realizePosition(state)


def zero_pose():
    return {c: 0.0 for c in JOINTS}


def moment_arm(model, state, muscle, coord_name, pose):
    set_pose(model, state, pose)
    coord = model.getCoordinateSet().get(coord_name)
    return muscle.computeMomentArm(state, coord)


def sweep(model, state, muscle, coord_name, angles):
    """Moment arm of `muscle` about `coord_name` over `angles`, other coordinates at 0."""
    out = np.empty(len(angles))
    for i, q in enumerate(angles):
        pose = zero_pose()
        pose[coord_name] = float(q)
        out[i] = moment_arm(model, state, muscle, coord_name, pose)
    return out


def vec3(v):
    return np.array([v.get(i) for i in range(3)])


def mat33(m):
    return np.array([[m.get(i, j) for j in range(3)] for i in range(3)])


def joint_of(model, coord_name):
    return model.getCoordinateSet().get(coord_name).getJoint()


def axis_in_ground(model, state, coord_name):
    """Rotation axis of a CustomJoint coordinate in ground, and a point on it."""
    joint = joint_of(model, coord_name)
    custom = osim.CustomJoint.safeDownCast(joint)
    transform = custom.getSpatialTransform()
    axis = None
    for i in range(3):  # the three rotation TransformAxes
        ta = transform.getTransformAxis(i)
        arr = ta.getCoordinateNamesInArray()
        names = [arr.get(k) for k in range(arr.getSize())]
        if coord_name in names:
            axis = vec3(ta.getAxis())
    if axis is None:
        raise RuntimeError(f"{coord_name}: no rotation axis found in {joint.getName()}")
    # SpatialTransform axes are expressed in the joint's parent frame.
    r_parent = mat33(joint.getParentFrame().getTransformInGround(state).R().asMat33())
    n = r_parent @ axis
    n /= np.linalg.norm(n)
    point = vec3(joint.getChildFrame().getPositionInGround(state))
    return n, point


def inertia_about_axis(model, state, body_names, n, point):
    """Moment of inertia of the listed bodies about the line (point, n), in the current pose."""
    total = 0.0
    for name in body_names:
        body = model.getBodySet().get(name)
        m = body.getMass()
        com = vec3(body.findStationLocationInGround(state, body.getMassCenter()))
        i6 = body.get_inertia()  # [Ixx Iyy Izz Ixy Ixz Iyz] about the mass centre, body frame
        i_c = np.array([[i6.get(0), i6.get(3), i6.get(4)],
                        [i6.get(3), i6.get(1), i6.get(5)],
                        [i6.get(4), i6.get(5), i6.get(2)]])
        r = mat33(body.getTransformInGround(state).R().asMat33())
        i_ground = r @ i_c @ r.T
        d = com - point
        total += n @ i_ground @ n + m * (d @ d - (d @ n) ** 2)  # parallel-axis theorem
    return total


# --------------------------------------------------------------------------- cleaning

def drop_glitches(q, r):
    """Removes isolated samples where OpenSim's wrapping solver briefly fails.

    arm26's shoulder wrap objects produce narrow spikes (a few samples wide, e.g. the
    BIClong path length jumps by ~87 mm for ~0.003 rad near 0.51 rad). A sample further
    than GLITCH_THRESHOLD from the running median of GLITCH_WINDOW samples is dropped; a
    genuine step (wrap engaging) survives a running median and is kept."""
    h = GLITCH_WINDOW // 2
    padded = np.concatenate([np.full(h, r[0]), r, np.full(h, r[-1])])
    med = np.array([np.median(padded[i:i + GLITCH_WINDOW]) for i in range(len(r))])
    keep = np.abs(r - med) <= GLITCH_THRESHOLD
    return q[keep], r[keep], q[~keep]


def discontinuities(q, r):
    """Steps larger than JUMP_THRESHOLD between neighbouring (cleaned) samples."""
    idx = np.where(np.abs(np.diff(r)) > JUMP_THRESHOLD)[0]
    return [(0.5 * (q[i] + q[i + 1]), r[i], r[i + 1]) for i in idx]


def glitch_ranges(dropped):
    """Groups dropped angles into short 'a..b' strings for printing."""
    if len(dropped) == 0:
        return ""
    groups, start, prev = [], dropped[0], dropped[0]
    for a in dropped[1:]:
        if a - prev > 0.05:
            groups.append((start, prev))
            start = a
        prev = a
    groups.append((start, prev))
    return ", ".join(f"{a:+.3f}" if a == b else f"{a:+.3f}..{b:+.3f}" for a, b in groups)


# --------------------------------------------------------------------------- fitting

def changes_sign(values):
    return bool(np.any(values > 0) and np.any(values < 0))


def fit_curve(angles, r):
    """Lowest-degree polynomial (≤ MAX_DEGREE) with max error < FIT_TOLERANCE, else MAX_DEGREE.

    When the OpenSim curve keeps one sign, a fit that changes sign inside the range is
    rejected in favour of the next degree. Returns (coefficients c0.., max error, warning)."""
    fine = np.linspace(angles[0], angles[-1], 2001)
    one_signed = not changes_sign(r)
    best = None
    for degree in range(MAX_DEGREE + 1):
        c = np.polynomial.polynomial.polyfit(angles, r, degree)
        err = float(np.max(np.abs(np.polynomial.polynomial.polyval(angles, c) - r)))
        flips = one_signed and changes_sign(np.polynomial.polynomial.polyval(fine, c))
        best = (c, err, flips)
        if err < FIT_TOLERANCE and not flips:
            break
    c, err, flips = best
    warning = "fitted polynomial changes sign inside the range" if flips else ""
    if err >= FIT_TOLERANCE:
        warning = (warning + "; " if warning else "") + f"max error {err * 1e3:.2f} mm ≥ tolerance"
    return c, err, warning


# --------------------------------------------------------------------------- scaling

def scaled_parameters(f, l, lt):
    """Jovanović et al. 2015 Table 1 reference muscle scaled to F = f, l = l_opt, lt = l_ts."""
    fr, lr, tr = f / F0, L0 / l, LTS0 / lt
    return {
        "mass": 0.95 * fr * (l / L0),
        "v_max": 0.5179 * l / L0,
        "k_te": 3022.0 * tr,
        "k_tl": 31140.0 * fr * tr,
        "k_t": 635540.0 * fr * tr,
        "f_tc": 200.0 * fr,
        "k_me": 90.4 * lr,
        "k_ml": 487.5 * fr * lr,
        "k_m": 6770.0 * fr * lr,
        "l_ms": l * (0.0959 / L0),
        "l_mc": 0.125 * l / L0,
        "f_mc": 69.4723 * fr,
        "b_m": 257.1 * fr * lr,
    }


# --------------------------------------------------------------------------- output

def g6(x):
    """6 significant digits, TOML-safe (always a float literal)."""
    s = f"{x:.6g}"
    if "e" in s:
        mant, exp = s.split("e")
        if "." not in mant:
            mant += ".0"
        return f"{mant}e{int(exp)}"
    return s if "." in s else s + ".0"


def toml_moment_arm(c):
    if len(c) == 1:
        return g6(c[0])
    return "[" + ", ".join(g6(v) for v in c) + "]"


def write_toml(path, source, joints, muscles, coupling):
    lines = [
        "# Built-in configuration `arm`: OpenSim's arm26 model (reduced Holzbaur et al. 2005",
        "# upper-limb model: shoulder elevation and elbow flexion, six muscles).",
        f"# Source: OpenSim arm26.osim, {source}.",
        "# Holzbaur, K.R.S., Murray, W.M., Delp, S.L. (2005) A model of the upper extremity for",
        "# simulating musculoskeletal surgery and analyzing neuromuscular control.",
        "# Ann. Biomed. Eng. 33, 829-840.",
        "#",
        "# GENERATED by scripts/fit_arm26.py (OpenSim " + osim.__version__ + "); do not edit by hand.",
        "# Rules:",
        "# - Joints r_shoulder_elev -> shoulder, r_elbow_flex -> elbow; ranges from the .osim.",
        "#   Each joint is an independent rotational inertia about its axis (no inertial",
        "#   coupling): shoulder = humerus + forearm/hand about the shoulder axis with the",
        "#   elbow at 0 rad, elbow = forearm/hand about the elbow axis (parallel-axis theorem).",
        "# - moment_arm: polynomial r(θ) = c0 + c1 θ + ... (m, m/rad, ...) fitted to OpenSim's",
        "#   computeMomentArm over the coordinate's range with the other coordinate at 0 rad;",
        f"#   lowest degree ≤ {MAX_DEGREE} with max error < {FIT_TOLERANCE * 1e3:g} mm. Positive when",
        "#   tension increases the joint angle; dL/dθ = -r. Spans below"
        f" {SPAN_THRESHOLD * 1e3:g} mm are omitted.",
        "#   Cross-coupling checked on a grid over both ranges: the largest change of a",
        "#   biarticular muscle's shoulder (elbow) moment arm over the elbow (shoulder) range",
        f"#   is zero to rounding ({max(v[0] for v in coupling.values()) * 1e3:.1g} mm;"
        f" elbow {max(v[1] for v in coupling.values()) * 1e3:.1g} mm): every path segment",
        "#   that crosses one joint ends on the humerus, so per-joint curves lose nothing.",
        "#   Each span's comment gives its fit error. The shoulder curves span 4.7 rad, change",
        "#   sign and (TRIlong, BIClong) jump where wrap objects engage: a quartic misses them",
        "#   by several mm at worst (see the comments).",
        "# - path_length: OpenSim MTU length with both coordinates at 0 rad.",
        "# - f_max, l_opt, l_ts from the .osim (max_isometric_force, optimal_fiber_length,",
        "#   tendon_slack_length); pennation is ignored. Every other muscle parameter is",
        "#   Jovanović et al. 2015 Table 1 (F0 = 3913 N, l0 = 0.0959 m, lts0 = 0.3185 m) scaled",
        "#   to the muscle: mass ∝ F l, v_max ∝ l, k_me ∝ 1/l, k_ml, k_m, b_m ∝ F/l, f_mc ∝ F,",
        "#   k_te ∝ 1/lt, k_tl, k_t ∝ F/lt, f_tc ∝ F. l_tc, t_act, t_deact, fl_width: defaults.",
        "",
    ]
    for j in joints:
        lines += [
            "[[joint]]",
            f'name = "{j["name"]}"',
            f"inertia = {g6(j['inertia'])}",
            f"damping = {g6(JOINT_DAMPING)}",
            f"min_angle = {g6(j['min'])}",
            f"max_angle = {g6(j['max'])}",
            f"limit_stiffness = {g6(JOINT_LIMIT_STIFFNESS)}",
            f"limit_damping = {g6(JOINT_LIMIT_DAMPING)}",
            f"initial_angle = {g6(INITIAL_ANGLE)}",
            "",
        ]
    keys = ["mass", "v_max", "l_ms", "l_mc", "k_me", "k_ml", "k_m", "f_mc", "b_m",
            "k_te", "k_tl", "k_t", "f_tc"]
    for m in muscles:
        lines += [
            "[[muscle]]",
            f'name = "{m["name"]}"',
            f"f_max = {g6(m['f_max'])}",
            f"l_opt = {g6(m['l_opt'])}",
            f"l_ts = {g6(m['l_ts'])}",
        ]
        lines += [f"{k} = {g6(m['scaled'][k])}" for k in keys]
        lines.append(f"path_length = {g6(m['path_length'])}")
        for sp in m["spans"]:
            note = (f"# degree {len(sp['coef']) - 1}, max fit error {sp['err'] * 1e3:.2f} mm, "
                    f"rms {sp['rms'] * 1e3:.2f} mm")
            if sp["jumps"]:
                note += "; OpenSim curve jumps at θ ≈ " + ", ".join(
                    f"{at:+.2f}" for at, _, _ in sp["jumps"]) + " rad"
            if sp["glitches"]:
                note += f"; {sp['glitches']} wrap-solver glitch sample(s) dropped"
            lines += ["[[muscle.span]]", f'joint = "{sp["joint"]}"', note,
                      f"moment_arm = {toml_moment_arm(sp['coef'])}"]
            if sp["changes_sign"]:
                # The muscle's line of action crosses the joint's axis inside the range: the
                # project refuses such an arm unless the configuration says so.
                lines.append("changes_sign = true")
        lines.append("")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


# --------------------------------------------------------------------------- main

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--osim", required=True, help="path to arm26.osim")
    ap.add_argument("--out", required=True, help="TOML to write, e.g. crates/core/configs/arm.toml")
    ap.add_argument("--source", default=DEFAULT_SOURCE,
                    help="where the .osim came from (written into the TOML header)")
    args = ap.parse_args()

    osim.Logger.setLevelString("warn")
    model = osim.Model(args.osim)
    state = model.initSystem()
    coords = model.getCoordinateSet()

    # ---- joints: ranges and inertias in the zero pose
    set_pose(model, state, zero_pose())
    joints, ranges = [], {}
    print("Joints (zero pose)")
    for cname, jname in JOINTS.items():
        c = coords.get(cname)
        lo, hi = c.getRangeMin(), c.getRangeMax()
        ranges[cname] = (lo, hi)
        n, p = axis_in_ground(model, state, cname)
        inertia = inertia_about_axis(model, state, DISTAL_BODIES[cname], n, p)
        joints.append({"name": jname, "inertia": inertia, "min": lo, "max": hi})
        print(f"  {jname:8s} ({cname}): range [{lo:.6g}, {hi:.6g}] rad, axis {np.round(n, 5)}, "
              f"inertia {inertia:.6g} kg m² (bodies {', '.join(DISTAL_BODIES[cname])})")

    # ---- muscles: moment-arm sweeps, fits, path length, scaled parameters
    muscles, fit_rows, warnings = [], [], []
    biarticular = []
    for mname in MUSCLES:
        mus = model.getMuscles().get(mname)
        set_pose(model, state, zero_pose())
        path_length = mus.getLength(state)
        for cname in JOINTS:  # guard against a wrapping glitch exactly at the zero pose
            near = []
            for dq in (-1e-3, 1e-3):
                pose = zero_pose()
                pose[cname] = dq
                set_pose(model, state, pose)
                near.append(mus.getLength(state))
            if abs(path_length - 0.5 * sum(near)) > 5e-4:
                warnings.append(f"{mname}: path length at the zero pose {path_length:.6f} m "
                                f"differs from its neighbours along {cname} {near}")
        f, l, lt = (mus.getMaxIsometricForce(), mus.getOptimalFiberLength(),
                    mus.getTendonSlackLength())
        spans = []
        for cname, jname in JOINTS.items():
            lo, hi = ranges[cname]
            q_all = np.linspace(lo, hi, SAMPLES)
            q, r, dropped = drop_glitches(q_all, sweep(model, state, mus, cname, q_all))
            if len(dropped):
                warnings.append(f"{mname}/{jname}: dropped {len(dropped)} glitch sample(s) "
                                f"of the wrapping solver at θ = {glitch_ranges(dropped)} rad")
            peak = float(np.max(np.abs(r)))
            if peak < SPAN_THRESHOLD:
                fit_rows.append((mname, jname, q, r, None, None, ""))
                continue
            c, err, warn = fit_curve(q, r)
            if warn:
                warnings.append(f"{mname}/{jname}: {warn}")
            if changes_sign(r):
                warnings.append(f"{mname}/{jname}: OpenSim moment arm itself changes sign "
                                f"({r.min() * 1e3:+.2f} .. {r.max() * 1e3:+.2f} mm)")
            jumps = discontinuities(q, r)
            for at, before, after in jumps:
                warnings.append(f"{mname}/{jname}: OpenSim moment arm jumps at θ ≈ {at:+.3f} rad "
                                f"({before * 1e3:+.2f} -> {after * 1e3:+.2f} mm)")
            rms = math.sqrt(float(np.mean((np.polynomial.polynomial.polyval(q, c) - r) ** 2)))
            spans.append({"joint": jname, "coef": c, "err": err, "rms": rms, "jumps": jumps,
                          "glitches": len(dropped), "changes_sign": changes_sign(r)})
            fit_rows.append((mname, jname, q, r, c, err, warn))
        if len(spans) == len(JOINTS):
            biarticular.append(mname)
        muscles.append({"name": mname, "f_max": f, "l_opt": l, "l_ts": lt,
                        "path_length": path_length, "scaled": scaled_parameters(f, l, lt),
                        "spans": spans})

    print("\nMoment-arm fits (r in mm over the range, other coordinate at 0 rad)")
    print(f"  {'muscle':9s} {'joint':8s} {'r min':>8s} {'r max':>8s} {'deg':>3s} "
          f"{'max err':>8s} {'rms err':>8s}  coefficients c0.. (m, m/rad, ...)")
    for mname, jname, q, r, c, err, warn in fit_rows:
        if c is None:
            print(f"  {mname:9s} {jname:8s} {r.min() * 1e3:8.3f} {r.max() * 1e3:8.3f}   -"
                  f"        -        -  no span (|r| < {SPAN_THRESHOLD * 1e3:g} mm)")
            continue
        rms = math.sqrt(float(np.mean((np.polynomial.polynomial.polyval(q, c) - r) ** 2)))
        print(f"  {mname:9s} {jname:8s} {r.min() * 1e3:8.3f} {r.max() * 1e3:8.3f} {len(c) - 1:3d} "
              f"{err * 1e3:8.3f} {rms * 1e3:8.3f}  [{', '.join(f'{v:.6g}' for v in c)}]"
              + (f"  ! {warn}" if warn else ""))

    # ---- fibre length at the initial pose (pennation ignored)
    print("\nFibre length at initial_angle with no activation: (path_length - l_ts) / l_opt")
    for m in muscles:
        ratio = (m["path_length"] - m["l_ts"]) / m["l_opt"]
        flag = "" if 0.5 <= ratio <= 1.5 else "  ! outside 0.5-1.5"
        print(f"  {m['name']:9s} path {m['path_length']:.6f} m, l_ts {m['l_ts']:.4f} m, "
              f"l_opt {m['l_opt']:.4f} m -> {ratio:.3f}{flag}")

    # ---- coupling of biarticular muscles: how much each moment arm depends on the other angle
    coupling = {}
    print(f"\nCoupling of biarticular muscles ({COUPLING_GRID}x{COUPLING_GRID} grid over both ranges)")
    (s_name, e_name) = list(JOINTS)
    qs = np.linspace(*ranges[s_name], COUPLING_GRID)
    qe = np.linspace(*ranges[e_name], COUPLING_GRID)
    for mname in biarticular:
        mus = model.getMuscles().get(mname)
        rs = np.empty((len(qs), len(qe)))
        re = np.empty((len(qs), len(qe)))
        for i, a in enumerate(qs):
            for j, b in enumerate(qe):
                pose = {s_name: float(a), e_name: float(b)}
                rs[i, j] = moment_arm(model, state, mus, s_name, pose)
                re[i, j] = moment_arm(model, state, mus, e_name, pose)
        ds = rs.max(axis=1) - rs.min(axis=1)   # per shoulder angle, change over the elbow sweep
        de = re.max(axis=0) - re.min(axis=0)   # per elbow angle, change over the shoulder sweep
        coupling[mname] = (float(ds.max()), float(de.max()))
        i0 = int(np.argmin(np.abs(qs)))
        i_max = int(np.argmax(ds))
        print(f"  {mname:9s} shoulder r vs elbow sweep: max change {ds.max() * 1e3:.4f} mm "
              f"(at shoulder {qs[i_max]:+.3f} rad: {rs[i_max].min() * 1e3:+.2f} .. "
              f"{rs[i_max].max() * 1e3:+.2f} mm), at shoulder 0: {ds[i0] * 1e3:.2f} mm "
              f"({rs[i0].min() * 1e3:+.2f} .. {rs[i0].max() * 1e3:+.2f} mm)")
        print(f"  {'':9s} elbow r vs shoulder sweep: max change {de.max() * 1e3:.4f} mm")

    if warnings:
        print("\nWarnings")
        for w in warnings:
            print("  " + w)

    write_toml(args.out, args.source, joints, muscles, coupling)
    print(f"\nwrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
