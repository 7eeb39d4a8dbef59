//! The node's topics and services, each declared once: name (before remapping), type, QoS,
//! direction, when the node has it, whether the recording holds it (on which channel) and
//! whether the live view serves it. The DDS set-up (`dds.rs`), the recording's channels
//! (`record.rs`), the live view's channels and inputs (`live/channels.rs`), the resolved names
//! ([`super::Names`]) and the publisher thread (`threads.rs`) read [`ENDPOINTS`];
//! docs/ros-interface.md's topics table is checked against it (`docs_table`).
//!
//! Adding a topic: a variant of [`Endpoint`], one entry here, and its handler (a `tasks.rs`
//! function and its arm in `node.rs` for an input; a message made in `threads.rs`'s
//! `publish_loop` for an output); its row in docs/ros-interface.md follows.

use super::live_kinds::{InputTopic, Service};
use muscle_actuator_recording::runs::channels::{
    Channel, ACTIVATION_TYPE, DIAGNOSTICS_TYPE, FLOAT64_ARRAY_TYPE, FLOAT64_TYPE, JOINT_STATE_TYPE,
    LOAD_TYPE, LOG_TYPE, STATE_TYPE,
};

/// Declares [`Endpoint`] and, for the tests, [`Endpoint::ALL`] (every variant in order) from
/// one list, so that a new endpoint is one line here and its entry in [`ENDPOINTS`].
macro_rules! endpoints {
    ($($(#[$doc:meta])* $variant:ident,)*) => {
        /// A topic or service of the node.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub(crate) enum Endpoint {
            $($(#[$doc])* $variant,)*
        }

        #[cfg(test)]
        impl Endpoint {
            /// Every endpoint, in declaration order.
            pub(crate) const ALL: &'static [Endpoint] = &[$(Endpoint::$variant,)*];
        }
    };
}

endpoints! {
    State,
    JointStates,
    Activation,
    Load,
    AppliedActivation,
    AppliedLoad,
    Diagnostics,
    Rosout,
    ActivationArray,
    /// `~/<muscle>/cmd_activation`, one per muscle.
    MuscleCommand,
    ClockOut,
    ClockIn,
    JointStatesIn,
    JointEfforts,
    AppliedJointMotion,
    Reset,
    Step,
    StepTopic,
}

/// How the node takes part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Direction {
    /// The node subscribes.
    Sub,
    /// The node publishes.
    Pub,
    /// The node serves it.
    Srv,
    /// Only in the recording (not on DDS): named under the node, never remapped.
    Recorded,
}

#[cfg(test)]
impl Direction {
    /// As docs/ros-interface.md's `kind` column writes it.
    pub(crate) fn doc_name(self) -> &'static str {
        match self {
            Direction::Sub => "sub",
            Direction::Pub => "pub",
            Direction::Srv => "srv",
            Direction::Recorded => "recorded",
        }
    }
}

/// Quality of service.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Qos {
    /// Reliable, volatile, keep last 10: every endpoint of the node but `/clock`.
    Reliable,
    /// Best effort, keep last `depth` (`/clock`, as rclpy's time source subscribes to it).
    BestEffort { depth: usize },
}

/// When the node has it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum When {
    Always,
    /// With driven joints in the start-up configuration.
    DrivenJoints,
    /// With `clock` sim or lockstep (the node is the graph's clock).
    PublishesClock,
    /// With `use_sim_time` and `clock` wall.
    FollowsClock,
    /// Made by the ROS client library itself (its logging), not by `dds.rs`.
    Library,
}

/// What the live view does with it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Live {
    No,
    /// A channel clients subscribe to.
    Outlet,
    /// A topic clients may publish on.
    Input(InputTopic),
    /// A service clients may call.
    Service(Service),
}

/// One endpoint.
pub(crate) struct EndpointSpec {
    pub(crate) endpoint: Endpoint,
    pub(crate) direction: Direction,
    /// Before namespace and remapping (`~/` = under the node); `<muscle>` stands for each
    /// muscle's name.
    pub(crate) name: &'static str,
    /// `pkg/msg/Type` or `pkg/srv/Type`.
    pub(crate) type_name: &'static str,
    pub(crate) qos: Qos,
    pub(crate) when: When,
    /// The recording's channel.
    pub(crate) record: Option<Channel>,
    pub(crate) live: Live,
}

const fn spec(
    endpoint: Endpoint,
    direction: Direction,
    name: &'static str,
    type_name: &'static str,
) -> EndpointSpec {
    EndpointSpec {
        endpoint,
        direction,
        name,
        type_name,
        qos: Qos::Reliable,
        when: When::Always,
        record: None,
        live: Live::No,
    }
}

impl EndpointSpec {
    const fn recorded(mut self, ch: Channel) -> Self {
        self.record = Some(ch);
        self
    }
    const fn live(mut self, live: Live) -> Self {
        self.live = live;
        self
    }
    const fn when(mut self, when: When) -> Self {
        self.when = when;
        self
    }
    const fn qos(mut self, qos: Qos) -> Self {
        self.qos = qos;
        self
    }
    /// `(package, type)` as the DDS type name takes them.
    pub(crate) fn package_and_type(&self) -> (&'static str, &'static str) {
        let mut parts = self.type_name.split('/');
        let pkg = parts.next().unwrap_or_default();
        (pkg, parts.next_back().unwrap_or_default())
    }
}

use Direction::{Pub, Recorded, Srv, Sub};
use Endpoint as E;

/// Every endpoint. The order is that of the recording's channels, then of the live view's
/// channels (their ids) and inputs.
pub(crate) const ENDPOINTS: &[EndpointSpec] = &[
    spec(E::State, Pub, "~/state", STATE_TYPE)
        .recorded(Channel::State)
        .live(Live::Outlet),
    spec(E::JointStates, Pub, "joint_states", JOINT_STATE_TYPE)
        .recorded(Channel::JointStates)
        .live(Live::Outlet),
    spec(E::Activation, Sub, "~/activation", ACTIVATION_TYPE)
        .recorded(Channel::Activation)
        .live(Live::Input(InputTopic::Activation)),
    spec(E::Load, Sub, "~/external_load", LOAD_TYPE)
        .recorded(Channel::Load)
        .live(Live::Input(InputTopic::Load)),
    spec(
        E::AppliedActivation,
        Recorded,
        "~/applied/activation",
        ACTIVATION_TYPE,
    )
    .recorded(Channel::AppliedActivation),
    spec(
        E::AppliedLoad,
        Recorded,
        "~/applied/external_load",
        LOAD_TYPE,
    )
    .recorded(Channel::AppliedLoad),
    spec(E::Diagnostics, Pub, "/diagnostics", DIAGNOSTICS_TYPE)
        .recorded(Channel::Diagnostics)
        .live(Live::Outlet),
    spec(E::Rosout, Pub, "/rosout", LOG_TYPE)
        .when(When::Library)
        .recorded(Channel::Rosout)
        .live(Live::Outlet),
    spec(
        E::ActivationArray,
        Sub,
        "~/activation_array",
        FLOAT64_ARRAY_TYPE,
    )
    .recorded(Channel::ActivationArray)
    .live(Live::Input(InputTopic::ActivationArray)),
    spec(
        E::MuscleCommand,
        Sub,
        "~/<muscle>/cmd_activation",
        FLOAT64_TYPE,
    )
    .recorded(Channel::MuscleCommand(0))
    .live(Live::Input(InputTopic::MuscleCommand(0))),
    spec(E::ClockOut, Pub, "/clock", CLOCK_TYPE)
        .when(When::PublishesClock)
        .qos(Qos::BestEffort { depth: 1 })
        .live(Live::Outlet),
    // Deeper, so that a jump back between two looks is still seen.
    spec(E::ClockIn, Sub, "/clock", CLOCK_TYPE)
        .when(When::FollowsClock)
        .qos(Qos::BestEffort { depth: 10 }),
    spec(E::JointStatesIn, Sub, "~/joint_states_in", JOINT_STATE_TYPE)
        .when(When::DrivenJoints)
        .recorded(Channel::JointStatesIn),
    spec(E::JointEfforts, Pub, "~/joint_efforts", FLOAT64_ARRAY_TYPE)
        .when(When::DrivenJoints)
        .recorded(Channel::JointEfforts)
        .live(Live::Outlet),
    spec(
        E::AppliedJointMotion,
        Recorded,
        "~/applied/joint_motion",
        JOINT_STATE_TYPE,
    )
    .when(When::DrivenJoints)
    .recorded(Channel::AppliedJointMotion),
    spec(E::Reset, Srv, "~/reset", "std_srvs/srv/Trigger").live(Live::Service(Service::Reset)),
    spec(E::Step, Srv, "~/step", "muscle_actuator_msgs/srv/Step")
        .live(Live::Service(Service::Step)),
    spec(E::StepTopic, Sub, "~/step", "std_msgs/msg/Int64"),
];

/// `/clock`'s type.
pub(crate) const CLOCK_TYPE: &str = "rosgraph_msgs/msg/Clock";

/// The entry of `e`.
pub(crate) fn spec_of(e: Endpoint) -> &'static EndpointSpec {
    // Every variant has its entry (`every_endpoint_has_one_entry`).
    ENDPOINTS
        .iter()
        .find(|s| s.endpoint == e)
        .unwrap_or(&ENDPOINTS[0])
}

/// Number of live channels (the size of per-outlet tables).
pub(crate) const OUTLETS: usize = {
    let mut n = 0;
    let mut i = 0;
    while i < ENDPOINTS.len() {
        if matches!(ENDPOINTS[i].live, Live::Outlet) {
            n += 1;
        }
        i += 1;
    }
    n
};

/// A live channel: its place among the table's [`Live::Outlet`] entries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct Outlet(usize);

impl Outlet {
    /// The live channel of `e`, if the live view serves it.
    pub(crate) fn of(e: Endpoint) -> Option<Self> {
        ENDPOINTS
            .iter()
            .filter(|s| s.live == Live::Outlet)
            .position(|s| s.endpoint == e)
            .map(Outlet)
    }
    /// Its index in per-outlet tables, below [`OUTLETS`].
    pub(crate) fn index(self) -> usize {
        self.0
    }
}
