//! An actuator stepped over per-tick inputs, its outputs recorded after each tick: what
//! `Actuator.rollout` and each instance of a batched `rollout` run.

use crate::outputs::{self, Outputs};
use muscle_actuator::sim::run::Record;
use muscle_actuator::sim::simulation::StepError;
use muscle_actuator::sim::Actuator;

/// Steps `a` one tick per row of `u` (ticks × muscles) and `tau` (ticks × joints), writing the
/// outputs after each tick into `bufs` (one per output, ticks × width).
pub fn run_one(
    a: &mut Actuator,
    outputs: &Outputs,
    u: &[f64],
    tau: Option<&[f64]>,
    ticks: usize,
    bufs: &mut [impl AsMut<[f64]>],
) -> Result<(), StepError> {
    let (m, j) = (a.muscle_names().len(), a.joint_names().len());
    let widths = outputs.widths(m, j);
    let mut slices: Vec<&mut [f64]> = bufs.iter_mut().map(|b| b.as_mut()).collect();
    for t in 0..ticks {
        for (i, &x) in u[t * m..(t + 1) * m].iter().enumerate() {
            a.set_excitation(i, x);
        }
        if let Some(tau) = tau {
            for (k, &x) in tau[t * j..(t + 1) * j].iter().enumerate() {
                a.set_external_torque(k, x);
            }
        }
        a.step()?;
        outputs::write_tick(
            outputs,
            &widths,
            &Record::of(0.0, a.state()),
            t,
            &mut slices,
        );
    }
    Ok(())
}
