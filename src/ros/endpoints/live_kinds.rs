//! What a live-view client may do with an endpoint that is not a channel: publish on an input
//! topic, or call a service.

/// An input topic a client may advertise and publish on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum InputTopic {
    Activation,
    ActivationArray,
    /// The k-th `~/<muscle>/cmd_activation` topic the node opened.
    MuscleCommand(usize),
    Load,
}

/// A service served to clients.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Service {
    Reset = 1,
    Step = 2,
}

impl Service {
    pub(crate) fn from_id(id: u32) -> Option<Self> {
        match id {
            1 => Some(Self::Reset),
            2 => Some(Self::Step),
            _ => None,
        }
    }
}
