//! An actuator's complete state as bytes, and an actuator from them: the copy continues bit for
//! bit as the original does (same inputs, same bits of every output), in this process or
//! another one running the same build (a Python binding's pickling and `get_state`/`set_state`).
//!
//! What is rebuilt and what is saved: the bytes hold how the actuator was built (its
//! configuration as TOML text, the model's name, the tick rate, the sub-stepping), from which
//! [`Actuator::with_stepping`] rebuilds, and validates, everything that does not change from
//! tick to tick (plant, calibrations, tableaux, index maps, storage); then only what does
//! change, read into that structure with every size checked against it:
//! - the simulation: tick, the inputs held over the next tick (driven joints' carried motion
//!   included), activations, the state vector, each muscle's energetics (the last tick's
//!   sample and the energies since start);
//! - each part: its contractile elements' own state (`ContractileModel::save_state`: the full
//!   Huxley model's bond grid and sub-step closures; nothing for Hill and DM), its state and
//!   inputs as last gathered, the carried sub-step size, the activation memo, and its stepper
//!   (Jacobian, factorisation and their validity, Newton's carried factors, the last step's end
//!   and derivative, the fourth-order flag, work vectors, counters);
//! - the published state ([`StateSnapshot`]), as it was after the last tick (the inputs set
//!   since then do not show in it until the next tick).
//!
//! Not saved, being rebuilt identically or written before every read: the whole plant's
//! contractile elements (only the parts' are stepped), the rates at a tick's start and the
//! Jacobian's scratch space.
//!
//! Layout (version 1; little-endian, values as in [`crate::state_bytes`]):
//!
//! | bytes | what |
//! | --- | --- |
//! | 0..8 | magic `MUSCACTS` |
//! | 8..12 | format version, `u32` |
//! | 12..20 | body length L, `u64` |
//! | 20..20+L | body: config TOML, model name, rate (f64 bits), stepping (tag 0: tolerance, max sub-steps; tag 1: sub-steps), then the state above in that order |
//! | 20+L..52+L | SHA-256 of every byte before it |
//!
//! [`Actuator::from_bytes`] checks the magic, the version, the length and the checksum before
//! it reads anything, then refuses a size that is not the rebuilt structure's: damaged or
//! foreign bytes give an error on one line, never a panic or an actuator that fails later. The
//! version changes with any change of what is saved or of its order (a field added to a saved
//! struct fails to compile until it is saved: the save functions name every field).

use crate::config::ActuatorConfig;
use crate::physics::models::ModelKind;
use crate::physics::stepping::{Stepping, MAX_SUBSTEPS};
use crate::sim::actuator::Actuator;
use crate::sim::snapshot::{
    JointSnapshot, MuscleSnapshot, StateSnapshot, JOINT_FIELD_COUNT, MUSCLE_FIELD_COUNT,
};
use crate::state_bytes::{SavedState, StateError, StateReader, StateWriter};
use sha2::{Digest, Sha256};

/// The first bytes of a saved state.
pub(crate) const MAGIC: [u8; 8] = *b"MUSCACTS";
/// The layout's version: what is saved, in which order.
pub(crate) const VERSION: u32 = 1;
/// Magic, version and body length.
const HEADER_BYTES: usize = 20;
/// The SHA-256 at the end.
const CHECKSUM_BYTES: usize = 32;
/// Longest configuration text read back, bytes.
const MAX_CONFIG_BYTES: usize = 64 << 20;

impl Actuator {
    /// The complete state as bytes (format version, checksum): everything a later tick reads.
    /// [`Actuator::from_bytes`] gives an actuator that continues bit for bit as this one does.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut body = StateWriter::new();
        // A validated configuration always has a TOML form (a run's metadata records it so).
        let toml = toml::to_string(self.config()).expect("a configuration serialises as TOML");
        body.str(&toml);
        body.str(self.model().name());
        body.f64(self.rate_hz());
        save_stepping(&mut body, self.simulation().stepping());
        self.simulation().save_state(&mut body);
        save_snapshot(&mut body, self.state());
        seal(body.bytes())
    }

    /// An actuator from [`Actuator::to_bytes`]'s output. Err with a one-line message naming
    /// what is wrong for bytes that are not such a state (empty, wrong magic or version,
    /// truncated, checksum mismatch, a configuration or model this build refuses, sizes that
    /// are not those of the actuator the configuration describes). Never panics.
    pub fn from_bytes(bytes: &[u8]) -> Result<Actuator, SavedStateError> {
        restore(unseal(bytes)?)
    }
}

/// Why bytes are not a saved actuator state; one line, `saved actuator state: …`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SavedStateError {
    /// Not sealed bytes of this format: empty, wrong magic or version, truncated or trailing
    /// bytes, checksum mismatch.
    #[error("saved actuator state: {0}")]
    Seal(String),
    /// A body that does not fit the actuator it describes.
    #[error("saved actuator state: {0}")]
    Body(#[from] StateError),
    /// A configuration, model or stepping that this build refuses or cannot build.
    #[error("saved actuator state: {0}")]
    Refused(String),
}

/// The actuator the body describes.
fn restore(body: &[u8]) -> Result<Actuator, SavedStateError> {
    let refused = SavedStateError::Refused;
    let mut input = StateReader::new(body);
    let toml = input.str("configuration", MAX_CONFIG_BYTES)?;
    let config = ActuatorConfig::from_toml_str(toml).map_err(|e| {
        refused(format!(
            "configuration: {}",
            crate::text::one_line(&e.to_string())
        ))
    })?;
    let name = input.str("model name", 256)?;
    let model: ModelKind = name.parse().map_err(|e| refused(format!("model: {e}")))?;
    let rate_hz = input.f64("tick rate")?;
    let stepping = restore_stepping(&mut input)?;
    let mut actuator = Actuator::with_stepping(&config, model, rate_hz, stepping).map_err(|e| {
        refused(format!(
            "cannot rebuild the actuator: {}",
            crate::text::one_line(&e.to_string())
        ))
    })?;
    let (sim, state) = actuator.restore_target();
    sim.restore_state(&mut input)?;
    restore_snapshot(&mut input, state)?;
    input.finish()?;
    Ok(actuator)
}

fn save_stepping(out: &mut StateWriter, stepping: Stepping) {
    match stepping {
        Stepping::Adaptive {
            tolerance,
            max_substeps,
        } => {
            out.u8(0);
            out.f64(tolerance);
            out.usize(max_substeps);
        }
        Stepping::Fixed(n) => {
            out.u8(1);
            out.usize(n);
        }
    }
}

fn restore_stepping(input: &mut StateReader) -> Result<Stepping, StateError> {
    let stepping = match input.u8("stepping")? {
        0 => Stepping::Adaptive {
            tolerance: input.f64("stepping tolerance")?,
            max_substeps: input.usize("most sub-steps", MAX_SUBSTEPS)?,
        },
        1 => Stepping::Fixed(input.usize("sub-steps", MAX_SUBSTEPS)?),
        tag => return Err(StateError::Invalid(format!("stepping: unknown kind {tag}"))),
    };
    stepping
        .check()
        .map(|()| stepping)
        .map_err(|e| StateError::Invalid(e.to_string()))
}

fn save_snapshot(out: &mut StateWriter, s: &StateSnapshot) {
    out.usize(s.muscles.len());
    out.usize(MUSCLE_FIELD_COUNT);
    for m in &s.muscles {
        for v in m.values() {
            out.f64(v);
        }
    }
    out.usize(s.joints.len());
    out.usize(JOINT_FIELD_COUNT);
    for j in &s.joints {
        for v in j.values() {
            out.f64(v);
        }
    }
    out.f64s(&s.stiffness_matrix);
}

fn restore_snapshot(input: &mut StateReader, s: &mut StateSnapshot) -> Result<(), StateError> {
    input.expect_len("published muscle states", s.muscles.len())?;
    input.expect_len("published muscle fields", MUSCLE_FIELD_COUNT)?;
    for m in s.muscles.iter_mut() {
        let mut v = [0.0; MUSCLE_FIELD_COUNT];
        for x in v.iter_mut() {
            *x = input.f64("published muscle state")?;
        }
        *m = MuscleSnapshot::from_values(v);
    }
    input.expect_len("published joint states", s.joints.len())?;
    input.expect_len("published joint fields", JOINT_FIELD_COUNT)?;
    for j in s.joints.iter_mut() {
        let mut v = [0.0; JOINT_FIELD_COUNT];
        for x in v.iter_mut() {
            *x = input.f64("published joint state")?;
        }
        *j = JointSnapshot::from_values(v);
    }
    input.f64s_into("published stiffness matrix", &mut s.stiffness_matrix)
}

/// Header, body and checksum.
fn seal(body: &[u8]) -> Vec<u8> {
    let mut out = StateWriter::new();
    out.raw(&MAGIC);
    out.raw(&VERSION.to_le_bytes());
    out.usize(body.len());
    out.raw(body);
    let sum = Sha256::digest(out.bytes());
    out.raw(&sum);
    out.into_bytes()
}

/// The body of sealed bytes, once their magic, version, length and checksum are checked.
fn unseal(bytes: &[u8]) -> Result<&[u8], SavedStateError> {
    let seal = SavedStateError::Seal;
    if bytes.is_empty() {
        return Err(seal("empty (0 bytes)".into()));
    }
    let start = &bytes[..bytes.len().min(MAGIC.len())];
    if !MAGIC.starts_with(start) {
        return Err(seal(
            "wrong magic: these bytes are not a saved state".into(),
        ));
    }
    if bytes.len() < HEADER_BYTES + CHECKSUM_BYTES {
        return Err(seal(format!(
            "truncated: {} bytes, fewer than a header and a checksum ({})",
            bytes.len(),
            HEADER_BYTES + CHECKSUM_BYTES
        )));
    }
    let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
    if version != VERSION {
        return Err(seal(format!(
            "format version {version}, this build reads version {VERSION}"
        )));
    }
    let announced = u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes"));
    let body_len = bytes.len() - HEADER_BYTES - CHECKSUM_BYTES;
    if announced != body_len as u64 {
        let whole = announced.saturating_add((HEADER_BYTES + CHECKSUM_BYTES) as u64);
        let what = if whole > bytes.len() as u64 {
            "truncated"
        } else {
            "trailing bytes"
        };
        return Err(seal(format!(
            "{what}: {} bytes, the header announces {whole}",
            bytes.len()
        )));
    }
    let (sealed, sum) = bytes.split_at(HEADER_BYTES + body_len);
    if Sha256::digest(sealed).as_slice() != sum {
        return Err(seal(
            "checksum mismatch: the bytes were changed or damaged".into(),
        ));
    }
    Ok(&sealed[HEADER_BYTES..])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A refusal says at which stage the bytes failed: the seal, the body, or what this build
    /// can rebuild.
    #[test]
    fn refusals_name_their_stage() {
        let e = Actuator::from_bytes(b"").unwrap_err();
        assert_eq!(e, SavedStateError::Seal("empty (0 bytes)".into()));
        assert_eq!(e.to_string(), "saved actuator state: empty (0 bytes)");
        let mut body = StateWriter::new();
        body.usize(10);
        body.raw(b"ab");
        let e = Actuator::from_bytes(&seal(body.bytes())).unwrap_err();
        assert!(
            matches!(
                e,
                SavedStateError::Body(StateError::Truncated { needed: 10, .. })
            ),
            "{e:?}"
        );
        let mut body = StateWriter::new();
        body.str("muscle = 3");
        let e = Actuator::from_bytes(&seal(body.bytes())).unwrap_err();
        assert!(matches!(e, SavedStateError::Refused(_)), "{e:?}");
        assert!(
            e.to_string()
                .starts_with("saved actuator state: configuration: "),
            "{e}"
        );
    }
}
