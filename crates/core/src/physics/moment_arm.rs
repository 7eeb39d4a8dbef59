//! Moment arms of a muscle about a joint it spans (docs/model.md §8b): a constant, or a
//! polynomial in the joint angle. Positive when the muscle's tension increases the angle; the
//! path length obeys `∂L/∂θ = -r(θ)`, so `L(θ) = L(0) - ∫_0^θ r(s) ds`.

use serde::{Deserialize, Serialize};

/// A moment arm r(θ), m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum MomentArm {
    /// A constant moment arm (a pulley), m.
    Constant(f64),
    /// `r(θ) = c0 + c1 θ + c2 θ² + …` (m, m/rad, m/rad², …): coefficients from the constant
    /// term up.
    Polynomial(Vec<f64>),
}

impl MomentArm {
    /// The coefficients, constant term first.
    pub(crate) fn coefficients(&self) -> &[f64] {
        match self {
            MomentArm::Constant(c) => std::slice::from_ref(c),
            MomentArm::Polynomial(c) => c,
        }
    }

    /// `r(θ)`, m (Horner).
    pub fn at(&self, theta: f64) -> f64 {
        match self {
            MomentArm::Constant(c) => *c,
            MomentArm::Polynomial(c) => c.iter().rev().fold(0.0, |acc, &ck| acc * theta + ck),
        }
    }

    /// `dr/dθ`, m/rad.
    pub fn slope(&self, theta: f64) -> f64 {
        match self {
            MomentArm::Constant(_) => 0.0,
            MomentArm::Polynomial(c) => c
                .iter()
                .enumerate()
                .skip(1)
                .rev()
                .fold(0.0, |acc, (k, &ck)| acc * theta + k as f64 * ck),
        }
    }

    /// The path-length change `∫_0^θ r(s) ds`, m (so `L(θ) = L(0) - excursion(θ)`).
    pub(crate) fn excursion(&self, theta: f64) -> f64 {
        match self {
            MomentArm::Constant(c) => c * theta,
            MomentArm::Polynomial(c) => {
                theta
                    * c.iter()
                        .enumerate()
                        .rev()
                        .fold(0.0, |acc, (k, &ck)| acc * theta + ck / (k as f64 + 1.0))
            }
        }
    }

    /// Whether r(θ) keeps one strict sign on [lo, hi]: checked at the ends and at every real
    /// root of r' in between (where r has its extrema), found by sampling and bisection.
    pub(crate) fn keeps_sign_on(&self, lo: f64, hi: f64) -> bool {
        let r_lo = self.at(lo);
        let sign = r_lo.signum();
        if r_lo == 0.0 || !r_lo.is_finite() {
            return false;
        }
        // Dense sampling is exact enough for low-degree polynomials over a joint's range: the
        // extrema are bracketed at 1/4096 of the range and refined by bisection on r'.
        const SAMPLES: usize = 4096;
        let step = (hi - lo) / SAMPLES as f64;
        let mut prev_theta = lo;
        let mut prev_slope = self.slope(lo);
        for k in 1..=SAMPLES {
            let theta = lo + step * k as f64;
            if self.at(theta) * sign <= 0.0 {
                return false;
            }
            let s = self.slope(theta);
            if s * prev_slope < 0.0 {
                let (mut a, mut b) = (prev_theta, theta);
                for _ in 0..60 {
                    let m = 0.5 * (a + b);
                    if self.slope(m) * prev_slope > 0.0 {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                if self.at(0.5 * (a + b)) * sign <= 0.0 {
                    return false;
                }
            }
            prev_theta = theta;
            prev_slope = s;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_excursion_is_the_integral_of_the_arm() {
        let arm = MomentArm::Polynomial(vec![0.02, -0.004, 0.003, 0.0005]);
        for theta in [-1.2, -0.3, 0.0, 0.7, 2.1] {
            // Simpson's rule with many panels.
            let n = 2000;
            let h = theta / n as f64;
            let mut s = arm.at(0.0) + arm.at(theta);
            for k in 1..n {
                s += arm.at(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
            }
            let integral = s * h / 3.0;
            assert!((arm.excursion(theta) - integral).abs() < 1e-14, "{theta}");
            let d = 1e-6;
            let fd = (arm.at(theta + d) - arm.at(theta - d)) / (2.0 * d);
            assert!((arm.slope(theta) - fd).abs() < 1e-9, "{theta}");
        }
        assert_eq!(MomentArm::Constant(0.03).excursion(2.0), 0.06);
    }

    #[test]
    fn sign_changes_inside_the_range_are_found() {
        // r = 0.01 - 0.01 θ changes sign at θ = 1.
        let arm = MomentArm::Polynomial(vec![0.01, -0.01]);
        assert!(arm.keeps_sign_on(-1.0, 0.9));
        assert!(!arm.keeps_sign_on(-1.0, 1.5));
        // r = (θ - 0.5)² + 1e-6 - ... dips below zero only between its ends: 0.001 - (θ-0.5)²·0
        let dip = MomentArm::Polynomial(vec![0.25 - 1e-4, -1.0, 1.0]); // (θ-0.5)² - 1e-4
        assert!(!dip.keeps_sign_on(0.0, 1.0));
        assert!(MomentArm::Constant(-0.03).keeps_sign_on(-1.0, 1.0));
        assert!(!MomentArm::Constant(0.0).keeps_sign_on(-1.0, 1.0));
    }
}
