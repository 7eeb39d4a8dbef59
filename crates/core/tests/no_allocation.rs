//! docs/model.md §10: no allocation per tick. A counting global allocator watches the ticks of
//! actuators (every adaptive model, the elbow and the arm, steady and after excitation steps,
//! with the published snapshot refreshed every tick; the arm with its shoulder driven, its motion
//! set every tick) once they have run a while: not one allocation. And a scenario's run keeps
//! its records without allocating per tick: a longer run of the same scenario allocates no
//! more (its records reserved once); so does a rollout (the Python package's loop,
//! `sim::rollout`) into buffers sized before it.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::physics::{ActivationKind, FibreKind, TendonKind};
use muscle_actuator_core::sim::{default_stepping, Actuator, Scenario};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

struct Counting;

thread_local! {
    /// Whether this thread's allocations are counted: the test harness's own threads allocate
    /// as tests start and end, and only the measured thread's allocations are the tick's.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);
/// The counter is the process's: one test counts at a time.
static SERIAL: Mutex<()> = Mutex::new(());

/// Whether the calling thread counts (false while its thread-local is being torn down).
fn counting() -> bool {
    COUNTING.try_with(Cell::get).unwrap_or(false)
}

// SAFETY: forwards every call to the system allocator unchanged; only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if counting() {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if counting() {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `f` on this thread (the tests count one at a time, under `SERIAL`).
fn allocations(f: impl FnOnce()) -> u64 {
    ALLOCATIONS.store(0, Ordering::SeqCst);
    COUNTING.with(|c| c.set(true));
    f();
    COUNTING.with(|c| c.set(false));
    ALLOCATIONS.load(Ordering::SeqCst)
}

#[test]
fn ticks_do_not_allocate() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut driven_arm = ActuatorConfig::resolve("arm").unwrap();
    driven_arm.joints[0].driven = true;
    // The arm with massless fibres (pennated) and with rigid tendons (docs/model.md §5b).
    let (mut equilibrium_arm, mut rigid_arm) = (driven_arm.clone(), driven_arm.clone());
    for m in &mut equilibrium_arm.muscles {
        m.params.fibre = FibreKind::Equilibrium;
        m.params.pennation = 0.2;
    }
    for m in &mut rigid_arm.muscles {
        (m.params.fibre, m.params.tendon) = (FibreKind::Equilibrium, TendonKind::Rigid);
    }
    // Lloyd & Besier's activation with a delay line (docs/model.md §2b).
    let mut neural_arm = driven_arm.clone();
    for m in &mut neural_arm.muscles {
        m.params.activation = ActivationKind::LloydBesier;
        (m.params.c1, m.params.c2, m.params.em_delay) = (Some(-0.6), Some(-0.4), Some(0.03));
        m.params.shape_factor = Some(-1.5);
    }
    for cfg in [
        ActuatorConfig::default(),
        ActuatorConfig::resolve("arm").unwrap(),
        driven_arm,
        equilibrium_arm,
        rigid_arm,
        neural_arm,
    ] {
        for model in [ModelKind::HILL, ModelKind::HUXLEY] {
            let mut act = Actuator::new(&cfg, model, 1000.0).unwrap();
            let n = act.muscle_names().len();
            // Warm up: the first Jacobians size their entry lists.
            for i in 0..n {
                act.set_excitation(i, 0.3);
            }
            for _ in 0..300 {
                act.step().unwrap();
            }
            let count = allocations(|| {
                for k in 0..300 {
                    if k % 100 == 0 {
                        // Excitation steps: the transients take many sub-steps.
                        for i in 0..n {
                            act.set_excitation(i, if (k / 100 + i) % 2 == 0 { 1.0 } else { 0.1 });
                        }
                        act.set_external_torque(0, (k as f64) * 0.01);
                    }
                    let t = k as f64 * 1e-3;
                    act.set_joint_motion(0, 0.3 * (6.0 * t).sin(), 1.8 * (6.0 * t).cos());
                    act.step().unwrap();
                    std::hint::black_box(act.state().muscles[0].force);
                    std::hint::black_box(act.joint_efforts().sum::<f64>());
                }
            });
            assert_eq!(
                count, 0,
                "{} muscles, {model}: {count} allocations in 300 ticks",
                n
            );
        }
    }
}

#[test]
fn scenario_runs_allocate_alike_at_any_length() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let arm = ActuatorConfig::resolve("arm").unwrap();
    let elbow = ActuatorConfig::default();
    let file = |name: &str| {
        let root = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
        Scenario::from_file(&root.join("scenarios").join(name)).unwrap()
    };
    let pulse = Scenario::built_in("pulse", &elbow.muscles[0].params).unwrap();
    for (sc, cfg) in [(pulse, &elbow), (file("arm_cocontraction.toml"), &arm)] {
        for model in [ModelKind::HILL, ModelKind::HUXLEY] {
            let count = |duration: f64| {
                let mut sc = sc.clone();
                sc.duration = duration;
                allocations(|| {
                    let run = sc.run(cfg, model, 1000.0, default_stepping(model)).unwrap();
                    assert_eq!(run.len(), (duration * 1000.0).round() as usize + 1);
                })
            };
            // Both lengths take every transient of the scenario (the pulse ends at 2 s, the
            // arm's last ramp at 0.8 s); the longer adds quiet ticks only.
            let long = sc.duration;
            let short = long - 0.15;
            count(short);
            let (a, b) = (count(short), count(long));
            assert_eq!(
                a, b,
                "{} {model}: {a} allocations in {short} s, {b} in {long} s",
                sc.name
            );
        }
    }
}

#[test]
fn rollouts_allocate_alike_at_any_length() {
    use muscle_actuator_core::sim::{rollout, Outputs};
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    for cfg in [
        ActuatorConfig::default(),
        ActuatorConfig::resolve("arm").unwrap(),
    ] {
        for model in [ModelKind::HILL, ModelKind::HUXLEY] {
            let mut warm = Actuator::new(&cfg, model, 1000.0).unwrap();
            let (m, j) = (warm.muscle_names().len(), warm.joint_names().len());
            for i in 0..m {
                warm.set_excitation(i, 0.3);
            }
            for _ in 0..300 {
                warm.step().unwrap();
            }
            let outputs = Outputs::all();
            let count = |ticks: usize| {
                // Excitation steps every 100 ticks (transients), a torque ramp.
                let u: Vec<f64> = (0..ticks * m)
                    .map(|k| {
                        if (k / m / 100 + k % m) % 2 == 0 {
                            1.0
                        } else {
                            0.1
                        }
                    })
                    .collect();
                let tau: Vec<f64> = (0..ticks * j).map(|k| (k / j) as f64 * 0.01).collect();
                let mut bufs: Vec<Vec<f64>> = outputs
                    .widths(m, j)
                    .iter()
                    .map(|w| vec![f64::NAN; ticks * w])
                    .collect();
                let mut a = warm.clone();
                let n = allocations(|| {
                    rollout(&mut a, &outputs, &u, Some(&tau), ticks, &mut bufs).unwrap();
                });
                assert!(
                    bufs.iter().flatten().all(|v| v.is_finite()),
                    "every tick written"
                );
                n
            };
            let (short, long) = (count(300), count(600));
            // The call's own lists (output widths, buffer slices); none per tick.
            assert_eq!(
                short, long,
                "{m} muscles, {model}: {short} allocations in 300 ticks, {long} in 600"
            );
            assert!(
                short <= 2,
                "{m} muscles, {model}: {short} allocations a call"
            );
        }
    }
}
