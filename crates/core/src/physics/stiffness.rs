//! Stiffness of the fibre, the muscle–tendon unit and the joint (docs/model.md §8).

/// Fibre stiffness `k_m = k_CE + dF_P/dl_m`, N/m.
pub(crate) fn fibre_stiffness(k_ce: f64, k_pe: f64) -> f64 {
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

/// Adds one muscle's share of the joint stiffness matrix (docs/model.md §8b, fibres quasi-static)
/// to `k` (row-major, `n × n`, N m/rad): `K_jk += k_mtu r_j r_k` over the joints it spans and
/// `K_jj -= F_SE dr_j/dθ_j`. `arms` yields (joint, r_j (m), dr_j/dθ_j (m/rad)) per spanned joint.
pub(crate) fn add_muscle_joint_stiffness<I>(
    k: &mut [f64],
    n: usize,
    k_mtu: f64,
    tendon_force: f64,
    arms: I,
) where
    I: Iterator<Item = (usize, f64, f64)> + Clone,
{
    for (j, r_j, dr_j) in arms.clone() {
        for (l, r_l, _) in arms.clone() {
            k[j * n + l] += k_mtu * (r_j * r_l);
        }
        k[j * n + j] -= tendon_force * dr_j;
    }
}
