//! A run recorded as its caller steps it: the caller owns the loop (a subject's units driven
//! through a measured trial, `predict --out`) and shows the recorder the simulation at rest,
//! then after each tick with that tick's applied inputs. The recording is an ordinary run, so
//! `replay`, `compare`, `export` and Foxglove read it as a `simulate --out` run.
//!
//! As every offline run, the state at tick 0 shows the inputs of tick 0 applied to the run at
//! rest (rebuilt from the metadata as `replay` rebuilds it); after tick k the recorder writes
//! the inputs of tick k and the state after it, so that `replay` gives every state back bit for
//! bit.

use super::error::RunError;
use super::limits;
use super::metadata::{BuildError, RunMeta};
use super::writer::RunWriter;
use muscle_actuator_core::physics::Inputs;
use muscle_actuator_core::sim::Simulation;
use std::path::Path;

/// A recording fed tick by tick ([`ObservedRun::observe`]), under a temporary name until
/// [`ObservedRun::commit`]; dropped instead, it leaves nothing behind (so that a command may
/// still fail after the run, on its other outputs, without leaving the recording).
#[must_use = "the recording is written under its name only by commit"]
pub struct ObservedRun {
    writer: RunWriter,
    meta: RunMeta,
    /// Simulations observed so far (the first at rest).
    observed: u64,
    /// The first error: the caller's run goes on, nothing more is written.
    error: Option<RunError>,
}

impl ObservedRun {
    /// Starts the recording of the run `meta` describes at `out`. Its rate (called `rate_name`
    /// in the message that refuses it) and stepping are checked against the recordings' limits
    /// first.
    pub fn start(out: &Path, meta: RunMeta, rate_name: &str) -> Result<ObservedRun, RunError> {
        limits::check_rate_hz(rate_name, meta.rate_hz)?;
        limits::check_stepping("the stepping", meta.stepping)?;
        Ok(ObservedRun {
            writer: RunWriter::start(out, &meta)?,
            meta,
            observed: 0,
            error: None,
        })
    }

    /// Shows the recorder the simulation: at rest first (`applied` is then ignored), then after
    /// each tick with the inputs that tick applied. After an error nothing more is written; the
    /// error waits for [`ObservedRun::take_error`].
    pub fn observe(&mut self, sim: &Simulation, applied: &Inputs) {
        if self.error.is_none() {
            if let Err(e) = self.write(sim, applied) {
                self.error = Some(e);
            }
        }
        self.observed += 1;
    }

    /// The first error met while observing, if any.
    pub fn take_error(&mut self) -> Option<RunError> {
        self.error.take()
    }

    /// Finishes the recording and renames it into place.
    pub fn commit(self) -> Result<(), RunError> {
        self.writer.finish()
    }

    /// After tick k (the observation k + 1): the inputs of tick k, the state after it; after
    /// tick 0 first the state at tick 0 (the run at rest with tick 0's inputs).
    fn write(&mut self, sim: &Simulation, applied: &Inputs) -> Result<(), RunError> {
        let Some(k) = self.observed.checked_sub(1) else {
            return Ok(());
        };
        if k == 0 {
            let state0 = self.state_zero(applied)?;
            self.writer.state(0, &state0.snapshot())?;
        }
        self.writer.inputs(k, applied)?;
        self.writer.state(k + 1, &sim.snapshot())
    }

    /// The run at rest as `replay` rebuilds it from the metadata, with tick 0's inputs.
    fn state_zero(&self, applied: &Inputs) -> Result<Simulation, BuildError> {
        let mut sim = self.meta.build(self.meta.model, self.meta.stepping)?;
        sim.inputs_mut().clone_from(applied);
        Ok(sim)
    }
}
