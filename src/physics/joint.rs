//! The revolute joint of the antagonistic actuator (MODEL.md §8).

use crate::physics::params::JointParams;

/// Path length of the agonist, `L0 - r θ`, m (flexion shortens it).
pub fn agonist_path(l0: f64, radius: f64, theta: f64) -> f64 {
    l0 - radius * theta
}

/// Path length of the antagonist, `L0 + r θ`, m.
pub fn antagonist_path(l0: f64, radius: f64, theta: f64) -> f64 {
    l0 + radius * theta
}

/// End-stop torque: a stiff, damped spring beyond the range limits that only ever pushes back
/// into the range, N m.
pub fn limit_torque(p: &JointParams, theta: f64, omega: f64) -> f64 {
    if theta > p.max_angle {
        (-p.limit_stiffness * (theta - p.max_angle) - p.limit_damping * omega).min(0.0)
    } else if theta < p.min_angle {
        (-p.limit_stiffness * (theta - p.min_angle) - p.limit_damping * omega).max(0.0)
    } else {
        0.0
    }
}

/// Angular acceleration `dω/dt = (r (F_ago - F_ant) - c ω + τ_ext + τ_limit) / I`, rad/s².
pub fn angular_acceleration(
    p: &JointParams,
    theta: f64,
    omega: f64,
    f_agonist: f64,
    f_antagonist: f64,
    external_torque: f64,
) -> f64 {
    let muscle = p.radius * (f_agonist - f_antagonist);
    (muscle - p.damping * omega + external_torque + limit_torque(p, theta, omega)) / p.inertia
}

/// Rotational kinetic energy `½ I ω²`, J.
pub fn kinetic_energy(p: &JointParams, omega: f64) -> f64 {
    0.5 * p.inertia * omega * omega
}
