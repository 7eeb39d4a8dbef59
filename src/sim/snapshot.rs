//! Plain data published after every tick: what the node, the recorder and the CSV writer read.

/// State of one muscle–tendon unit after a tick (the fields of `MuscleState.msg`, SI units).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MuscleSnapshot {
    /// Neural excitation u in force during the tick, [0, 1].
    pub excitation: f64,
    /// Activation a.
    pub activation: f64,
    /// Tendon force F_SE, N.
    pub force: f64,
    /// Contractile-element force F_CE, N.
    pub ce_force: f64,
    /// Parallel-element force F_P (spring only), N.
    pub pe_force: f64,
    /// Fibre length l_m, m.
    pub fiber_length: f64,
    /// Fibre lengthening velocity dl_m/dt, m/s.
    pub fiber_velocity: f64,
    /// Tendon length l_t, m.
    pub tendon_length: f64,
    /// Contractile-element stiffness k_CE, N/m.
    pub stiffness: f64,
    /// Muscle–tendon-unit stiffness (fibre and tendon in series), N/m.
    pub mtu_stiffness: f64,
    /// Distribution-Moment state Q0 (0 for the Hill model).
    pub q0: f64,
    /// Distribution-Moment state Q1.
    pub q1: f64,
    /// Distribution-Moment state Q2.
    pub q2: f64,
    /// Tendon strain energy, J.
    pub tendon_energy: f64,
    /// Parallel-element strain energy, J.
    pub fiber_energy: f64,
    /// Cross-bridge elastic energy, J.
    pub crossbridge_energy: f64,
}

/// State of the joint after a tick.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JointSnapshot {
    /// Angle θ, rad (positive: flexion, the agonist's direction).
    pub position: f64,
    /// Angular velocity ω, rad/s.
    pub velocity: f64,
    /// Net muscle torque r (F_ago - F_ant), N m.
    pub torque: f64,
    /// External load torque in force during the tick, N m.
    pub external_torque: f64,
    /// Joint stiffness K = r² (k_mtu,ago + k_mtu,ant), N m/rad.
    pub stiffness: f64,
}
