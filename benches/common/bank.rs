//! What the bank benchmarks share (`benches/limb.rs`, `examples/bank_threads.rs`): the bank of
//! independent elbows and the generator of their random excitations.

use muscle_actuator_core::config::{ActuatorConfig, MuscleConfig, SpanConfig};
use muscle_actuator_core::physics::{JointParams, MomentArm, MuscleParams};

/// k antagonistic elbows, independent.
pub fn bank(k: usize) -> ActuatorConfig {
    let mut cfg = ActuatorConfig {
        joints: vec![],
        muscles: vec![],
        stepper: Default::default(),
    };
    for j in 0..k {
        let name = format!("joint{j}");
        cfg.joints.push(JointParams {
            name: name.clone(),
            ..JointParams::default()
        });
        for (m, r) in [("flexor", 0.03), ("extensor", -0.03)] {
            cfg.muscles.push(MuscleConfig {
                name: format!("{m}{j}"),
                params: MuscleParams::default(),
                path_length: None,
                spans: vec![SpanConfig {
                    joint: name.clone(),
                    moment_arm: MomentArm::Constant(r),
                    changes_sign: false,
                }],
            });
        }
    }
    cfg
}

/// A deterministic generator in [0, 1).
pub struct Lcg(pub u64);
impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}
