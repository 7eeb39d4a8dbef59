//! docs/model.md §10: no allocation per tick. A counting global allocator watches the ticks of
//! actuators (every adaptive model, the elbow and the arm, steady and after excitation steps,
//! with the published snapshot refreshed every tick; the arm with its shoulder driven, its motion
//! set every tick) once they have run a while: not one allocation.

use muscle_actuator::config::ActuatorConfig;
use muscle_actuator::physics::model::ModelKind;
use muscle_actuator::sim::Actuator;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

// SAFETY: forwards every call to the system allocator unchanged; only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `f` (this test binary runs one test, so no other thread counts).
fn allocations(f: impl FnOnce()) -> u64 {
    ALLOCATIONS.store(0, Ordering::SeqCst);
    COUNTING.store(true, Ordering::SeqCst);
    f();
    COUNTING.store(false, Ordering::SeqCst);
    ALLOCATIONS.load(Ordering::SeqCst)
}

#[test]
fn ticks_do_not_allocate() {
    let mut driven_arm = ActuatorConfig::resolve("arm").unwrap();
    driven_arm.joints[0].driven = true;
    for cfg in [
        ActuatorConfig::default(),
        ActuatorConfig::resolve("arm").unwrap(),
        driven_arm,
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
