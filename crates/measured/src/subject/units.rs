//! A CEINMS subject's units as the project's muscles (docs/emg.md "Subjects"): per unit its
//! [`MuscleParams`], the degrees of freedom and the units that span each.
//!
//! The mapping (CEINMS's lib/NMSmodel MTU.cpp; Lloyd & Besier 2003):
//! - maximum isometric force `f_max` = `maxIsometricForce · strengthCoefficient`;
//! - `l_opt`, `l_ts`, `pennation` as given;
//! - `v_max = 10 l_opt` per second: CEINMS normalises the fibre velocity by ten optimal lengths
//!   per second, the abscissa of its force–velocity curve;
//! - the four curves as `curves = "tabulated"` (docs/model.md §4b), interpolated as CEINMS
//!   interpolates them;
//! - an equilibrium (massless) fibre on an elastic tendon, CEINMS's elastic-tendon unit;
//! - CEINMS's fibre damping d (maximum isometric forces per unit of normalised velocity) as
//!   the parallel damping `b_m = d · f_max / v_max`, N s/m;
//! - Lloyd & Besier's activation with the unit's C1, C2, shape factor A and delay, C1 and C2
//!   belonging to the EMG's sample period (the tick of a drive, [`crate::subject::drive`]).
//!
//! - CEINMS's activation-dependent optimal fibre length (`percentageChange`) as
//!   `optimal_length_shift`.

use crate::measured::{Subject, Unit};
use crate::subject::bounds::Bounds;
use crate::subject::calibration_record::CalibrationRecord;
use crate::subject::error::DriveError;
use muscle_actuator_core::config::{ActuatorConfig, ConfigError, MuscleConfig, SpanConfig};
use muscle_actuator_core::physics::curves::CurveSet;
use muscle_actuator_core::physics::{
    ActivationKind, FibreKind, JointParams, MomentArm, MuscleParams, TabulatedCurves, TendonKind,
};
use muscle_actuator_core::text::excerpt;

/// CEINMS's maximum contraction velocity, optimal fibre lengths per second.
pub(crate) const MAX_VELOCITY_LOPT_PER_S: f64 = 10.0;

/// A subject as the project models it: its units' parameters and its degrees of freedom.
#[derive(Debug, Clone, PartialEq)]
pub struct SubjectModel {
    /// The subject's name (CEINMS's `subjectID`, or the file's).
    pub id: String,
    /// The units, in the subject's order.
    pub units: Vec<UnitModel>,
    /// Per degree of freedom its name and the units that span it, by name.
    pub dofs: Vec<(String, Vec<String>)>,
    /// How it was calibrated, if it was (`crate::subject::calibrate`).
    pub calibration: Option<CalibrationRecord>,
    /// The bounds a calibration keeps its parameters within.
    pub bounds: Bounds,
}

/// One muscle–tendon unit: its name and its muscle's parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitModel {
    /// The unit's name, as the trials' `lmt.txt` and `<dof>Ma.txt` name its columns.
    pub name: String,
    /// Its parameters.
    pub params: MuscleParams,
}

impl SubjectModel {
    /// The project's model of a CEINMS subject (the module's mapping); refused when the
    /// subject gives no tendon force–strain curve (an elastic tendon needs one).
    pub fn of_ceinms(subject: &Subject) -> Result<SubjectModel, NoTendonCurve> {
        if subject.defaults.curves.tendon_force_strain.is_none() {
            return Err(NoTendonCurve);
        }
        let id = match &subject.calibration {
            crate::measured::Calibration::Uncalibrated { subject_id, .. } => subject_id.clone(),
            crate::measured::Calibration::Calibrated {
                start_subject_file, ..
            } => start_subject_file.clone(),
        };
        Ok(SubjectModel {
            id,
            units: subject
                .units
                .iter()
                .map(|u| {
                    Ok(UnitModel {
                        name: u.name.clone(),
                        params: unit_params(subject, u).ok_or(NoTendonCurve)?,
                    })
                })
                .collect::<Result<_, _>>()?,
            dofs: subject
                .dofs
                .iter()
                .map(|d| (d.name.clone(), d.units.clone()))
                .collect(),
            calibration: None,
            bounds: Bounds::default(),
        })
    }

    /// Each unit's parameters checked by a configuration's rules (docs/configuration.md): the
    /// first broken rule, if any.
    pub(crate) fn check(&self) -> Result<(), String> {
        self.bounds.check()?;
        let mut cfg = ActuatorConfig {
            joints: vec![JointParams {
                name: "check".into(),
                // The other fields of a joint no unit's check reads.
                ..JointParams::default()
            }],
            muscles: Vec::with_capacity(self.units.len()),
            stepper: Default::default(),
        };
        for u in &self.units {
            cfg.muscles.push(MuscleConfig {
                name: u.name.clone(),
                params: u.params.clone(),
                path_length: None,
                spans: vec![SpanConfig {
                    joint: "check".into(),
                    moment_arm: MomentArm::Constant(0.01),
                    changes_sign: false,
                }],
            });
        }
        match cfg.validate() {
            Err(ConfigError::Invalid(errors)) => {
                Err(errors.first().map_or_else(String::new, ToString::to_string))
            }
            Err(other) => Err(other.to_string()),
            Ok(()) => Ok(()),
        }
    }

    /// The parameters of the units named `units`, in their order (the prepared trial's
    /// units, `crate::subject::PreparedTrial::units`); the first one the subject lacks refused.
    pub fn params_of(&self, units: &[String]) -> Result<Vec<MuscleParams>, DriveError> {
        units
            .iter()
            .map(|u| {
                self.unit(u)
                    .map(|m| m.params.clone())
                    .ok_or_else(|| DriveError::UnitNotInSubject(excerpt(u)))
            })
            .collect()
    }

    /// The unit named `name`.
    pub fn unit(&self, name: &str) -> Option<&UnitModel> {
        self.units.iter().find(|u| u.name == name)
    }

    /// The units that span `dof`, by name; None for a degree of freedom it does not have.
    pub(crate) fn dof_units(&self, dof: &str) -> Option<&[String]> {
        self.dofs
            .iter()
            .find(|(d, _)| d == dof)
            .map(|(_, u)| u.as_slice())
    }
}

/// A subject without a `tendonForceStrain` curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error(
    "the subject gives no tendonForceStrain curve in <mtuDefault>, which an elastic tendon needs"
)]
pub struct NoTendonCurve;

/// The parameters of `unit` of `subject` (the module's mapping); `None` when the subject gives
/// no tendon curve.
pub(crate) fn unit_params(subject: &Subject, unit: &Unit) -> Option<MuscleParams> {
    let d = &subject.defaults;
    let f_max = unit.max_isometric_force_n * unit.strength_coefficient;
    let v_max = MAX_VELOCITY_LOPT_PER_S * unit.optimal_fibre_length_m;
    let tendon = d.curves.tendon_force_strain.as_ref()?;
    // The engine's own values for what the subject does not give (its fixed constants, e.g.
    // the linear parts' turning forces, are not settable from outside the engine).
    let mut p = MuscleParams::default();
    p.f_max = f_max;
    p.l_opt = unit.optimal_fibre_length_m;
    p.v_max = v_max;
    p.l_ts = unit.tendon_slack_length_m;
    p.pennation = unit.pennation_angle_rad;
    p.optimal_length_shift = (d.percentage_change > 0.0).then_some(d.percentage_change);
    p.b_m = d.damping * f_max / v_max;
    p.curves = CurveSet::Tabulated;
    p.tabulated = Some(TabulatedCurves {
        active_force_length: d.curves.active_force_length.points(),
        passive_force_length: d.curves.passive_force_length.points(),
        force_velocity: d.curves.force_velocity.points(),
        tendon_force_strain: tendon.points(),
    });
    p.fibre = FibreKind::Equilibrium;
    p.tendon = TendonKind::Elastic;
    p.activation = ActivationKind::LloydBesier;
    p.c1 = Some(unit.c1);
    p.c2 = Some(unit.c2);
    p.shape_factor = Some(unit.shape_factor);
    p.em_delay = Some(subject.em_delay_s(unit));
    p.neural_rate_hz = None;
    Some(p)
}
