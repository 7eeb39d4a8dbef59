//! The node's topics and services, each declared once, in one row of [`endpoint_list`]: name
//! (before remapping), type, QoS, direction, when the node has it, whether the recording holds
//! it, whether the live view serves it, and what takes or makes its messages (its role: an
//! input's handler, an output's producer). The DDS set-up (`dds.rs`), the recording's channels
//! (`record.rs`), the live view's channels and inputs (`live/channels.rs`), the resolved names
//! ([`super::Names`]), the publisher thread (`outputs/`) and the input handling (`inputs/`) read
//! [`ENDPOINTS`]; `roles.rs` reads the roles; docs/ros-interface.md's topics table is checked
//! against it (`docs_table`).
//!
//! Adding a topic: its row here, and its handler (an input: a file in `inputs/`) or its producer
//! (an output: a file in `outputs/`). `src/tests_topic.rs` adds one that way.

use muscle_actuator_recording::runs::{
    NodeTopic, ACTIVATION, APPLIED_ACTIVATION, APPLIED_JOINT_MOTION, APPLIED_LOAD,
    DIAGNOSTICS_TYPE, FLOAT64_ARRAY_TYPE, FLOAT64_TYPE, JOINT_STATES, JOINT_STATE_TYPE, LOAD,
    LOG_TYPE, STATE,
};

/// Declares [`Endpoint`] (one variant per row), [`ENDPOINTS`] (the rows' data, in order) and,
/// for the tests, [`Endpoint::ALL`], from [`endpoint_list`]; the rows' roles are read by
/// `roles.rs`.
macro_rules! endpoints {
    ($($(#[doc = $doc:literal])* $(#[cfg($cfg:meta)])* $variant:ident: $row:expr => $role:expr,)*) => {
        /// A topic or service of the node.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub(crate) enum Endpoint {
            $($(#[doc = $doc])* $(#[cfg($cfg)])* $variant,)*
        }

        /// Every endpoint. The order is that of the recording's channels, then of the live
        /// view's channels (their ids) and inputs, and of the inputs' polling.
        pub(crate) const ENDPOINTS: &[EndpointSpec] = &[
            $($(#[cfg($cfg)])* $row.of(Endpoint::$variant),)*
        ];

        #[cfg(test)]
        impl Endpoint {
            /// Every endpoint, in declaration order.
            pub(crate) const ALL: &'static [Endpoint] = &[$($(#[cfg($cfg)])* Endpoint::$variant,)*];
        }
    };
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
    Input,
    /// A service clients may call.
    Service(Service),
}

/// A service served to the live view's clients (its id in the protocol).
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

/// One endpoint.
#[derive(Clone, Copy)]
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
    /// Whether the recording holds it (a channel per instance).
    pub(crate) record: bool,
    pub(crate) live: Live,
}

/// A row, as the table writes it ([`EndpointSpec::of`] names its endpoint).
const fn spec(direction: Direction, name: &'static str, type_name: &'static str) -> EndpointSpec {
    EndpointSpec {
        endpoint: Endpoint::State,
        direction,
        name,
        type_name,
        qos: Qos::Reliable,
        when: When::Always,
        record: false,
        live: Live::No,
    }
}

/// The row of a topic offline runs share.
const fn topic(direction: Direction, t: NodeTopic) -> EndpointSpec {
    spec(direction, t.name, t.type_name)
}

impl EndpointSpec {
    const fn of(mut self, endpoint: Endpoint) -> Self {
        self.endpoint = endpoint;
        self
    }
    const fn recorded(mut self) -> Self {
        self.record = true;
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

/// The node's endpoints, one row each: `Variant: data => role,`. The data (name, type, QoS,
/// when, recording, live view) is read here; the role (what takes or makes the messages: an
/// input's handler in `inputs/`, an output's producer in `outputs/`, or `own` for those made by
/// their own code) is read by `roles.rs`, which is above the handlers, so that nothing the
/// handlers use depends on them. `$then` is the macro that reads the list.
macro_rules! endpoint_list {
    ($then:ident) => {
        $then! {
            State: topic(Pub, STATE).recorded().live(Live::Outlet)
                => output(&outputs::STATE),
            JointStates: topic(Pub, JOINT_STATES).recorded().live(Live::Outlet)
                => output(&outputs::JOINT_STATES),
            Activation: topic(Sub, ACTIVATION).recorded().live(Live::Input)
                => input(&inputs::ACTIVATION),
            Load: topic(Sub, LOAD).recorded().live(Live::Input)
                => input(&inputs::LOAD),
            AppliedActivation: topic(Recorded, APPLIED_ACTIVATION).recorded() => own(),
            AppliedLoad: topic(Recorded, APPLIED_LOAD).recorded() => own(),
            Diagnostics: spec(Pub, "/diagnostics", DIAGNOSTICS_TYPE)
                .recorded()
                .live(Live::Outlet)
                => own(),
            Rosout: spec(Pub, "/rosout", LOG_TYPE)
                .when(When::Library)
                .recorded()
                .live(Live::Outlet)
                => own(),
            ActivationArray: spec(Sub, "~/activation_array", FLOAT64_ARRAY_TYPE)
                .recorded()
                .live(Live::Input)
                => input(&inputs::ACTIVATION_ARRAY),
            /// `~/<muscle>/cmd_activation`, one per muscle.
            MuscleCommand: spec(Sub, "~/<muscle>/cmd_activation", FLOAT64_TYPE)
                .recorded()
                .live(Live::Input)
                => input(&inputs::MUSCLE_COMMAND),
            #[cfg(feature = "test-topic")]
            TestExcitation: spec(Sub, "~/test_excitation", FLOAT64_TYPE)
                .recorded()
                .live(Live::Input)
                => input(&inputs::test_excitation::TEST_EXCITATION),
            ClockOut: spec(Pub, "/clock", CLOCK_TYPE)
                .when(When::PublishesClock)
                .qos(Qos::BestEffort { depth: 1 })
                .live(Live::Outlet)
                => output(&outputs::CLOCK),
            // Deeper, so that a jump back between two looks is still seen.
            ClockIn: spec(Sub, "/clock", CLOCK_TYPE)
                .when(When::FollowsClock)
                .qos(Qos::BestEffort { depth: 10 })
                => input(&inputs::CLOCK_IN),
            JointStatesIn: spec(Sub, "~/joint_states_in", JOINT_STATE_TYPE)
                .when(When::DrivenJoints)
                .recorded()
                => input(&inputs::JOINT_STATES_IN),
            JointEfforts: spec(Pub, "~/joint_efforts", FLOAT64_ARRAY_TYPE)
                .when(When::DrivenJoints)
                .recorded()
                .live(Live::Outlet)
                => output(&outputs::JOINT_EFFORTS),
            AppliedJointMotion: topic(Recorded, APPLIED_JOINT_MOTION)
                .when(When::DrivenJoints)
                .recorded()
                => own(),
            Reset: spec(Srv, "~/reset", "std_srvs/srv/Trigger")
                .live(Live::Service(Service::Reset))
                => own(),
            Step: spec(Srv, "~/step", "muscle_actuator_msgs/srv/Step")
                .live(Live::Service(Service::Step))
                => own(),
            StepTopic: spec(Sub, "~/step", "std_msgs/msg/Int64")
                => input(&inputs::STEP_TOPIC),
        }
    };
}
pub(crate) use endpoint_list;

endpoint_list!(endpoints);

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
