//! How the recorded EMG channels drive the muscle–tendon units: CEINMS's `emgGenerator` file
//! (the toolbox's lib/FileIO/EMGgenerator/EMGgeneratorFromXml.cpp reads it; its schema is
//! TestCfg/emgGenerator.xsd there):
//!
//! ```xml
//! <emgGenerator>
//!   <experimental> <emg id="gmax_r"/> <emg id="gmed_r"/> </experimental>
//!   <mapping>
//!     <emg id="gmax1_r" operation="assign"> gmax_r </emg>
//!     <emg id="gmin1_r" operation="mean"> gmed_r gmax_r </emg>
//!     <emg id="psoas_r" operation="nil"/>
//!   </mapping>
//!   <output> gmax1_r gmin1_r psoas_r gmed_r </output>
//! </emgGenerator>
//! ```
//!
//! `<experimental>` declares the channels, `<output>` the units in order; a unit is driven as
//! its `<mapping>` entry says (`assign` one channel, `mean` or `sum` of channels, `nil` none:
//! zero), else by the channel of its own name. CEINMS makes any other operation, and a unit
//! with neither, a silent zero; here they are refused, as are unknown channels, entries for
//! units `<output>` lacks, and names given twice.

use crate::measured::table::Table;
use crate::measured::xml::{self, Element, XmlError};
use crate::measured::{read_bytes, shown, utf8_text, MeasuredError};
use muscle_actuator_core::text::excerpt;
use roxmltree::Node;
use std::path::Path;

/// Most units a map may drive.
pub(crate) const MAX_UNITS: usize = 2000;

/// The channels and, per unit, where its excitation comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct ExcitationMap {
    /// The recorded channels (`<experimental>`), in the file's order; names unique.
    pub channels: Vec<String>,
    /// The units (`<output>`), in its order; names unique.
    pub units: Vec<UnitExcitation>,
}

/// A unit and where its excitation comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitExcitation {
    /// The unit.
    pub unit: String,
    /// Its excitation.
    pub excitation: Excitation,
}

/// Where a unit's excitation comes from; every channel named is one of the map's.
#[derive(Debug, Clone, PartialEq)]
pub enum Excitation {
    /// One channel as it is (`assign`, or the channel of the unit's own name).
    Channel(String),
    /// The mean of channels (`mean`), each once.
    Mean(Vec<String>),
    /// The sum of channels (`sum`), each once.
    Sum(Vec<String>),
    /// No channel: zero (`nil`).
    Zero,
}

impl Excitation {
    /// The channels it reads.
    pub(crate) fn channels(&self) -> &[String] {
        match self {
            Excitation::Channel(c) => std::slice::from_ref(c),
            Excitation::Mean(c) | Excitation::Sum(c) => c,
            Excitation::Zero => &[],
        }
    }
}

impl ExcitationMap {
    /// Reads and checks the map in `path` (a regular file of at most 1 MiB).
    pub fn read(path: &Path) -> Result<ExcitationMap, MeasuredError> {
        let error = |error| MeasuredError::ExcitationMap {
            path: shown(path),
            error,
        };
        let text = utf8_text(read_bytes(path, xml::MAX_XML_BYTES)?)
            .map_err(|line| error(XmlError::NotText { line }.into()))?;
        ExcitationMap::parse(&text).map_err(error)
    }

    /// Parses and checks a map's text.
    pub fn parse(text: &str) -> Result<ExcitationMap, ExcitationMapError> {
        let doc = xml::parse(text)?;
        let root = xml::root(&doc, "emgGenerator")?;
        let el = Element::new(
            root,
            "emgGenerator".into(),
            &["experimental", "mapping", "output"],
        )?;
        let channels = channels(el.required("experimental")?)?;
        let output = el.required("output")?;
        let outputs = outputs(output)?;
        let mut mapped = mapping(el.required("mapping")?, &channels, &outputs)?;
        let mut units = Vec::with_capacity(outputs.len());
        for unit in outputs {
            let excitation = match mapped.iter().position(|(u, _)| *u == unit) {
                Some(i) => mapped.swap_remove(i).1,
                None if channels.contains(&unit) => Excitation::Channel(unit.clone()),
                None => {
                    return Err(ExcitationMapError::NoSource {
                        line: xml::line(output),
                        unit,
                    })
                }
            };
            units.push(UnitExcitation { unit, excitation });
        }
        Ok(ExcitationMap { channels, units })
    }

    /// The unit named `unit`'s excitation.
    pub fn unit(&self, unit: &str) -> Option<&Excitation> {
        self.units
            .iter()
            .find(|u| u.unit == unit)
            .map(|u| &u.excitation)
    }

    /// The units' excitations from the channel table `emg` (its columns named as the map's
    /// channels, in any order): a table of one column per unit, in the map's order, at `emg`'s
    /// times.
    pub fn excitations(&self, emg: &Table) -> Result<Table, ExcitationMapError> {
        let rows = emg.rows();
        let column = |channel: &String| {
            emg.column_named(channel)
                .ok_or_else(|| ExcitationMapError::ChannelNotInTable {
                    channel: channel.clone(),
                })
        };
        let mut values = Vec::with_capacity(rows * self.units.len());
        for unit in &self.units {
            let sources = unit
                .excitation
                .channels()
                .iter()
                .map(column)
                .collect::<Result<Vec<_>, _>>()?;
            let sum = |row: usize| sources.iter().map(|c| c[row]).sum::<f64>();
            match &unit.excitation {
                Excitation::Zero => values.extend(std::iter::repeat_n(0.0, rows)),
                Excitation::Mean(_) => {
                    let n = sources.len() as f64;
                    values.extend((0..rows).map(|row| sum(row) / n));
                }
                Excitation::Channel(_) | Excitation::Sum(_) => values.extend((0..rows).map(sum)),
            }
        }
        let units = self.units.iter().map(|u| u.unit.clone()).collect();
        Ok(Table::from_columns(units, emg.times().to_vec(), values))
    }
}

/// The `id` of `node`, non-empty; `within` names its parent.
fn id(node: Node, within: &str) -> Result<String, ExcitationMapError> {
    let id = xml::attribute(node, within, "id")?.trim();
    if id.is_empty() {
        return Err(ExcitationMapError::EmptyId {
            line: xml::line(node),
            within: within.to_string(),
        });
    }
    Ok(id.to_string())
}

/// `<experimental>`: the channels, at least one, each once.
fn channels(node: Node) -> Result<Vec<String>, ExcitationMapError> {
    let el = Element::new(node, "experimental".into(), &["emg"])?;
    let mut channels: Vec<String> = Vec::new();
    for emg in el.all("emg") {
        let channel = id(emg, &el.within)?;
        if channels.contains(&channel) {
            return Err(ExcitationMapError::Repeated {
                line: xml::line(emg),
                list: "experimental",
                name: channel,
            });
        }
        channels.push(channel);
    }
    if channels.is_empty() {
        return Err(XmlError::Missing {
            line: xml::line(node),
            within: el.within,
            element: "emg",
        }
        .into());
    }
    Ok(channels)
}

/// `<output>`: the units, at least one and at most [`MAX_UNITS`], each once.
fn outputs(node: Node) -> Result<Vec<String>, ExcitationMapError> {
    let line = xml::line(node);
    let units = xml::words(node, "emgGenerator")?;
    if units.is_empty() || units.len() > MAX_UNITS {
        return Err(ExcitationMapError::UnitCount {
            line,
            found: units.len(),
        });
    }
    if let Some(i) = (1..units.len()).find(|&i| units[..i].contains(&units[i])) {
        return Err(ExcitationMapError::Repeated {
            line,
            list: "output",
            name: units[i].clone(),
        });
    }
    Ok(units)
}

/// `<mapping>`: per unit of `outputs` at most one entry, its channels among `channels`.
fn mapping(
    node: Node,
    channels: &[String],
    outputs: &[String],
) -> Result<Vec<(String, Excitation)>, ExcitationMapError> {
    let el = Element::new(node, "mapping".into(), &["emg"])?;
    let mut mapped: Vec<(String, Excitation)> = Vec::new();
    for emg in el.all("emg") {
        let line = xml::line(emg);
        let unit = id(emg, &el.within)?;
        if mapped.iter().any(|(u, _)| *u == unit) {
            return Err(ExcitationMapError::Repeated {
                line,
                list: "mapping",
                name: unit,
            });
        }
        if !outputs.contains(&unit) {
            return Err(ExcitationMapError::NotAnOutput { line, unit });
        }
        let excitation = entry(emg, &unit, channels)?;
        mapped.push((unit, excitation));
    }
    Ok(mapped)
}

/// One `<emg>` of `<mapping>`, for `unit`: its operation and channels.
fn entry(emg: Node, unit: &str, channels: &[String]) -> Result<Excitation, ExcitationMapError> {
    let line = xml::line(emg);
    let within = format!("mapping of {:?}", excerpt(unit));
    let operation = xml::attribute(emg, &within, "operation")?.trim();
    let names = xml::words(emg, &within)?;
    let error = |kind| ExcitationMapError::Entry {
        line,
        unit: unit.to_string(),
        kind,
    };
    if let Some(i) = (1..names.len()).find(|&i| names[..i].contains(&names[i])) {
        return Err(error(EntryError::RepeatedChannel(names[i].clone())));
    }
    if let Some(c) = names.iter().find(|c| !channels.contains(c)) {
        return Err(error(EntryError::UnknownChannel(c.clone())));
    }
    let arity = |expected: &'static str| {
        error(EntryError::Arity {
            operation: operation.to_string(),
            found: names.len(),
            expected,
        })
    };
    match operation {
        "assign" if names.len() == 1 => Ok(Excitation::Channel(names[0].clone())),
        "assign" => Err(arity("one")),
        "mean" | "sum" if names.is_empty() => Err(arity("one or more")),
        "mean" => Ok(Excitation::Mean(names)),
        "sum" => Ok(Excitation::Sum(names)),
        "nil" if names.is_empty() => Ok(Excitation::Zero),
        "nil" => Err(arity("none")),
        other => Err(error(EntryError::UnknownOperation(other.to_string()))),
    }
}

/// What is wrong with an excitation map, or with a channel table given to it; lines count
/// from 1.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExcitationMapError {
    /// Not well-formed, or not of the schema's shape.
    #[error(transparent)]
    Xml(#[from] XmlError),
    /// An `<emg>` whose `id` is empty.
    #[error("line {line}: {within}: an <emg> with an empty id")]
    EmptyId {
        /// The `<emg>`'s line.
        line: usize,
        /// Its parent.
        within: String,
    },
    /// A name given twice in one list (`experimental`, `mapping`, `output`).
    #[error("line {line}: {list}: {:?} is given twice", excerpt(.name))]
    Repeated {
        /// The second one's line (the list's, for `output`).
        line: usize,
        /// The list.
        list: &'static str,
        /// The name.
        name: String,
    },
    /// No unit in `<output>`, or more than `MAX_UNITS`.
    #[error("line {line}: output: {found} units, a map drives 1 to {MAX_UNITS}")]
    UnitCount {
        /// `<output>`'s line.
        line: usize,
        /// The units found.
        found: usize,
    },
    /// A mapping entry for a unit `<output>` does not list.
    #[error("line {line}: mapping: {:?} is not a unit of <output>", excerpt(.unit))]
    NotAnOutput {
        /// The entry's line.
        line: usize,
        /// Its unit.
        unit: String,
    },
    /// A mapping entry that does not hold.
    #[error("line {line}: mapping of {:?}: {kind}", excerpt(.unit))]
    Entry {
        /// The entry's line.
        line: usize,
        /// Its unit.
        unit: String,
        /// What is wrong.
        kind: EntryError,
    },
    /// A unit of `<output>` without a mapping entry nor a channel of its name.
    #[error(
        "line {line}: output: unit {:?} has no mapping entry and no channel of its name \
         (give it one; operation=\"nil\" for none)",
        excerpt(.unit)
    )]
    NoSource {
        /// `<output>`'s line.
        line: usize,
        /// The unit.
        unit: String,
    },
    /// The channel table lacks a channel of the map.
    #[error("the channel table has no column {:?}", excerpt(.channel))]
    ChannelNotInTable {
        /// The channel.
        channel: String,
    },
}

/// What is wrong with a mapping entry.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EntryError {
    /// A channel `<experimental>` does not declare.
    #[error("channel {:?} is not one of <experimental>", excerpt(.0))]
    UnknownChannel(
        /// The channel.
        String,
    ),
    /// A channel named twice.
    #[error("channel {:?} is named twice", excerpt(.0))]
    RepeatedChannel(
        /// The channel.
        String,
    ),
    /// An operation other than `assign`, `mean`, `sum` and `nil`.
    #[error("unknown operation {:?} (expected assign, mean, sum or nil)", excerpt(.0))]
    UnknownOperation(
        /// The operation.
        String,
    ),
    /// Another count of channels than the operation takes.
    #[error("operation {} takes {expected} channel(s), found {found}", excerpt(.operation))]
    Arity {
        /// The operation.
        operation: String,
        /// The channels given.
        found: usize,
        /// The count it takes.
        expected: &'static str,
    },
}

#[cfg(test)]
mod tests;
