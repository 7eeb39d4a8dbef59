//! The full Huxley model's accuracy against its grid and sub-steps, and its cost:
//! `cargo run --release --example pde_tradeoff`.
//!
//! Accuracy: the isometric plateau of the `pulse` scenario (t = 1.9 s) against the exact value
//! Fmax·f(l_m), and the steady force at half vmax against the closed-form oracle; cost: wall time
//! per tick of the pulse (one muscle) on this machine.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::contractile::{
    calibrate_exact, force_length, steady_q1, CrossBridgeGrid,
};
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::Stepping;
use muscle_actuator_core::sim::Scenario;
use std::time::Instant;

fn main() {
    println!("| cells per h | sub-steps per tick | plateau error (N) | steady error at vmax/2 (% Fmax) | cost per muscle-tick (µs) |");
    println!("|---|---|---|---|---|");
    for cells in [100, 250, 500, 1000] {
        for substeps in [10, 20, 40] {
            let mut cfg = ActuatorConfig::default();
            cfg.muscles[0].params.crossbridge.pde_cells = cells;
            let p = cfg.muscles[0].params.clone();
            let sc = Scenario::built_in("pulse", &p).unwrap();
            let t = Instant::now();
            let run = sc
                .run(
                    &cfg,
                    ModelKind::HUXLEY_PDE,
                    1000.0,
                    Stepping::Fixed(substeps),
                )
                .unwrap();
            let per_tick = t.elapsed().as_secs_f64() * 1e6 / 3000.0;
            let rec = &run.record(1900).muscles[0];
            let exact = p.f_max * force_length(rec.fiber_length, p.l_opt, p.fl_width, p.fl_shape);
            // Steady shortening at vmax/2 on this grid (kinematic), against the oracle.
            let cal = calibrate_exact(&p);
            let u = cal.shortening_rate(-0.5 * p.v_max);
            let mut g = CrossBridgeGrid::new(cells, 64.0);
            let dt = 1e-3 / substeps as f64;
            for _ in 0..(0.3 / dt) as usize {
                g.advance(&cal.rates, 1.0, dt, -u * dt);
            }
            let steady = cal.force(g.moments()[1]);
            let oracle = cal.force(steady_q1(&cal.rates, 1.0, u));
            println!(
                "| {cells} | {substeps} | {:.2} | {:.3} | {per_tick:.1} |",
                rec.ce_force - exact,
                100.0 * (steady - oracle) / p.f_max
            );
        }
    }
}
