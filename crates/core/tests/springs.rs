//! The exponential-then-linear springs (docs/model.md §4): continuity, inverses and strain energies,
//! checked against independent computations (finite differences, quadrature).

use muscle_actuator_core::physics::{parallel_spring, tendon, ExpLinearSpring, MuscleParams};

fn springs() -> [(&'static str, ExpLinearSpring); 2] {
    let p = MuscleParams::default();
    [("tendon", tendon(&p)), ("parallel", parallel_spring(&p))]
}

#[test]
fn derived_tendon_transition_length_matches_model_md() {
    let p = MuscleParams::default();
    assert!(
        (p.derived_l_tc() - 0.3194980).abs() < 5e-8,
        "l_tc = {}",
        p.derived_l_tc()
    );
    // With it, the slope at l_tc equals k_t exactly: k_tl + k_te F_tc = 635540 N/m.
    let t = tendon(&p);
    let slope_exp = t.k_l * (t.k_e * (t.l_c - t.l_s)).exp();
    assert!(
        (slope_exp - p.k_t).abs() / p.k_t < 1e-12,
        "slope {slope_exp}"
    );
}

#[test]
fn force_is_continuous_at_slack_and_transition() {
    for (name, s) in springs() {
        assert_eq!(s.force(s.l_s - 1e-9), 0.0, "{name}");
        assert!(s.force(s.l_s + 1e-12) < 1e-6, "{name}");
        let below = s.force(s.l_c - 1e-12);
        let above = s.force(s.l_c + 1e-12);
        assert!(
            (above - below).abs() < 1e-3,
            "{name}: jump {below} -> {above} N at l_c"
        );
    }
}

#[test]
fn slope_is_continuous_within_the_stated_kink() {
    // The tendon is exactly C1 at l_tc; the parallel element has a 0.03% kink (6767.8 vs 6770 N/m).
    for (name, s, allowed) in [
        ("tendon", springs()[0].1, 1e-8),
        ("parallel", springs()[1].1, 4e-4),
    ] {
        let left = s.stiffness(s.l_c - 1e-12);
        let right = s.stiffness(s.l_c + 1e-12);
        let kink = (right - left).abs() / right;
        assert!(
            kink <= allowed,
            "{name}: slope kink {kink:.2e} > {allowed:.0e}"
        );
        // And the reported stiffness is the derivative of the force (central differences).
        for l in [s.l_s + 0.2 * (s.l_c - s.l_s), s.l_c + 0.003] {
            let h = 1e-8;
            let fd = (s.force(l + h) - s.force(l - h)) / (2.0 * h);
            assert!(
                (fd - s.stiffness(l)).abs() / fd < 1e-5,
                "{name} at {l}: {fd} vs {}",
                s.stiffness(l)
            );
        }
    }
}

#[test]
fn inverse_recovers_length() {
    for (name, s) in springs() {
        for i in 1..=400 {
            let l = s.l_s + (s.l_c - s.l_s) * 3.0 * i as f64 / 400.0;
            let back = s.length_at_force(s.force(l));
            assert!(
                (back - l).abs() < 1e-12 + 1e-10 * l,
                "{name}: l = {l}, inverse {back}"
            );
        }
        assert_eq!(s.length_at_force(0.0), s.l_s);
        assert_eq!(
            s.length_at_force(-5.0),
            s.l_s,
            "{name}: a push is not transmitted"
        );
    }
}

/// Composite Simpson quadrature on n intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        s += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

#[test]
fn energy_is_the_integral_of_force() {
    for (name, s) in springs() {
        for frac in [0.3, 1.0, 1.7, 4.0] {
            let l = s.l_s + frac * (s.l_c - s.l_s);
            // Integrate piecewise so the quadrature never straddles the transition.
            let mid = l.min(s.l_c);
            let mut q = simpson(|x| s.force(x), s.l_s, mid, 2000);
            if l > s.l_c {
                q += simpson(|x| s.force(x), s.l_c, l, 2000);
            }
            let e = s.energy(l);
            assert!(
                (e - q).abs() <= 1e-9 * q.max(1e-12),
                "{name} at {l}: closed form {e} J, quadrature {q} J"
            );
        }
        assert_eq!(s.energy(s.l_s - 0.01), 0.0);
    }
}
