//! Shared helpers of the Rust tests: the adaptive reference solution of a scenario, and small
//! configuration and scenario fixtures.
#![allow(dead_code)]

pub mod fixtures;
mod reference;

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{activation_rate, Stepping};
use muscle_actuator_core::sim::{Record, Scenario};

/// Tick-by-tick comparison of the 1 kHz stepper with the Dop853 reference (tolerance 1e-10 on
/// scaled variables), same inputs held over each tick. Returns the worst force and fibre-length
/// deviations over all ticks and muscles, N and m.
pub fn worst_deviation_from_reference(
    scenario: &Scenario,
    cfg: &ActuatorConfig,
    model: ModelKind,
    rate_hz: f64,
    stepping: Stepping,
) -> (f64, f64) {
    assert!(
        model != ModelKind::HUXLEY_PDE,
        "the full model has no ODE reference"
    );
    let mut runner = scenario.runner(cfg, model, rate_hz, stepping).unwrap();
    let plant = runner.simulation().plant().clone();
    let dim = plant.dim();
    let n_mus = plant.muscle_count();
    let mut y: Vec<f64> = runner.simulation().state().to_vec();
    y.extend_from_slice(runner.simulation().activations());
    let mut scales = vec![0.0; dim];
    plant.scales(&mut scales);
    scales.extend(std::iter::repeat_n(1.0, n_mus));
    let ticks = (scenario.duration * rate_hz).round() as u64;
    let (mut worst_f, mut worst_l) = (0.0f64, 0.0f64);
    for k in 0..ticks {
        let t0 = k as f64 / rate_hz;
        let inputs = runner.inputs_at(t0);
        let f = |t: f64, y: &[f64], dy: &mut [f64]| {
            let act = &y[dim..];
            plant.derivatives(t - t0, &y[..dim], act, &inputs, &mut dy[..dim]);
            for i in 0..n_mus {
                let p = &plant.mtus[i].params;
                dy[dim + i] = activation_rate(inputs.excitation[i], act[i], p.t_act, p.t_deact);
            }
        };
        reference::integrate(&f, t0, t0 + 1.0 / rate_hz, &mut y, &scales, 1e-10).unwrap();
        runner.step().unwrap();
        let rec: Record<'_> = runner.record();
        for i in 0..n_mus {
            let state = plant.fibre_state(&y[..dim], i, y[dim + i], &inputs);
            let (f_ref, l_ref) = (state.tendon_force, state.ce.fibre_length);
            worst_f = worst_f.max((rec.muscles[i].force - f_ref).abs());
            worst_l = worst_l.max((rec.muscles[i].fiber_length - l_ref).abs());
        }
    }
    (worst_f, worst_l)
}
