//! Activation dynamics (docs/model.md §2): excitation u drives activation a.

/// The time constant in force: `t_act` while activating (u > a), `t_deact` otherwise, s.
pub(crate) fn time_constant(u: f64, a: f64, t_act: f64, t_deact: f64) -> f64 {
    if u > a {
        t_act
    } else {
        t_deact
    }
}

/// `da/dt = (u - a) / tau` (docs/model.md §2), 1/s.
pub fn activation_rate(u: f64, a: f64, t_act: f64, t_deact: f64) -> f64 {
    (u - a) / time_constant(u, a, t_act, t_deact)
}

/// Exact activation after `dt` seconds with u held constant: a moves monotonically towards u, so
/// the time constant chosen at the start holds throughout and
/// `a(dt) = u + (a0 - u) exp(-dt / tau)`.
pub(crate) fn activation_after(a0: f64, u: f64, dt: f64, t_act: f64, t_deact: f64) -> f64 {
    let tau = time_constant(u, a0, t_act, t_deact);
    u + (a0 - u) * (-dt / tau).exp()
}
