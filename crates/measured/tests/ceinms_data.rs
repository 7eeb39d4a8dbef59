//! The measured data of data/ceinms (the CEINMS toolbox's test data: one person, six trials;
//! data/ceinms/README.md) through the readers of `measured`: every trial, the subject and the
//! excitation map read and agree, and facts checked by hand in the files hold.

use muscle_actuator_measured::measured::{
    Calibration, Excitation, ExcitationMap, Subject, Table, Trial,
};
use std::path::PathBuf;

const TRIALS: [&str; 6] = [
    "_CrossOvers1_",
    "_CrossOvers6_",
    "_CrossOvers7_",
    "_FastWalking1_",
    "_FastWalking9_",
    "_FastWalking_",
];

/// The 16 channels of `emg.txt`, in its order.
const CHANNELS: [&str; 16] = [
    "addmag_r",
    "bicfemlh_r",
    "gaslat_r",
    "gasmed_r",
    "gmax_r",
    "gmed_r",
    "gra_r",
    "perlong_r",
    "recfem_r",
    "sar_r",
    "semimem_r",
    "sol_r",
    "tfl_r",
    "tibant_r",
    "vaslat_r",
    "vasmed_r",
];

/// The units spanning the knee, as `R_knee_feMa.txt` and the subject's `dofSet` list them.
const KNEE_UNITS: [&str; 13] = [
    "bicfemlh_r",
    "bicfemsh_r",
    "gaslat_r",
    "gasmed_r",
    "gra_r",
    "recfem_r",
    "sar_r",
    "semimem_r",
    "semiten_r",
    "tfl_r",
    "vasint_r",
    "vaslat_r",
    "vasmed_r",
];

fn data() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/ceinms")
}

fn trial(name: &str) -> Trial {
    Trial::read(&data().join(name)).unwrap_or_else(|e| panic!("{e}"))
}

fn subject() -> Subject {
    Subject::read(&data().join("uncalibratedSubject.xml")).unwrap_or_else(|e| panic!("{e}"))
}

fn map() -> ExcitationMap {
    ExcitationMap::read(&data().join("emgGenerator-16To34.xml")).unwrap_or_else(|e| panic!("{e}"))
}

/// Every step between `table`'s times is `step` s within rounding.
fn assert_uniform(table: &Table, step: f64, what: &str) {
    for w in table.times().windows(2) {
        assert!(
            ((w[1] - w[0]) - step).abs() < 1e-9,
            "{what}: {} to {}",
            w[0],
            w[1]
        );
    }
}

#[test]
fn every_trial_has_16_channels_at_2_khz_and_34_units_at_250_hz() {
    for name in TRIALS {
        let t = trial(name);
        assert_eq!(t.name, name);
        assert_eq!(t.emg.columns(), CHANNELS, "{name}");
        assert_uniform(&t.emg, 0.0005, name);
        assert_eq!(t.lmt.columns().len(), 34, "{name}");
        assert_uniform(&t.lmt, 0.004, name);
        assert_eq!(
            t.dofs().collect::<Vec<_>>(),
            ["R_ankle_fe", "R_hip_aa", "R_hip_fe", "R_knee_fe"],
            "{name}"
        );
        assert_eq!(t.moment_arms["R_knee_fe"].columns(), KNEE_UNITS, "{name}");
        assert_eq!(t.moment_arms["R_hip_fe"].columns().len(), 23, "{name}");
        assert_eq!(t.moment_arms["R_hip_aa"].columns().len(), 23, "{name}");
        assert_eq!(t.moment_arms["R_ankle_fe"].columns().len(), 7, "{name}");
        // The EMG starts 130 ms before the kinematics and ends after them.
        assert!(
            (t.lmt.start() - t.emg.start() - 0.13).abs() < 1e-9,
            "{name}"
        );
        assert!(t.emg.end() > t.lmt.end(), "{name}");
        // The stance phase: 0.356 s (CrossOvers7) to 0.712 s (FastWalking_).
        let duration = t.lmt.end() - t.lmt.start();
        assert!((0.35..0.72).contains(&duration), "{name}: {duration}");
        // Envelopes are never negative; lengths are positive and below 0.6 m.
        assert!(t.emg.column(0).is_some());
        for j in 0..16 {
            assert!(t.emg.column(j).unwrap().iter().all(|&v| v >= 0.0), "{name}");
        }
        for j in 0..34 {
            assert!(
                t.lmt.column(j).unwrap().iter().all(|&l| l > 0.0 && l < 0.6),
                "{name}"
            );
        }
    }
}

#[test]
fn fast_walking_s_first_and_last_values_are_the_file_s() {
    let t = trial("_FastWalking_");
    assert_eq!(
        (t.emg.rows(), t.emg.start(), t.emg.end()),
        (1739, 2.19, 3.059)
    );
    assert_eq!(
        (t.lmt.rows(), t.lmt.start(), t.lmt.end()),
        (179, 2.32, 3.032)
    );
    assert_eq!(t.emg.column_named("tibant_r").unwrap()[0], 0.298994);
    assert_eq!(t.emg.column_named("vasmed_r").unwrap()[1738], 0.003035);
    assert_eq!(t.lmt.column_named("addbrev_r").unwrap()[0], 0.137607387245);
    let ankle = &t.moment_arms["R_ankle_fe"];
    assert_eq!(ankle.column_named("gaslat_r").unwrap()[0], -0.0426035419759);
    assert_eq!(ankle.times(), t.lmt.times());
    let knee = t.moment("R_knee_fe").unwrap();
    assert_eq!((knee[0], knee[178]), (8.56730199053, -19.1374787041));
    assert_eq!(t.moments["R_knee_fe"].columns(), ["R_knee_fe"]);
}

#[test]
fn the_subject_has_34_units_and_their_parameters_in_si() {
    let s = subject();
    assert_eq!(s.units.len(), 34);
    let t = trial("_FastWalking_");
    let names: Vec<&str> = s.units.iter().map(|u| u.name.as_str()).collect();
    assert_eq!(t.lmt.columns(), names);
    assert_eq!(s.defaults.em_delay_s, 0.0);
    assert_eq!(s.defaults.percentage_change, 0.15);
    assert_eq!(s.defaults.damping, 0.1);
    let c = &s.defaults.curves;
    assert_eq!(
        (c.active_force_length.len(), c.passive_force_length.len()),
        (17, 13)
    );
    assert_eq!(c.force_velocity.len(), 11);
    assert_eq!(c.active_force_length.x()[0], -5.0);
    assert_eq!(c.force_velocity.y()[5], 1.0);
    let tendon = c.tendon_force_strain.as_ref().unwrap();
    assert_eq!(
        (tendon.len(), tendon.x()[12], tendon.y()[12]),
        (17, 0.0123, 0.227)
    );
    let u = s.unit("addlong_r").unwrap();
    assert_eq!(
        (u.c1, u.c2, u.shape_factor),
        (0.768956, -0.990048, 0.101198)
    );
    assert_eq!(u.optimal_fibre_length_m, 0.138);
    assert_eq!(u.pennation_angle_rad, 6f64.to_radians());
    assert_eq!(u.tendon_slack_length_m, 0.11);
    assert_eq!(u.max_isometric_force_n, 627.0);
    assert_eq!(u.strength_coefficient, 0.50001);
    assert_eq!((u.em_delay_s, s.em_delay_s(u)), (None, 0.0));
    let v = s.unit("vaslat_r").unwrap();
    assert_eq!(
        (v.max_isometric_force_n, v.pennation_angle_rad),
        (1871.0, 5f64.to_radians())
    );
    // The activation constants are shared, the shape factor positive (near-linear).
    assert!(s
        .units
        .iter()
        .all(|u| u.shape_factor == 0.101198 && u.c1 == 0.768956));
    assert_eq!(
        s.calibration,
        Calibration::Uncalibrated {
            subject_id: "testSubject00".into(),
            additional_info: "initial values computed with Wimby scale method #9".into()
        }
    );
}

#[test]
fn the_subject_s_degrees_of_freedom_are_the_trials_moment_arms() {
    let s = subject();
    let dofs: Vec<&str> = s.dofs.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(dofs, ["R_hip_aa", "R_hip_fe", "R_knee_fe", "R_ankle_fe"]);
    assert_eq!(s.dof("R_knee_fe").unwrap().units, KNEE_UNITS);
    for name in TRIALS {
        let t = trial(name);
        for dof in &s.dofs {
            assert_eq!(
                t.moment_arms[&dof.name].columns(),
                dof.units,
                "{name} {}",
                dof.name
            );
        }
    }
}

#[test]
fn the_excitation_map_covers_every_unit_of_the_subject() {
    let m = map();
    assert_eq!(m.channels, CHANNELS);
    let s = subject();
    let units: Vec<&str> = m.units.iter().map(|u| u.unit.as_str()).collect();
    let subject_units: Vec<&str> = s.units.iter().map(|u| u.name.as_str()).collect();
    assert_eq!(units, subject_units);
    assert_eq!(m.unit("illiacus_r"), Some(&Excitation::Zero));
    assert_eq!(m.unit("psoas_r"), Some(&Excitation::Zero));
    assert_eq!(
        m.unit("bicfemsh_r"),
        Some(&Excitation::Channel("bicfemlh_r".into()))
    );
    assert_eq!(m.unit("sol_r"), Some(&Excitation::Channel("sol_r".into())));
    assert_eq!(
        m.unit("gmin2_r"),
        Some(&Excitation::Mean(vec!["gmed_r".into(), "gmax_r".into()]))
    );
    let means = m
        .units
        .iter()
        .filter(|u| matches!(u.excitation, Excitation::Mean(_)))
        .count();
    assert_eq!(means, 4);
}

#[test]
fn a_mean_unit_s_excitation_is_the_mean_of_its_channels() {
    let t = trial("_FastWalking_");
    let e = map().excitations(&t.emg).unwrap();
    assert_eq!(e.columns().len(), 34);
    assert_eq!(e.times(), t.emg.times());
    // First row of emg.txt: vaslat_r 0.001654, vasmed_r 0.0016; gmed_r 0.010657, gmax_r 0.005468.
    let at = |unit: &str, row: usize| e.column_named(unit).unwrap()[row];
    assert_eq!(at("vasint_r", 0), (0.001654 + 0.0016) / 2.0);
    assert_eq!(at("gmin1_r", 0), (0.010657 + 0.005468) / 2.0);
    assert_eq!(at("addbrev_r", 0), 0.004982);
    assert_eq!(at("psoas_r", 0), 0.0);
    for row in [0, 800, 1738] {
        let channel = |c: &str| t.emg.column_named(c).unwrap()[row];
        let mean = (channel("vaslat_r") + channel("vasmed_r")) / 2.0;
        assert_eq!(at("vasint_r", row), mean);
        assert_eq!(at("semiten_r", row), channel("semimem_r"));
    }
}

#[test]
fn known_oddities_of_the_data_hold() {
    // The envelopes are normalised to a maximum voluntary contraction but not capped at 1.
    let t = trial("_CrossOvers7_");
    let max = (0..16)
        .flat_map(|j| t.emg.column(j).unwrap().iter().copied())
        .fold(f64::MIN, f64::max);
    assert_eq!(max, 1.372008);
    // CrossOvers6's inverse dynamics starts with a transient of thousands of N m.
    let t = trial("_CrossOvers6_");
    let hip_aa = t.moment("R_hip_aa").unwrap();
    assert_eq!(hip_aa[1], -7479.22167568);
    assert!(hip_aa[20..].iter().all(|m| m.abs() < 200.0));
}

#[test]
fn moment_arm_signs_say_which_way_each_moment_turns() {
    // (degree of freedom, unit, sign of its moment arm at every sample of every trial)
    let signs = [
        ("R_knee_fe", "vaslat_r", 1.0),
        ("R_knee_fe", "recfem_r", 1.0),
        ("R_knee_fe", "semimem_r", -1.0),
        ("R_knee_fe", "gasmed_r", -1.0),
        ("R_hip_fe", "psoas_r", 1.0),
        ("R_hip_fe", "gmax1_r", -1.0),
        ("R_hip_aa", "addlong_r", 1.0),
        ("R_hip_aa", "gmed1_r", -1.0),
        ("R_ankle_fe", "tibant_r", 1.0),
        ("R_ankle_fe", "sol_r", -1.0),
    ];
    for name in TRIALS {
        let t = trial(name);
        for (dof, unit, sign) in signs {
            let arms = t.moment_arms[dof].column_named(unit).unwrap();
            assert!(arms.iter().all(|r| r * sign > 0.0), "{name} {dof} {unit}");
        }
    }
    // The short head of biceps femoris, a knee flexor, turns positive near full extension.
    let t = trial("_FastWalking_");
    let bicfemsh = t.moment_arms["R_knee_fe"]
        .column_named("bicfemsh_r")
        .unwrap();
    let max = bicfemsh.iter().copied().fold(f64::MIN, f64::max);
    assert_eq!(max, 0.00592878443895);
}

/// `text` with the byte at a pseudo-random place replaced, inserted or removed, `n` times over
/// (a fixed sequence, so a failure repeats).
fn corruptions(text: &str, n: usize) -> impl Iterator<Item = String> + '_ {
    const BYTES: &[u8] = b"\t\n\r <>\"/x-0.9e";
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    (0..n).map(move |_| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let mut bytes = text.as_bytes().to_vec();
        let at = (state >> 33) as usize % bytes.len();
        let byte = BYTES[(state >> 20) as usize % BYTES.len()];
        match state % 3 {
            0 => bytes[at] = byte,
            1 => bytes.insert(at, byte),
            _ => {
                bytes.remove(at);
            }
        }
        String::from_utf8_lossy(&bytes).into_owned()
    })
}

#[test]
fn corrupted_files_give_errors_not_panics() {
    let read = |name: &str| std::fs::read_to_string(data().join(name)).unwrap();
    let lmt = read("_CrossOvers7_/R_knee_feMa.txt");
    let refused = corruptions(&lmt, 400)
        .filter(|t| Table::parse(t).is_err())
        .count();
    assert!(refused > 150, "{refused}");
    let subject = read("uncalibratedSubject.xml");
    let refused = corruptions(&subject, 400)
        .filter(|t| Subject::parse(t).is_err())
        .count();
    assert!(refused > 250, "{refused}");
    let map = read("emgGenerator-16To34.xml");
    let refused = corruptions(&map, 400)
        .filter(|t| ExcitationMap::parse(t).is_err())
        .count();
    assert!(refused > 200, "{refused}");
}
