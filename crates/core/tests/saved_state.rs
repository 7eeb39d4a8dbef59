//! Saved states (crates/core/src/sim/saved.rs): an actuator rebuilt from `to_bytes` continues bit for bit as
//! the original does, for every model, the built-in limbs, driven joints, a stepper caught in a
//! transient and a reset; a clone does too; damaged or foreign bytes are refused with a message
//! that names what is wrong, and never panic.
//!
//! Every output is compared by its bits: each tick's whole published state (every muscle and
//! joint field, the stiffness matrix), the joint efforts, the state vector, the activations, the
//! integrator's work counters, the tick and the time.

use muscle_actuator_core::config::ActuatorConfig;
use muscle_actuator_core::physics::models::ModelKind;
use muscle_actuator_core::sim::{Actuator, JointSnapshot, MuscleSnapshot};
use sha2::{Digest, Sha256};
use std::ops::Range;

const MODELS: [ModelKind; 3] = [ModelKind::HILL, ModelKind::HUXLEY, ModelKind::HUXLEY_PDE];
const RATE_HZ: f64 = 1000.0;
/// Where the runs are saved, and where they end.
const SAVE: u64 = 300;
const END: u64 = 600;

fn built_in(name: &str) -> ActuatorConfig {
    ActuatorConfig::resolve(name).unwrap()
}

/// The elbow (one joint) and the arm (two), by name.
fn limbs() -> [(&'static str, ActuatorConfig); 2] {
    [("elbow", built_in("elbow")), ("arm", built_in("arm"))]
}

/// Muscle i's excitation at tick k: quiet, a step of the even muscles, a ramp, co-contraction,
/// then (from tick 300) a large step of the odd muscles (the even ones released), a ramp down
/// and co-contraction again.
fn excitation(k: u64, i: usize) -> f64 {
    let (t, p) = (k as f64, i as f64);
    match k {
        0..=49 => 0.0,
        50..=119 if i.is_multiple_of(2) => 0.9,
        50..=119 => 0.05,
        120..=219 => ((t - 120.0) / 100.0 * (0.3 + 0.1 * p)).min(1.0),
        220..=299 => 0.45 + 0.25 * ((t + 7.0 * p) / 13.0).sin(),
        300..=389 if i % 2 == 1 => 1.0,
        300..=389 => 0.0,
        390..=479 => 1.0 - (t - 390.0) / 90.0 * (0.5 + 0.05 * p),
        _ => 0.6 + 0.3 * ((t + 3.0 * p) / 9.0).cos(),
    }
}

/// Joint j's external torque at tick k, N m: a slow sine and a step at tick 420.
fn torque(k: u64, j: usize) -> f64 {
    let step = if k >= 420 { 3.0 } else { 0.0 };
    2.0 * (k as f64 / 37.0 + j as f64).sin() + step
}

/// A driven joint's motion set at tick k (angle, velocity), at a few ticks only: in between,
/// the motion set last carries on.
fn joint_motion(k: u64, n: usize) -> Option<(f64, f64)> {
    let s = if n.is_multiple_of(2) { 1.0 } else { -1.0 };
    match k {
        0 => Some((0.0, 0.8 * s)),
        150 => Some((0.25 * s, -1.2 * s)),
        330 => Some((0.1, 0.5 * s)),
        460 => Some((-0.2 * s, 0.0)),
        _ => None,
    }
}

/// Sets tick k's inputs.
fn apply_inputs(a: &mut Actuator, k: u64) {
    for i in 0..a.muscle_names().len() {
        a.set_excitation(i, excitation(k, i));
    }
    let driven = a.driven_joints().to_vec();
    for j in 0..a.joint_names().len() {
        if !driven.contains(&j) {
            a.set_external_torque(j, torque(k, j));
        }
    }
    for (n, &j) in driven.iter().enumerate() {
        if let Some((angle, velocity)) = joint_motion(k, n) {
            assert!(a.set_joint_motion(j, angle, velocity));
        }
    }
}

/// Every output after a tick, as bits.
fn observe(a: &Actuator) -> Vec<u64> {
    let s = a.state();
    let mut v = vec![a.tick(), a.time().to_bits()];
    for m in &s.muscles {
        v.extend(m.values().map(f64::to_bits));
    }
    for j in &s.joints {
        v.extend(j.values().map(f64::to_bits));
    }
    v.extend(s.stiffness_matrix.iter().map(|x| x.to_bits()));
    v.extend(a.joint_efforts().map(f64::to_bits));
    let sim = a.simulation();
    v.extend(sim.state().iter().map(|x| x.to_bits()));
    v.extend(sim.activations().iter().map(|x| x.to_bits()));
    let st = sim.stats();
    v.extend([
        st.rhs_evals,
        st.jacobians,
        st.factorisations,
        st.solves,
        st.substeps,
        st.rejected,
    ]);
    v
}

/// What each entry of [`observe`] is.
fn labels(a: &Actuator) -> Vec<String> {
    let mut l = vec!["tick".to_string(), "time".to_string()];
    for m in a.muscle_names() {
        l.extend(MuscleSnapshot::FIELDS.iter().map(|f| format!("{m}.{f}")));
    }
    for j in a.joint_names() {
        l.extend(JointSnapshot::FIELDS.iter().map(|f| format!("{j}.{f}")));
    }
    let n = a.joint_names().len();
    l.extend((0..n * n).map(|k| format!("stiffness_matrix[{k}]")));
    l.extend(a.driven_joints().iter().map(|j| format!("effort[{j}]")));
    l.extend((0..a.simulation().state().len()).map(|k| format!("y[{k}]")));
    l.extend((0..a.muscle_names().len()).map(|k| format!("activation[{k}]")));
    l.extend(
        [
            "rhs_evals",
            "jacobians",
            "factorisations",
            "solves",
            "substeps",
            "rejected",
        ]
        .map(String::from),
    );
    l
}

/// Steps through ticks `ticks` (inputs of those ticks), recording every tick's outputs.
fn run(a: &mut Actuator, ticks: Range<u64>) -> Vec<Vec<u64>> {
    ticks
        .map(|k| {
            apply_inputs(a, k);
            a.step().unwrap_or_else(|e| panic!("tick {k}: {e}"));
            observe(a)
        })
        .collect()
}

/// Both runs equal bit for bit, or the first tick and output that differ.
fn assert_same(what: &str, a: &Actuator, original: &[Vec<u64>], copy: &[Vec<u64>]) {
    assert_eq!(original.len(), copy.len(), "{what}: run lengths");
    let names = labels(a);
    for (k, (x, y)) in original.iter().zip(copy).enumerate() {
        assert_eq!(x.len(), names.len(), "{what}: the labels cover the outputs");
        if let Some(i) = (0..x.len()).find(|&i| x[i] != y[i]) {
            panic!(
                "{what}: tick {} of the continuation differs first in {}: {} vs {} (bits {:#x} vs {:#x})",
                k + 1,
                names[i],
                f64::from_bits(x[i]),
                f64::from_bits(y[i]),
                x[i],
                y[i]
            );
        }
    }
}

/// Restores `a`'s bytes, checks the copy shows the same state at once, then continues both over
/// `ticks` and compares them.
fn continue_both(what: &str, a: &mut Actuator, ticks: Range<u64>) -> usize {
    let bytes = a.to_bytes();
    let mut b = Actuator::from_bytes(&bytes).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(
        observe(a),
        observe(&b),
        "{what}: the state right after the restore"
    );
    assert_eq!(
        a.to_bytes(),
        b.to_bytes(),
        "{what}: the copy saves the same bytes"
    );
    assert_eq!(a.config(), b.config(), "{what}: configuration");
    assert_eq!(
        format!("{:?}", a.config()),
        format!("{:?}", b.config()),
        "{what}: config bits"
    );
    assert_eq!(
        (a.model(), a.rate_hz().to_bits()),
        (b.model(), b.rate_hz().to_bits())
    );
    assert_eq!(a.simulation().stepping(), b.simulation().stepping());
    let original = run(a, ticks.clone());
    let copy = run(&mut b, ticks);
    assert_same(what, a, &original, &copy);
    bytes.len()
}

#[test]
fn restored_actuators_continue_bit_for_bit_for_every_model_and_limb() {
    for (limb, cfg) in limbs() {
        for model in MODELS {
            let what = format!("{limb}/{model}");
            let mut a = Actuator::new(&cfg, model, RATE_HZ).unwrap();
            run(&mut a, 0..SAVE);
            let size = continue_both(&what, &mut a, SAVE..END);
            eprintln!("payload {what} after {SAVE} ticks: {size} bytes");
        }
    }
}

/// Saved one tick after a large excitation step (tick 300: the odd muscles 0.2..0.7 → 1, the
/// even ones → 0): the adaptive stepper is mid-transient, its carried sub-step shorter than a
/// tick (the DM model then steps with its fourth-order method), its Jacobian kept.
#[test]
fn a_stepper_saved_mid_transient_continues_bit_for_bit() {
    for (limb, cfg) in limbs() {
        for model in MODELS {
            let what = format!("{limb}/{model} mid-transient");
            let mut a = Actuator::new(&cfg, model, RATE_HZ).unwrap();
            run(&mut a, 0..SAVE + 1);
            if model.is_ode() {
                let before = a.simulation().stats().substeps;
                let mut probe = a.clone();
                run(&mut probe, SAVE + 1..SAVE + 2);
                let substeps = probe.simulation().stats().substeps - before;
                assert!(
                    substeps > 1,
                    "{what}: the tick after the save takes {substeps} sub-steps"
                );
            }
            continue_both(&what, &mut a, SAVE + 1..END);
        }
    }
}

#[test]
fn a_state_saved_after_reset_continues_bit_for_bit() {
    for (limb, cfg) in limbs() {
        for model in MODELS {
            let what = format!("{limb}/{model} after reset");
            let mut a = Actuator::new(&cfg, model, RATE_HZ).unwrap();
            run(&mut a, 0..SAVE);
            a.reset();
            assert_eq!(a.tick(), 0);
            // The inputs of ticks 300.. from tick 0: a step straight from rest.
            continue_both(&what, &mut a, SAVE..END);
        }
    }
}

/// Driven joints: the motion set at ticks 0, 150, 330 and 460 carries on in between, across
/// the save at tick 300 too. The elbow driven alone, and the arm with its elbow driven and its
/// shoulder free.
#[test]
fn driven_joints_carry_their_motion_across_a_restore() {
    let mut elbow = built_in("elbow");
    elbow.joints[0].driven = true;
    let mut arm = built_in("arm");
    let e = arm.joints.iter().position(|j| j.name == "elbow").unwrap();
    arm.joints[e].driven = true;
    for (limb, cfg) in [("driven elbow", elbow), ("arm, elbow driven", arm)] {
        for model in MODELS {
            let what = format!("{limb}/{model}");
            let mut a = Actuator::new(&cfg, model, RATE_HZ).unwrap();
            assert!(!a.driven_joints().is_empty());
            run(&mut a, 0..SAVE);
            continue_both(&what, &mut a, SAVE..END);
        }
    }
}

/// Limbs of several parts (four independent joints), and of a core too large for the explicit
/// inverse (a chain of five joints in one part: the Schur complement's LU, its permutation
/// kept across ticks), with a chosen stepping.
#[test]
fn several_parts_and_a_large_core_continue_bit_for_bit() {
    let four = ActuatorConfig::from_file(std::path::Path::new(concat!(
        concat!(env!("CARGO_MANIFEST_DIR"), "/../.."),
        "/configs/four_joints.toml"
    )))
    .unwrap();
    let chain = ActuatorConfig::from_toml_str(&chain_toml(5)).unwrap();
    for (limb, cfg) in [("four joints", four), ("chain of five", chain)] {
        for model in [ModelKind::HUXLEY, ModelKind::HUXLEY_PDE] {
            let what = format!("{limb}/{model}");
            let mut a = Actuator::new(&cfg, model, RATE_HZ).unwrap();
            run(&mut a, 0..SAVE);
            continue_both(&what, &mut a, SAVE..END);
        }
    }
    let stepping = muscle_actuator_core::physics::Stepping::Adaptive {
        tolerance: 3e-6,
        max_substeps: 17,
    };
    let mut a =
        Actuator::with_stepping(&built_in("arm"), ModelKind::HILL, 750.0, stepping).unwrap();
    run(&mut a, 0..SAVE);
    continue_both("arm/hill at 750 Hz, chosen stepping", &mut a, SAVE..END);
}

/// `n` joints in a chain, each pair of neighbours spanned by an antagonistic pair of two-joint
/// muscles, and one pair on the first joint alone.
fn chain_toml(n: usize) -> String {
    let mut t = String::new();
    for j in 1..=n {
        t += &format!("[[joint]]\nname = \"j{j}\"\n");
    }
    let mut muscle = |name: String, spans: &[(usize, f64)]| {
        let s: Vec<String> = (spans.iter())
            .map(|(j, r)| format!("{{ joint = \"j{j}\", moment_arm = {r:?} }}"))
            .collect();
        t += &format!("[[muscle]]\nname = \"{name}\"\nspan = [{}]\n", s.join(", "));
    };
    muscle("first_flexor".into(), &[(1, 0.03)]);
    muscle("first_extensor".into(), &[(1, -0.03)]);
    for j in 1..n {
        muscle(format!("m{j}_flexor"), &[(j, 0.02), (j + 1, 0.025)]);
        muscle(format!("m{j}_extensor"), &[(j, -0.02), (j + 1, -0.025)]);
    }
    t
}

#[test]
fn a_clone_continues_as_the_original() {
    for (limb, cfg) in limbs() {
        for model in MODELS {
            let what = format!("{limb}/{model} clone");
            let mut a = Actuator::new(&cfg, model, RATE_HZ).unwrap();
            run(&mut a, 0..SAVE + 1);
            let mut b = a.clone();
            let original = run(&mut a, SAVE + 1..END);
            let copy = run(&mut b, SAVE + 1..END);
            assert_same(&what, &a, &original, &copy);
        }
    }
}

/// Set in the child process of [`a_state_restored_in_another_process_continues_bit_for_bit`]:
/// the directory of the saved states it restores and of the outputs it writes.
const CHILD_DIR: &str = "MUSCLE_ACTUATOR_SAVED_STATE_DIR";

/// Each model's arm saved here, restored and continued by a fresh process (this test binary run
/// again for this one test): its outputs are the original's, bit for bit.
#[test]
fn a_state_restored_in_another_process_continues_bit_for_bit() {
    let names = |dir: &std::path::Path, model: ModelKind| {
        (
            dir.join(format!("{model}.state")),
            dir.join(format!("{model}.out")),
        )
    };
    if let Some(dir) = std::env::var_os(CHILD_DIR) {
        // The child: restore, continue, write every tick's outputs.
        for model in MODELS {
            let (state, out) = names(std::path::Path::new(&dir), model);
            let mut a = Actuator::from_bytes(&std::fs::read(state).unwrap()).unwrap();
            let bits: Vec<u8> = (run(&mut a, SAVE..END).into_iter().flatten())
                .flat_map(u64::to_le_bytes)
                .collect();
            std::fs::write(out, bits).unwrap();
        }
        return;
    }
    let dir = std::env::temp_dir().join(format!("muscle_actuator_saved_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut originals = Vec::new();
    for model in MODELS {
        let mut a = Actuator::new(&built_in("arm"), model, RATE_HZ).unwrap();
        run(&mut a, 0..SAVE);
        std::fs::write(names(&dir, model).0, a.to_bytes()).unwrap();
        originals.push((run(&mut a, SAVE..END), a));
    }
    let status = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "a_state_restored_in_another_process_continues_bit_for_bit",
        ])
        .arg("--test-threads=1")
        .env(CHILD_DIR, &dir)
        .stdout(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(status.success(), "the child process failed: {status}");
    for (model, (original, a)) in MODELS.into_iter().zip(&originals) {
        let bytes = std::fs::read(names(&dir, model).1).unwrap();
        let bits: Vec<u64> = (bytes.chunks_exact(8))
            .map(|b| u64::from_le_bytes(b.try_into().unwrap()))
            .collect();
        let copy: Vec<Vec<u64>> = bits
            .chunks(original[0].len())
            .map(<[u64]>::to_vec)
            .collect();
        assert_same(
            &format!("arm/{model} in another process"),
            a,
            original,
            &copy,
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The configuration comes back identical, every f64 by its bits, from the TOML text the bytes
/// hold: values that need all 17 digits, tiny and huge ones, −0, polynomial arms, an energy
/// model chosen.
#[test]
fn the_configuration_comes_back_bit_for_bit() {
    let mut cfg = built_in("arm");
    cfg.joints[0].initial_angle = -0.0;
    cfg.joints[1].inertia = 0.1 + 0.2;
    cfg.joints[1].damping = 1.0 / 3.0;
    cfg.muscles[0].params.f_max = 4000.000000000001;
    cfg.muscles[1].params.l_opt = std::f64::consts::PI / 30.0;
    cfg.muscles[2].path_length = Some(0.3 + 1e-16);
    let cfg = cfg.with_energy_model(muscle_actuator_core::physics::EnergyModel::Bhargava);
    for model in MODELS {
        let a = Actuator::new(&cfg, model, 999.9999999999999).unwrap();
        let b = Actuator::from_bytes(&a.to_bytes()).unwrap();
        assert_eq!(a.config(), b.config());
        assert_eq!(format!("{:?}", a.config()), format!("{:?}", b.config()));
        assert_eq!(a.rate_hz().to_bits(), b.rate_hz().to_bits());
        assert_eq!(a.to_bytes(), b.to_bytes());
    }
}

// --- damaged and foreign bytes -----------------------------------------------------------

/// Magic, version and length; the SHA-256 at the end.
const HEADER: usize = 20;
const CHECKSUM: usize = 32;

fn body(bytes: &[u8]) -> &[u8] {
    &bytes[HEADER..bytes.len() - CHECKSUM]
}

/// A body sealed as `to_bytes` seals it (a valid checksum over whatever it holds).
fn seal(body: &[u8]) -> Vec<u8> {
    let mut out = bytes_of_header(body.len());
    out.extend_from_slice(body);
    let sum = Sha256::digest(&out);
    out.extend_from_slice(&sum);
    out
}

fn bytes_of_header(body_len: usize) -> Vec<u8> {
    let mut out = b"MUSCACTS".to_vec();
    out.extend_from_slice(&1u32.to_le_bytes());
    out.extend_from_slice(&(body_len as u64).to_le_bytes());
    out
}

/// A real payload: `limb` and `model` after 300 ticks.
fn payload(limb: &str, model: ModelKind) -> Vec<u8> {
    let mut a = Actuator::new(&built_in(limb), model, RATE_HZ).unwrap();
    run(&mut a, 0..SAVE);
    a.to_bytes()
}

fn refused(bytes: &[u8]) -> String {
    match Actuator::from_bytes(bytes) {
        Ok(_) => panic!("{} bytes accepted", bytes.len()),
        Err(e) => {
            let text = e.to_string();
            assert!(!text.contains('\n'), "one line: {text}");
            text
        }
    }
}

#[test]
fn every_truncation_is_refused() {
    for model in [ModelKind::HUXLEY, ModelKind::HUXLEY_PDE] {
        let p = payload("elbow", model);
        assert!(Actuator::from_bytes(&p).is_ok());
        for n in 0..p.len() {
            let e = refused(&p[..n]);
            let expected = if n == 0 { "empty" } else { "truncated" };
            assert!(e.contains(expected), "{n} of {} bytes: {e}", p.len());
        }
    }
}

#[test]
fn single_bit_flips_are_refused_by_what_they_hit() {
    let p = payload("elbow", ModelKind::HUXLEY);
    let positions = (0..HEADER).chain((0..200).map(|k| HEADER + k * (p.len() - HEADER) / 200));
    for pos in positions.chain(p.len() - CHECKSUM..p.len()) {
        for bit in [pos % 8, 7 - pos % 8] {
            let mut q = p.clone();
            q[pos] ^= 1 << bit;
            let e = refused(&q);
            let expected: &[&str] = match pos {
                0..8 => &["wrong magic"],
                8..12 => &["format version"],
                12..20 => &["truncated", "trailing bytes"],
                _ => &["checksum mismatch"],
            };
            assert!(
                expected.iter().any(|x| e.contains(x)),
                "bit {bit} of byte {pos}: {e}"
            );
        }
    }
}

#[test]
fn empty_and_random_bytes_are_refused() {
    assert!(refused(&[]).contains("empty"));
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for k in 0..300 {
        let len = (next() % 6000) as usize + 1;
        let mut q: Vec<u8> = (0..len).map(|_| next() as u8).collect();
        if k % 3 == 0 {
            // A right header over random bytes: only the checksum tells.
            let n = q.len().max(HEADER + CHECKSUM);
            q.resize(n, 0);
            q[..HEADER].copy_from_slice(&bytes_of_header(n - HEADER - CHECKSUM));
            assert!(refused(&q).contains("checksum mismatch"));
        } else {
            let e = refused(&q);
            assert!(e.contains("wrong magic") || e.contains("truncated"), "{e}");
        }
    }
    // Another format's version.
    let mut p = payload("elbow", ModelKind::HILL);
    p[8] = 2;
    assert!(refused(&p).contains("format version 2"));
}

/// With a valid checksum (bytes made to look sound), every body that does not fit the actuator
/// its configuration describes is refused, naming what does not fit.
#[test]
fn sound_looking_bytes_that_do_not_fit_are_refused() {
    let elbow = payload("elbow", ModelKind::HUXLEY);
    let arm = payload("arm", ModelKind::HUXLEY);
    let (eb, ab) = (body(&elbow), body(&arm));
    // The elbow's configuration over the arm's state, and the reverse.
    let config_end = |b: &[u8]| 8 + u64::from_le_bytes(b[..8].try_into().unwrap()) as usize;
    for (config, state) in [(eb, ab), (ab, eb)] {
        let mut spliced = config[..config_end(config)].to_vec();
        spliced.extend_from_slice(&state[config_end(state)..]);
        let e = refused(&seal(&spliced));
        assert!(e.contains("saved, this structure has"), "{e}");
    }
    // Another model's name: the Hill element has no state of its own, the full model no
    // adaptive sub-steps, an unknown one is unknown.
    let name_at = config_end(eb);
    for (other, expected) in [
        ("hill", "saved, this structure has"),
        ("huxley-pde", "needs a fixed number of sub-steps"),
        ("huxlex", "unknown model"),
    ] {
        let mut b = eb[..name_at].to_vec();
        b.extend_from_slice(&(other.len() as u64).to_le_bytes());
        b.extend_from_slice(other.as_bytes());
        b.extend_from_slice(&eb[name_at + 8 + "huxley".len()..]);
        let e = refused(&seal(&b));
        assert!(e.contains(expected), "{other}: {e}");
    }
    // A damaged configuration text.
    let mut b = eb.to_vec();
    b[8] = b'=';
    assert!(refused(&seal(&b)).contains("configuration"));
    // Cut short, or with more after it.
    for k in 0..200 {
        let n = k * eb.len() / 200;
        let e = refused(&seal(&eb[..n]));
        assert!(
            e.contains("end inside"),
            "body cut at {n} of {}: {e}",
            eb.len()
        );
    }
    let mut longer = eb.to_vec();
    longer.push(0);
    assert!(refused(&seal(&longer)).contains("left over"));
}

/// Any byte of a sound-looking body changed: no panic, either an error or an actuator that
/// steps (to an error, perhaps) without a panic either. Some changed bodies (a changed number)
/// are accepted, so the stepping is exercised too.
#[test]
fn changed_values_under_a_valid_checksum_never_panic() {
    for (limb, model, count) in [
        ("elbow", ModelKind::HUXLEY, 400),
        ("arm", ModelKind::HILL, 150),
        ("elbow", ModelKind::HUXLEY_PDE, 150),
    ] {
        let p = payload(limb, model);
        let b = body(&p);
        let mut accepted = 0;
        for k in 0..count {
            let pos = (k * 7919) % b.len();
            let mut q = b.to_vec();
            q[pos] = q[pos].wrapping_add(0x5b);
            if let Ok(mut a) = Actuator::from_bytes(&seal(&q)) {
                accepted += 1;
                for k in SAVE..SAVE + 3 {
                    apply_inputs(&mut a, k);
                    if a.step().is_err() {
                        a.reset();
                    }
                }
            }
        }
        eprintln!("{limb}/{model}: {accepted} of {count} changed bodies accepted");
        assert!(
            accepted > 0,
            "{limb}/{model}: no changed body was accepted and stepped"
        );
    }
}
