//! Why a figure, or `summary.md`, cannot be made: a run or a curve it shows, the drawing, or a
//! file it writes (named by its path).

use muscle_actuator_core::physics::contractile::SteadyStateError;
use std::path::PathBuf;

/// Why a figure cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// A built-in scenario that cannot be found.
    #[error(transparent)]
    Scenario(#[from] muscle_actuator_core::sim::ScenarioError),
    /// A scenario that cannot be set up or run.
    #[error(transparent)]
    ScenarioRun(#[from] muscle_actuator_core::sim::ScenarioRunError),
    /// Steady states that cannot be computed.
    #[error(transparent)]
    Steady(#[from] muscle_actuator_core::sim::steady::SteadyError),
    /// A run with no ticks, where the figure reads its last one.
    #[error("no ticks")]
    NoTicks,
    /// The Distribution-Moment model's steady states cannot be found.
    #[error(transparent)]
    SteadyState(#[from] SteadyStateError),
    /// The output directory cannot be created.
    #[error("cannot create {}: {source}", path.display())]
    CreateDir {
        /// The directory.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// An image file cannot be created.
    #[error("cannot create {}: {source}", path.display())]
    CreateFile {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file cannot be written into place.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The plotting backend failed while drawing an image.
    #[error("{}: {source}", path.display())]
    Draw {
        /// The image.
        path: PathBuf,
        /// The backend's error.
        source: PlotError,
    },
    /// A plot path with no file name to derive the images' names from.
    #[error("bad plot file name {}", path.display())]
    PlotFileName {
        /// The path given.
        path: PathBuf,
    },
}

/// The plotting backend's error (plotters'), as it prints itself.
#[derive(Debug, thiserror::Error)]
#[error("plot: {0}")]
pub struct PlotError(pub String);
