//! A revolute joint (docs/model.md §8, §8b): an independent rotational inertia with viscous
//! damping and stiff, damped end stops, driven by the muscles that span it.

use crate::physics::limb_params::JointParams;

/// End-stop torque: a stiff, damped spring beyond the range limits that only ever pushes back
/// into the range, N m.
pub(crate) fn limit_torque(p: &JointParams, theta: f64, omega: f64) -> f64 {
    if theta > p.max_angle {
        (-p.limit_stiffness * (theta - p.max_angle) - p.limit_damping * omega).min(0.0)
    } else if theta < p.min_angle {
        (-p.limit_stiffness * (theta - p.min_angle) - p.limit_damping * omega).max(0.0)
    } else {
        0.0
    }
}

/// The end-stop torque's slopes `(∂τ_limit/∂θ, ∂τ_limit/∂ω)` (N m/rad, N m s/rad): the spring and
/// damper while they push back, zero inside the range or while the stop lets go.
pub(crate) fn limit_torque_slopes(p: &JointParams, theta: f64, omega: f64) -> (f64, f64) {
    let engaged = if theta > p.max_angle {
        -p.limit_stiffness * (theta - p.max_angle) - p.limit_damping * omega < 0.0
    } else if theta < p.min_angle {
        -p.limit_stiffness * (theta - p.min_angle) - p.limit_damping * omega > 0.0
    } else {
        false
    };
    if engaged {
        (-p.limit_stiffness, -p.limit_damping)
    } else {
        (0.0, 0.0)
    }
}

/// Angular acceleration `dω/dt = (τ_muscles - c ω + τ_ext + τ_limit) / I`, rad/s², where
/// `τ_muscles = Σ_i r_i(θ) F_SE,i` is the muscles' net torque, N m.
pub(crate) fn angular_acceleration(
    p: &JointParams,
    theta: f64,
    omega: f64,
    muscle_torque: f64,
    external_torque: f64,
) -> f64 {
    (muscle_torque - p.damping * omega + external_torque + limit_torque(p, theta, omega))
        / p.inertia
}

/// Angular acceleration of a driven joint within a tick, rad/s²: zero, so that the prescribed
/// motion is `θ(t) = θ0 + ω0 (t - t0)`, `ω(t) = ω0` from the values set at the tick's start
/// (docs/model.md §8c).
pub(crate) fn driven_angular_acceleration() -> f64 {
    0.0
}

/// A driven joint's angle `θ0 + ω0 t` at time t after the tick's start, from the angle θ0 and
/// velocity ω0 set at the start (linear extrapolation), rad.
pub(crate) fn prescribed_angle(theta0: f64, omega0: f64, t: f64) -> f64 {
    theta0 + omega0 * t
}

/// Rotational kinetic energy `½ I ω²`, J.
pub(crate) fn kinetic_energy(p: &JointParams, omega: f64) -> f64 {
    0.5 * p.inertia * omega * omega
}
