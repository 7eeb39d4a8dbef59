//! CEINMS's subject file (`<subject>`, its schema data/ceinms/subject.xsd): the defaults shared
//! by the muscle–tendon units (`<mtuDefault>`: delay, the two fibre constants, the curves), each
//! unit's parameters (`<mtuSet>`), the degrees of freedom and the units that span each
//! (`<dofSet>`), and whether the file is calibrated (`<calibrationInfo>`).
//!
//! The meaning of each parameter is CEINMS's (the toolbox's lib/NMSmodel: MTU.cpp,
//! Activation/ExponentialActivation.cpp; Lloyd & Besier 2003, J Biomech 36(6): 765-776; Sartori,
//! Reggiani, Farina & Lloyd 2012, PLoS ONE 7(12): e52618). Values are read in the file's units
//! and stored in SI, the unit in each field's name; the pennation angle, in degrees in the file,
//! is stored in radians. Each value is checked finite and physically sensible
//! ([`SubjectError::OutOfRange`] says the rule), and every unit a degree of freedom names must be
//! in the set.

use crate::measured::curve::{Curve, CurveError};
use crate::measured::xml::{self, Element, XmlError};
use crate::measured::{read_bytes, shown, utf8_text, MeasuredError};
use muscle_actuator_core::text::excerpt;
use roxmltree::Node;
use std::path::Path;

/// A subject as CEINMS describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct Subject {
    /// What the units share (`<mtuDefault>`).
    pub defaults: UnitDefaults,
    /// The muscle–tendon units (`<mtuSet>`), in the file's order; names unique.
    pub units: Vec<Unit>,
    /// The degrees of freedom (`<dofSet>`), in the file's order; names unique.
    pub dofs: Vec<Dof>,
    /// Whether, and from what, the parameters were calibrated (`<calibrationInfo>`).
    pub calibration: Calibration,
}

/// What the units share (`<mtuDefault>`).
#[derive(Debug, Clone, PartialEq)]
pub struct UnitDefaults {
    /// Electromechanical delay, s (`emDelay`), for the units that give none; ≥ 0.
    pub em_delay_s: f64,
    /// Fractional change of the optimal fibre length with activation (`percentageChange`):
    /// CEINMS uses `l_opt · (percentageChange · (1 − a) + 1)` at activation `a`; in [0, 1).
    pub percentage_change: f64,
    /// The fibre's damping (`damping`), in maximum isometric forces per unit of CEINMS's
    /// normalised fibre velocity; ≥ 0.
    pub damping: f64,
    /// The curves.
    pub curves: SubjectCurves,
}

/// The curves the units share (`<curve>` in `<mtuDefault>`), each as points.
#[derive(Debug, Clone, PartialEq)]
pub struct SubjectCurves {
    /// `activeForceLength`: x fibre length / optimal fibre length, y active force / maximum
    /// isometric force.
    pub active_force_length: Curve,
    /// `passiveForceLength`: x fibre length / optimal fibre length, y passive force / maximum
    /// isometric force.
    pub passive_force_length: Curve,
    /// `forceVelocity`: x CEINMS's normalised fibre velocity (positive lengthening), y the
    /// force's multiplier.
    pub force_velocity: Curve,
    /// `tendonForceStrain`, if given (the schema makes every curve optional; CEINMS needs the
    /// other three): x tendon strain, y tendon force / maximum isometric force.
    pub tendon_force_strain: Option<Curve>,
}

/// One muscle–tendon unit (`<mtu>`).
#[derive(Debug, Clone, PartialEq)]
pub struct Unit {
    /// Its name (`name`).
    pub name: String,
    /// Its own electromechanical delay, s (`emDelay`, optional; ≥ 0); without it the defaults'
    /// ([`Subject::em_delay_s`]).
    pub em_delay_s: Option<f64>,
    /// The activation filter's first coefficient (`c1`), |c1| < 1: CEINMS's neural activation
    /// is `u(t) = α e(t − d) − β1 u(t − 1) − β2 u(t − 2)` with `β1 = c1 + c2`, `β2 = c1 c2`,
    /// `α = 1 + β1 + β2`, per EMG sample.
    pub c1: f64,
    /// The activation filter's second coefficient (`c2`), |c2| < 1.
    pub c2: f64,
    /// The shape factor A of activation from neural activation (`shapeFactor`),
    /// dimensionless: `a = (e^(A u) − 1) / (e^A − 1)`; any finite value.
    pub shape_factor: f64,
    /// Optimal fibre length, m (`optimalFibreLength`); > 0.
    pub optimal_fibre_length_m: f64,
    /// Pennation angle at optimal fibre length, rad (`pennationAngle`, degrees in the file);
    /// in [0, π/2).
    pub pennation_angle_rad: f64,
    /// Tendon slack length, m (`tendonSlackLength`); > 0.
    pub tendon_slack_length_m: f64,
    /// Maximum isometric force, N (`maxIsometricForce`); > 0.
    pub max_isometric_force_n: f64,
    /// Multiplies the maximum isometric force (`strengthCoefficient`), dimensionless; > 0.
    pub strength_coefficient: f64,
}

/// A degree of freedom and the units that span it (`<dof>`).
#[derive(Debug, Clone, PartialEq)]
pub struct Dof {
    /// Its name (`name`), as trials name their `<name>Ma.txt` and `<name>Torque.txt`.
    pub name: String,
    /// The units that span it (`mtuNameSet`), in the file's order: at least one, each once,
    /// each in the subject's units.
    pub units: Vec<String>,
}

/// Whether the parameters were calibrated (`<calibrationInfo>`).
#[derive(Debug, Clone, PartialEq)]
pub enum Calibration {
    /// Not calibrated (`<uncalibrated>`).
    Uncalibrated {
        /// `subjectID`.
        subject_id: String,
        /// `additionalInfo`.
        additional_info: String,
    },
    /// Calibrated (`<calibrated>`).
    Calibrated {
        /// The subject file calibration started from (`startSubjectFile`).
        start_subject_file: String,
        /// The calibration steps (`calibrationSequence`, a list of words).
        calibration_sequence: Vec<String>,
    },
}

impl Subject {
    /// Reads and checks the subject file `path` (a regular file of at most 1 MiB).
    pub fn read(path: &Path) -> Result<Subject, MeasuredError> {
        let error = |error| MeasuredError::Subject {
            path: shown(path),
            error,
        };
        let text = utf8_text(read_bytes(path, xml::MAX_XML_BYTES)?)
            .map_err(|line| error(XmlError::NotText { line }.into()))?;
        Subject::parse(&text).map_err(error)
    }

    /// Parses and checks a subject file's text.
    pub fn parse(text: &str) -> Result<Subject, SubjectError> {
        let doc = xml::parse(text)?;
        let root = xml::root(&doc, "subject")?;
        let subject = Element::new(
            root,
            "subject".into(),
            &["mtuDefault", "mtuSet", "dofSet", "calibrationInfo"],
        )?;
        let defaults = defaults(subject.required("mtuDefault")?)?;
        let units = units(subject.required("mtuSet")?)?;
        let dofs = dofs(subject.required("dofSet")?, &units)?;
        let calibration = calibration(subject.required("calibrationInfo")?)?;
        Ok(Subject {
            defaults,
            units,
            dofs,
            calibration,
        })
    }

    /// The unit named `name`.
    pub fn unit(&self, name: &str) -> Option<&Unit> {
        self.units.iter().find(|u| u.name == name)
    }

    /// The degree of freedom named `name`.
    pub fn dof(&self, name: &str) -> Option<&Dof> {
        self.dofs.iter().find(|d| d.name == name)
    }

    /// `unit`'s electromechanical delay, s: its own, else the defaults'.
    pub fn em_delay_s(&self, unit: &Unit) -> f64 {
        unit.em_delay_s.unwrap_or(self.defaults.em_delay_s)
    }
}

/// What a parameter must be.
#[derive(Debug, Clone, Copy)]
enum Rule {
    /// > 0.
    Positive,
    /// ≥ 0.
    NonNegative,
    /// In [0, 1).
    Fraction,
    /// In (−1, 1).
    InsideUnit,
    /// In [0, 90) degrees.
    PennationDegrees,
}

impl Rule {
    fn holds(self, v: f64) -> bool {
        match self {
            Rule::Positive => v > 0.0,
            Rule::NonNegative => v >= 0.0,
            Rule::Fraction => (0.0..1.0).contains(&v),
            Rule::InsideUnit => v.abs() < 1.0,
            Rule::PennationDegrees => (0.0..90.0).contains(&v),
        }
    }

    fn text(self) -> &'static str {
        match self {
            Rule::Positive => "above 0",
            Rule::NonNegative => "0 or more",
            Rule::Fraction => "in [0, 1)",
            Rule::InsideUnit => "in (-1, 1)",
            Rule::PennationDegrees => "in [0, 90) degrees",
        }
    }
}

/// The number in `el`'s child `name`, which must follow `rule`.
fn checked(el: &Element, name: &'static str, rule: Rule) -> Result<f64, SubjectError> {
    let value = el.number(name)?;
    follows(el, name, value, rule)?;
    Ok(value)
}

/// `value` of `el`'s child `name` follows `rule`, or the error saying so.
fn follows(el: &Element, name: &'static str, value: f64, rule: Rule) -> Result<(), SubjectError> {
    if rule.holds(value) {
        return Ok(());
    }
    let line = el
        .optional(name)
        .ok()
        .flatten()
        .map_or(xml::line(el.node), xml::line);
    Err(SubjectError::OutOfRange {
        line,
        within: el.within.clone(),
        element: name,
        value,
        rule: rule.text(),
    })
}

/// `<mtuDefault>`.
fn defaults(node: Node) -> Result<UnitDefaults, SubjectError> {
    let el = Element::new(
        node,
        "mtuDefault".into(),
        &["emDelay", "percentageChange", "damping", "curve"],
    )?;
    Ok(UnitDefaults {
        em_delay_s: checked(&el, "emDelay", Rule::NonNegative)?,
        percentage_change: checked(&el, "percentageChange", Rule::Fraction)?,
        damping: checked(&el, "damping", Rule::NonNegative)?,
        curves: curves(&el)?,
    })
}

/// The curves' names, in [`SubjectCurves`]' order.
const CURVES: [&str; 4] = [
    "activeForceLength",
    "passiveForceLength",
    "forceVelocity",
    "tendonForceStrain",
];

/// The `<curve>`s of `<mtuDefault>`: each name once, the first three required.
fn curves(el: &Element) -> Result<SubjectCurves, SubjectError> {
    let mut found: [Option<Curve>; 4] = Default::default();
    for node in el.all("curve") {
        let (name, curve) = curve(node)?;
        let line = xml::line(node);
        let slot =
            CURVES
                .iter()
                .position(|c| *c == name)
                .ok_or_else(|| SubjectError::UnknownCurve {
                    line,
                    name: name.clone(),
                })?;
        if found[slot].is_some() {
            return Err(SubjectError::DuplicateCurve { line, name });
        }
        found[slot] = Some(curve);
    }
    let [active, passive, velocity, tendon] = found;
    let required = |curve: Option<Curve>, name: &'static str| {
        curve.ok_or(SubjectError::MissingCurve {
            line: xml::line(el.node),
            name,
        })
    };
    Ok(SubjectCurves {
        active_force_length: required(active, CURVES[0])?,
        passive_force_length: required(passive, CURVES[1])?,
        force_velocity: required(velocity, CURVES[2])?,
        tendon_force_strain: tendon,
    })
}

/// One `<curve>`: its name and points.
fn curve(node: Node) -> Result<(String, Curve), SubjectError> {
    let el = Element::new(node, "curve".into(), &["name", "xPoints", "yPoints"])?;
    let name = el.name("name")?;
    let el = el.named(format!("curve {:?}", excerpt(&name)));
    let x = xml::numbers(el.required("xPoints")?, &el.within)?;
    let y = xml::numbers(el.required("yPoints")?, &el.within)?;
    let curve = Curve::new(x, y).map_err(|error| SubjectError::Curve {
        line: xml::line(node),
        name: name.clone(),
        error,
    })?;
    Ok((name, curve))
}

/// `<mtuSet>`: at least one unit, names unique.
fn units(node: Node) -> Result<Vec<Unit>, SubjectError> {
    let el = Element::new(node, "mtuSet".into(), &["mtu"])?;
    let mut units: Vec<Unit> = Vec::new();
    for node in el.all("mtu") {
        let unit = unit(node)?;
        if units.iter().any(|u| u.name == unit.name) {
            return Err(SubjectError::DuplicateUnit {
                line: xml::line(node),
                name: unit.name,
            });
        }
        units.push(unit);
    }
    if units.is_empty() {
        return Err(XmlError::Missing {
            line: xml::line(node),
            within: "mtuSet".into(),
            element: "mtu",
        }
        .into());
    }
    Ok(units)
}

/// One `<mtu>`.
fn unit(node: Node) -> Result<Unit, SubjectError> {
    let el = Element::new(
        node,
        "mtu".into(),
        &[
            "name",
            "emDelay",
            "c1",
            "c2",
            "shapeFactor",
            "optimalFibreLength",
            "pennationAngle",
            "tendonSlackLength",
            "maxIsometricForce",
            "strengthCoefficient",
        ],
    )?;
    let name = el.name("name")?;
    let el = el.named(format!("mtu {:?}", excerpt(&name)));
    let em_delay_s = el.optional_number("emDelay")?;
    if let Some(delay) = em_delay_s {
        follows(&el, "emDelay", delay, Rule::NonNegative)?;
    }
    Ok(Unit {
        em_delay_s,
        c1: checked(&el, "c1", Rule::InsideUnit)?,
        c2: checked(&el, "c2", Rule::InsideUnit)?,
        shape_factor: el.number("shapeFactor")?,
        optimal_fibre_length_m: checked(&el, "optimalFibreLength", Rule::Positive)?,
        pennation_angle_rad: checked(&el, "pennationAngle", Rule::PennationDegrees)?.to_radians(),
        tendon_slack_length_m: checked(&el, "tendonSlackLength", Rule::Positive)?,
        max_isometric_force_n: checked(&el, "maxIsometricForce", Rule::Positive)?,
        strength_coefficient: checked(&el, "strengthCoefficient", Rule::Positive)?,
        name,
    })
}

/// `<dofSet>`: at least one degree of freedom, names unique, each with units of `units`.
fn dofs(node: Node, units: &[Unit]) -> Result<Vec<Dof>, SubjectError> {
    let el = Element::new(node, "dofSet".into(), &["dof"])?;
    let mut dofs: Vec<Dof> = Vec::new();
    for node in el.all("dof") {
        let dof = dof(node, units)?;
        if dofs.iter().any(|d| d.name == dof.name) {
            return Err(SubjectError::DuplicateDof {
                line: xml::line(node),
                dof: dof.name,
            });
        }
        dofs.push(dof);
    }
    if dofs.is_empty() {
        return Err(XmlError::Missing {
            line: xml::line(node),
            within: "dofSet".into(),
            element: "dof",
        }
        .into());
    }
    Ok(dofs)
}

/// One `<dof>`: its units at least one, each once, each in `units`.
fn dof(node: Node, units: &[Unit]) -> Result<Dof, SubjectError> {
    let el = Element::new(node, "dof".into(), &["name", "mtuNameSet"])?;
    let name = el.name("name")?;
    let set = el.required("mtuNameSet")?;
    let line = xml::line(set);
    let names = xml::words(set, &format!("dof {:?}", excerpt(&name)))?;
    if names.is_empty() {
        return Err(SubjectError::EmptyDof { line, dof: name });
    }
    for (i, unit) in names.iter().enumerate() {
        let (dof, unit) = (name.clone(), unit.clone());
        if names[..i].contains(&unit) {
            return Err(SubjectError::RepeatedUnit { line, dof, unit });
        }
        if !units.iter().any(|u| u.name == unit) {
            return Err(SubjectError::UnknownUnit { line, dof, unit });
        }
    }
    Ok(Dof { name, units: names })
}

/// `<calibrationInfo>`: `<uncalibrated>` or `<calibrated>`.
fn calibration(node: Node) -> Result<Calibration, SubjectError> {
    let el = Element::new(
        node,
        "calibrationInfo".into(),
        &["uncalibrated", "calibrated"],
    )?;
    let (uncalibrated, calibrated) = (el.optional("uncalibrated")?, el.optional("calibrated")?);
    match (uncalibrated, calibrated) {
        (Some(node), None) => {
            let el = Element::new(
                node,
                "uncalibrated".into(),
                &["subjectID", "additionalInfo"],
            )?;
            Ok(Calibration::Uncalibrated {
                subject_id: xml::value(el.required("subjectID")?, &el.within)?,
                additional_info: xml::value(el.required("additionalInfo")?, &el.within)?,
            })
        }
        (None, Some(node)) => {
            let el = Element::new(
                node,
                "calibrated".into(),
                &["startSubjectFile", "calibrationSequence"],
            )?;
            Ok(Calibration::Calibrated {
                start_subject_file: xml::value(el.required("startSubjectFile")?, &el.within)?,
                calibration_sequence: xml::words(el.required("calibrationSequence")?, &el.within)?,
            })
        }
        _ => Err(SubjectError::Calibration {
            line: xml::line(node),
        }),
    }
}

/// What is wrong with a subject file; lines count from 1.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SubjectError {
    /// Not well-formed, or not of the schema's shape.
    #[error(transparent)]
    Xml(#[from] XmlError),
    /// A parameter outside its physically sensible range.
    #[error("line {line}: {within}: <{element}> = {value}, must be {rule}")]
    OutOfRange {
        /// The value's line.
        line: usize,
        /// Its element's parent (`mtuDefault`, `mtu "addbrev_r"`).
        within: String,
        /// Its element.
        element: &'static str,
        /// The value, in the file's unit.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },
    /// A curve's points do not make a curve.
    #[error("line {line}: curve {:?}: {error}", excerpt(.name))]
    Curve {
        /// The curve's line.
        line: usize,
        /// Its name.
        name: String,
        /// What is wrong.
        error: CurveError,
    },
    /// A curve of another name than the four CEINMS knows.
    #[error(
        "line {line}: mtuDefault: unknown curve {:?} (expected activeForceLength, \
         passiveForceLength, forceVelocity or tendonForceStrain)",
        excerpt(.name)
    )]
    UnknownCurve {
        /// The curve's line.
        line: usize,
        /// Its name.
        name: String,
    },
    /// A curve given twice.
    #[error("line {line}: mtuDefault: a second curve {:?}", excerpt(.name))]
    DuplicateCurve {
        /// The second one's line.
        line: usize,
        /// Its name.
        name: String,
    },
    /// A curve CEINMS needs is missing.
    #[error("line {line}: mtuDefault: no curve {name}")]
    MissingCurve {
        /// `<mtuDefault>`'s line.
        line: usize,
        /// The curve's name.
        name: &'static str,
    },
    /// Two units of one name.
    #[error("line {line}: mtuSet: a second mtu named {:?}", excerpt(.name))]
    DuplicateUnit {
        /// The second one's line.
        line: usize,
        /// The name.
        name: String,
    },
    /// Two degrees of freedom of one name.
    #[error("line {line}: dofSet: a second dof named {:?}", excerpt(.dof))]
    DuplicateDof {
        /// The second one's line.
        line: usize,
        /// The name.
        dof: String,
    },
    /// A degree of freedom without units.
    #[error("line {line}: dof {:?}: no unit in <mtuNameSet>", excerpt(.dof))]
    EmptyDof {
        /// The `<mtuNameSet>`'s line.
        line: usize,
        /// The degree of freedom.
        dof: String,
    },
    /// A degree of freedom names a unit that is not in `<mtuSet>`.
    #[error("line {line}: dof {:?}: unit {:?} is not in <mtuSet>", excerpt(.dof), excerpt(.unit))]
    UnknownUnit {
        /// The `<mtuNameSet>`'s line.
        line: usize,
        /// The degree of freedom.
        dof: String,
        /// The unit.
        unit: String,
    },
    /// A degree of freedom names a unit twice.
    #[error("line {line}: dof {:?}: unit {:?} is named twice", excerpt(.dof), excerpt(.unit))]
    RepeatedUnit {
        /// The `<mtuNameSet>`'s line.
        line: usize,
        /// The degree of freedom.
        dof: String,
        /// The unit.
        unit: String,
    },
    /// `<calibrationInfo>` holds neither or both of `<uncalibrated>` and `<calibrated>`.
    #[error("line {line}: calibrationInfo: expected one of <uncalibrated> and <calibrated>")]
    Calibration {
        /// `<calibrationInfo>`'s line.
        line: usize,
    },
}

#[cfg(test)]
mod tests;
