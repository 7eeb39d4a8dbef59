//! A trial made ready to drive (docs/emg.md "Prediction"): the units of the asked degrees of
//! freedom, each one's excitation and length per tick on the EMG's time base
//! ([`crate::subject::drive`]), the moment arms and the measured moments at the kinematic
//! samples; every input checked.

use super::drive::PreparedTrial;
use super::error::DriveError;
use super::limits::EMG_STEP_TOLERANCE;
use crate::measured::resample::{self, ResampleError};
use crate::measured::{ExcitationMap, Trial};
use crate::subject::units::SubjectModel;
use muscle_actuator_core::text::excerpt;

impl PreparedTrial {
    /// The inputs of `trial` for the units of `dofs` of `subject`, excited through `map`.
    pub fn new(
        subject: &SubjectModel,
        map: &ExcitationMap,
        trial: &Trial,
        dofs: &[String],
    ) -> Result<PreparedTrial, DriveError> {
        let name = trial.name.clone();
        if dofs.is_empty() {
            return Err(DriveError::NoDof);
        }
        let resample_error = |error| DriveError::Resample {
            trial: name.clone(),
            error,
        };
        let units = units_of(subject, map, trial, dofs)?;
        let rate_hz = emg_rate(trial)?;
        let emg_times = trial.emg.times();
        let (start_s, lmt_times) = (emg_times[0], trial.lmt.times());
        let (lmt_start, lmt_end) = (trial.lmt.start(), trial.lmt.end());
        if lmt_start < start_s || lmt_end > trial.emg.end() {
            return Err(DriveError::KinematicsOutsideEmg {
                trial: name,
                lmt_start,
                lmt_end,
                emg_start: start_s,
                emg_end: trial.emg.end(),
            });
        }
        // The ticks cover [start, lmt_end]; the last tick ends at or just after lmt_end.
        let ticks = ((lmt_end - start_s) * rate_hz - 1e-6).ceil().max(1.0) as usize;
        let tick_times: Vec<f64> = (0..=ticks).map(|k| start_s + k as f64 / rate_hz).collect();
        let held: Vec<f64> = tick_times
            .iter()
            .map(|&t| t.clamp(lmt_start, lmt_end))
            .collect();
        let excitations = map
            .excitations(&trial.emg)
            .map_err(|error| DriveError::Map {
                trial: name.clone(),
                error,
            })?;
        let mut clamped_excitations = 0;
        let mut excitation = Vec::with_capacity(units.len());
        let mut length = Vec::with_capacity(units.len());
        for u in &units {
            let column = excitations.column_named(u).unwrap_or(&[]);
            let (e, clamped) = excitation_of(&name, u, column, &tick_times[..ticks])?;
            clamped_excitations += clamped;
            excitation.push(e);
            length.push(resample::unit_length(trial, u, &held).map_err(resample_error)?);
        }
        let (arms, measured) = arms_of(subject, trial, dofs, &units)?;
        let unused_arms = unused_arms(subject, trial, dofs);
        Ok(PreparedTrial {
            name,
            rate_hz,
            start_s,
            units,
            excitation,
            length,
            clamped_excitations,
            times: lmt_times.to_vec(),
            dofs: dofs.to_vec(),
            arms,
            measured,
            unused_arms,
        })
    }
}

/// Per degree of freedom, the columns of its moment-arm file with a moment arm somewhere
/// (above 1 µm) whose unit the subject does not give that degree of freedom.
fn unused_arms(
    subject: &SubjectModel,
    trial: &Trial,
    dofs: &[String],
) -> Vec<(String, Vec<String>)> {
    let mut unused = Vec::new();
    for dof in dofs {
        let (Some(table), Some(spanning)) = (trial.moment_arms.get(dof), subject.dof_units(dof))
        else {
            continue;
        };
        let units: Vec<String> = (table.columns().iter().enumerate())
            .filter(|(_, u)| !spanning.contains(u))
            .filter(|(k, _)| {
                table
                    .column(*k)
                    .is_some_and(|c| c.iter().any(|r| r.abs() > 1e-6))
            })
            .map(|(_, u)| u.clone())
            .collect();
        if !units.is_empty() {
            unused.push((dof.clone(), units));
        }
    }
    unused
}

/// The units that span `dofs`, in the subject's order, each one in the subject, the map and the
/// trial's lengths.
fn units_of(
    subject: &SubjectModel,
    map: &ExcitationMap,
    trial: &Trial,
    dofs: &[String],
) -> Result<Vec<String>, DriveError> {
    let mut units: Vec<String> = Vec::new();
    for dof in dofs {
        let spanning = subject
            .dof_units(dof)
            .ok_or_else(|| DriveError::DofNotInSubject {
                dof: excerpt(dof),
                known: known(subject.dofs.iter().map(|(d, _)| d.as_str())),
            })?;
        for u in spanning {
            if !units.contains(u) {
                units.push(u.clone());
            }
        }
    }
    // In the subject's order.
    units.sort_by_key(|u| subject.units.iter().position(|m| &m.name == u));
    for u in &units {
        if subject.unit(u).is_none() {
            return Err(DriveError::UnitNotInSubject(excerpt(u)));
        }
        if map.unit(u).is_none() {
            return Err(DriveError::UnitNotInMap(excerpt(u)));
        }
        if trial.lmt.column_index(u).is_none() {
            return Err(DriveError::UnitNotInTrial {
                trial: trial.name.clone(),
                file: "lmt.txt".into(),
                unit: excerpt(u),
            });
        }
    }
    Ok(units)
}

/// A unit's excitation at each tick (EMG row k at tick k) from its map column, clamped to at
/// most 1, and how many samples were clamped; a negative sample refused.
fn excitation_of(
    trial: &str,
    unit: &str,
    column: &[f64],
    tick_times: &[f64],
) -> Result<(Vec<f64>, usize), DriveError> {
    let mut clamped = 0;
    let mut e = Vec::with_capacity(tick_times.len());
    for (k, &time_s) in tick_times.iter().enumerate() {
        let v = column.get(k).copied().unwrap_or(0.0);
        if v < 0.0 {
            return Err(DriveError::NegativeExcitation {
                trial: trial.to_string(),
                unit: excerpt(unit),
                time_s,
                value: v,
            });
        }
        if v > 1.0 {
            clamped += 1;
        }
        e.push(v.min(1.0));
    }
    Ok((e, clamped))
}

/// Per degree of freedom, its units' moment arms (index into `units`, arm per kinematic
/// sample) and its measured moment.
#[allow(clippy::type_complexity)]
fn arms_of(
    subject: &SubjectModel,
    trial: &Trial,
    dofs: &[String],
    units: &[String],
) -> Result<(Vec<Vec<(usize, Vec<f64>)>>, Vec<Vec<f64>>), DriveError> {
    let name = &trial.name;
    let mut arms = Vec::with_capacity(dofs.len());
    let mut measured = Vec::with_capacity(dofs.len());
    for dof in dofs {
        let (Some(table), Some(moment)) = (trial.moment_arms.get(dof), trial.moment(dof)) else {
            return Err(DriveError::DofNotInTrial {
                trial: name.clone(),
                dof: excerpt(dof),
                known: known(trial.dofs()),
            });
        };
        let mut of_dof = Vec::new();
        for u in subject.dof_units(dof).unwrap_or(&[]) {
            let column = table
                .column_named(u)
                .ok_or_else(|| DriveError::UnitNotInTrial {
                    trial: name.clone(),
                    file: format!("{}Ma.txt", excerpt(dof)),
                    unit: excerpt(u),
                })?;
            let index = units.iter().position(|x| x == u).unwrap_or(0);
            of_dof.push((index, column.to_vec()));
        }
        arms.push(of_dof);
        measured.push(moment.to_vec());
    }
    Ok((arms, measured))
}

/// The EMG's sample rate, Hz, from its times (evenly spaced within
/// [`EMG_STEP_TOLERANCE`]).
fn emg_rate(trial: &Trial) -> Result<f64, DriveError> {
    let t = trial.emg.times();
    if t.len() < 2 {
        return Err(DriveError::Resample {
            trial: trial.name.clone(),
            error: ResampleError::TooFewSamples {
                found: t.len(),
                needed: 2,
            },
        });
    }
    let mean = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    for (row, w) in t.windows(2).enumerate() {
        let step = w[1] - w[0];
        if ((step - mean) / mean).abs() > EMG_STEP_TOLERANCE {
            return Err(DriveError::UnevenEmg {
                trial: trial.name.clone(),
                row: row + 2,
                step_s: step,
                mean_s: mean,
            });
        }
    }
    Ok(1.0 / mean)
}

/// Names as an error lists the valid ones: each an excerpt, joined by ", " ("none" when empty).
fn known<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<String> = names.map(excerpt).collect();
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}
