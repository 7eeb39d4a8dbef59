//! Stiffness of the fibre, the muscle–tendon unit and the joint (MODEL.md §8).

/// Fibre stiffness `k_m = k_CE + dF_P/dl_m`, N/m.
pub fn fibre_stiffness(k_ce: f64, k_pe: f64) -> f64 {
    k_ce + k_pe
}

/// Series combination `k_m k_SE / (k_m + k_SE)` (0 if both are 0), N/m.
pub fn series_stiffness(k_m: f64, k_se: f64) -> f64 {
    let sum = k_m + k_se;
    if sum > 0.0 {
        k_m * k_se / sum
    } else {
        0.0
    }
}

/// Joint stiffness `K = r² (k_mtu,ago + k_mtu,ant)`, N m/rad.
pub fn joint_stiffness(radius: f64, k_mtu_agonist: f64, k_mtu_antagonist: f64) -> f64 {
    radius * radius * (k_mtu_agonist + k_mtu_antagonist)
}
