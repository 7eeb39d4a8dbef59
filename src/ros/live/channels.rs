//! What the live view offers: the node's published topics as channels (with the recordings'
//! `ros2msg` schemas), the input topics a client may publish on, and the two services.

use crate::msgs::definition;
use crate::recording::schema::ros2msg_schema;
use crate::runs::channels::{
    ACTIVATION_TYPE, DIAGNOSTICS_TOPIC, DIAGNOSTICS_TYPE, FLOAT64_ARRAY_TYPE, FLOAT64_TYPE,
    JOINT_STATE_TYPE, LOAD_TYPE, LOG_TYPE, ROSOUT_TOPIC, STATE_TYPE,
};
use serde_json::{json, Value};

/// A topic the node publishes, served as a live channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum Outlet {
    State,
    JointStates,
    Diagnostics,
    Rosout,
    /// With a simulated clock.
    Clock,
    /// With driven joints.
    JointEfforts,
}

/// Number of [`Outlet`]s: the size of per-outlet tables.
pub(crate) const OUTLETS: usize = 6;

impl Outlet {
    pub(crate) fn index(self) -> usize {
        self as usize
    }
}

/// One advertised channel: id (its [`Outlet`]'s index + 1), topic, type and schema.
#[derive(Debug, Clone)]
pub(crate) struct ChannelInfo {
    pub(crate) outlet: Outlet,
    pub(crate) id: u32,
    pub(crate) topic: String,
    pub(crate) type_name: &'static str,
    pub(crate) schema: String,
}

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

/// The `.srv` text of `~/step`, split into request and response below.
const STEP_SRV: &str = include_str!("../../../msg/srv/Step.srv");

/// The `.msg` text of a service's request or response part (as `pkg/msg/Service_Part`, for
/// [`ros2msg_schema`]), or of any recorded type.
fn service_part(name: &str) -> Option<&'static str> {
    let (req, resp) = STEP_SRV.split_once("\n---\n")?;
    match name {
        // std_srvs/Trigger: an empty request; the response as ROS 2 kilted defines it.
        "std_srvs/msg/Trigger_Request" => Some(""),
        "std_srvs/msg/Trigger_Response" => Some("bool success # indicate successful run of triggered service\nstring message # informational, e.g. for error messages\n"),
        "muscle_actuator_msgs/msg/Step_Request" => Some(req),
        "muscle_actuator_msgs/msg/Step_Response" => Some(resp),
        other => definition(other),
    }
}

/// The node's resolved topic and service names.
#[derive(Debug, Clone, Default)]
pub(crate) struct Topics {
    pub(crate) state: String,
    pub(crate) joint_states: String,
    pub(crate) activation: String,
    pub(crate) activation_array: String,
    /// One per muscle topic opened, in order.
    pub(crate) muscle_commands: Vec<String>,
    pub(crate) load: String,
    pub(crate) reset: String,
    pub(crate) step: String,
    /// `~/joint_efforts`, with driven joints.
    pub(crate) joint_efforts: Option<String>,
}

/// Everything the live view serves, resolved once at start-up.
#[derive(Debug, Clone)]
pub(crate) struct Catalogue {
    pub(crate) channels: Vec<ChannelInfo>,
    /// Resolved input topic names with their kind and type.
    pub(crate) inputs: Vec<(String, InputTopic, &'static str)>,
    /// `advertiseServices`, as sent to each client.
    pub(crate) services_json: String,
}

impl Catalogue {
    /// The node's channels under its resolved names; `/clock` with a simulated clock.
    pub(crate) fn new(names: &Topics, publishes_clock: bool) -> Result<Self, String> {
        let mut channels = Vec::new();
        let mut add =
            |outlet: Outlet, topic: &str, type_name: &'static str| -> Result<(), String> {
                channels.push(ChannelInfo {
                    outlet,
                    id: outlet.index() as u32 + 1,
                    topic: topic.into(),
                    type_name,
                    schema: ros2msg_schema(type_name, &definition)?,
                });
                Ok(())
            };
        add(Outlet::State, &names.state, STATE_TYPE)?;
        add(Outlet::JointStates, &names.joint_states, JOINT_STATE_TYPE)?;
        add(Outlet::Diagnostics, DIAGNOSTICS_TOPIC, DIAGNOSTICS_TYPE)?;
        add(Outlet::Rosout, ROSOUT_TOPIC, LOG_TYPE)?;
        if publishes_clock {
            add(Outlet::Clock, "/clock", "rosgraph_msgs/msg/Clock")?;
        }
        if let Some(efforts) = &names.joint_efforts {
            add(Outlet::JointEfforts, efforts, FLOAT64_ARRAY_TYPE)?;
        }
        let mut inputs = vec![
            (
                names.activation.clone(),
                InputTopic::Activation,
                ACTIVATION_TYPE,
            ),
            (
                names.activation_array.clone(),
                InputTopic::ActivationArray,
                FLOAT64_ARRAY_TYPE,
            ),
            (names.load.clone(), InputTopic::Load, LOAD_TYPE),
        ];
        for (k, t) in names.muscle_commands.iter().enumerate() {
            inputs.push((t.clone(), InputTopic::MuscleCommand(k), FLOAT64_TYPE));
        }
        let services_json = services_json(names)?;
        Ok(Self {
            channels,
            inputs,
            services_json,
        })
    }

    /// The `advertise` message of every channel.
    pub(crate) fn advertise_json(&self) -> String {
        let channels: Vec<Value> = self
            .channels
            .iter()
            .map(|c| {
                json!({
                    "id": c.id,
                    "topic": c.topic,
                    "encoding": "cdr",
                    "schemaName": c.type_name,
                    "schemaEncoding": "ros2msg",
                    "schema": c.schema,
                })
            })
            .collect();
        json!({"op": "advertise", "channels": channels}).to_string()
    }

    pub(crate) fn channel(&self, id: u32) -> Option<&ChannelInfo> {
        self.channels.iter().find(|c| c.id == id)
    }

    /// The input topic `topic` of type `type_name`, or why a client cannot publish on it.
    pub(crate) fn input(&self, topic: &str, type_name: &str) -> Result<InputTopic, String> {
        // Clients name types `pkg/msg/Type` or `pkg/Type`.
        let normal = match type_name.split('/').collect::<Vec<_>>()[..] {
            [pkg, ty] => format!("{pkg}/msg/{ty}"),
            _ => type_name.to_string(),
        };
        match self.inputs.iter().find(|(t, _, _)| t == topic) {
            Some((_, kind, ty)) if *ty == normal => Ok(*kind),
            Some((_, _, ty)) => Err(format!(
                "{} takes {ty}, not {}",
                crate::text::excerpt(topic),
                crate::text::excerpt(type_name)
            )),
            None => Err(format!(
                "{} is not an input topic of this node (inputs: {})",
                crate::text::excerpt(topic),
                crate::text::excerpt(
                    &self
                        .inputs
                        .iter()
                        .map(|(t, _, _)| t.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            )),
        }
    }
}

/// A service's request or response description, in the form of both the current and the older
/// specification (`requestSchema` / `responseSchema`).
fn part(schema_name: &str, lookup_name: &str) -> Result<(Value, String), String> {
    let schema = ros2msg_schema(lookup_name, &service_part)?;
    Ok((
        json!({
            "encoding": "cdr",
            "schemaName": schema_name,
            "schemaEncoding": "ros2msg",
            "schema": schema,
        }),
        schema,
    ))
}

fn services_json(names: &Topics) -> Result<String, String> {
    let mut services = Vec::new();
    for (service, name, ty, pkg, srv) in [
        (
            Service::Reset,
            &names.reset,
            "std_srvs/srv/Trigger",
            "std_srvs",
            "Trigger",
        ),
        (
            Service::Step,
            &names.step,
            "muscle_actuator_msgs/srv/Step",
            "muscle_actuator_msgs",
            "Step",
        ),
    ] {
        let (req, req_schema) = part(
            &format!("{pkg}/srv/{srv}_Request"),
            &format!("{pkg}/msg/{srv}_Request"),
        )?;
        let (resp, resp_schema) = part(
            &format!("{pkg}/srv/{srv}_Response"),
            &format!("{pkg}/msg/{srv}_Response"),
        )?;
        services.push(json!({
            "id": service as u32,
            "name": name,
            "type": ty,
            "request": req,
            "response": resp,
            "requestSchema": req_schema,
            "responseSchema": resp_schema,
        }));
    }
    Ok(json!({"op": "advertiseServices", "services": services}).to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> Topics {
        Topics {
            activation: "/m/activation".into(),
            activation_array: "/m/activation_array".into(),
            muscle_commands: vec!["/m/flexor/cmd_activation".into()],
            load: "/m/external_load".into(),
            state: "/m/state".into(),
            joint_states: "/joint_states".into(),
            reset: "/m/reset".into(),
            step: "/m/step".into(),
            joint_efforts: None,
        }
    }

    #[test]
    fn channels_carry_the_recordings_schemas() {
        let c = Catalogue::new(&names(), true).unwrap();
        let topics: Vec<&str> = c.channels.iter().map(|c| c.topic.as_str()).collect();
        assert_eq!(
            topics,
            [
                "/m/state",
                "/joint_states",
                "/diagnostics",
                "/rosout",
                "/clock"
            ]
        );
        let state = crate::runs::channels::channel("/m/state", STATE_TYPE).unwrap();
        assert_eq!(c.channels[0].schema, state.schema);
        assert!(c.channels[4]
            .schema
            .starts_with("builtin_interfaces/Time clock\n"));
        assert!(Catalogue::new(&names(), false)
            .unwrap()
            .channel(5)
            .is_none());
    }

    #[test]
    fn services_carry_their_parts() {
        let c = Catalogue::new(&names(), false).unwrap();
        let v: Value = serde_json::from_str(&c.services_json).unwrap();
        let step = &v["services"][1];
        assert_eq!(step["name"], "/m/step");
        assert!(step["request"]["schema"]
            .as_str()
            .unwrap()
            .contains("int64 ticks"));
        let resp = step["response"]["schema"].as_str().unwrap();
        assert!(
            resp.contains("MSG: muscle_actuator_msgs/ActuatorState"),
            "{resp}"
        );
        assert_eq!(v["services"][0]["request"]["schema"], "\n");
    }

    /// Every plot of docs/foxglove-layout.json names a channel of the default node and fields
    /// its schema has; its publish panel names an input topic with its type.
    #[test]
    fn the_layout_file_names_real_channels_and_fields() {
        use crate::recording::schema::field_names;
        let layout: Value =
            serde_json::from_str(include_str!("../../../docs/foxglove-layout.json")).unwrap();
        let mut n = names();
        n.state = "/muscle_actuator/state".into();
        n.activation = "/muscle_actuator/activation".into();
        let c = Catalogue::new(&n, false).unwrap();
        let panels = layout["configById"].as_object().unwrap();
        let mut checked = 0;
        for (id, cfg) in panels {
            for path in cfg["paths"].as_array().into_iter().flatten() {
                let v = path["value"].as_str().unwrap();
                let (topic, rest) = v.split_once('.').unwrap();
                let ch = c.channels.iter().find(|ch| ch.topic == topic).expect(v);
                // `a[0].b` → the root's field `a`, then `b` of the muscles' type.
                let parts: Vec<&str> = rest
                    .split('.')
                    .map(|p| p.split('[').next().unwrap())
                    .collect();
                let root = field_names(&ch.schema, ch.type_name, true).unwrap();
                assert!(root.contains(&parts[0].to_string()), "{id}: {v}");
                if let Some(inner) = parts.get(1) {
                    let muscle =
                        field_names(&ch.schema, "muscle_actuator_msgs/MuscleState", false).unwrap();
                    assert!(muscle.contains(&inner.to_string()), "{id}: {v}");
                }
                checked += 1;
            }
        }
        assert!(checked >= 8, "{checked} paths");
        let publish = &panels["Publish!activation"];
        assert_eq!(
            c.input(
                publish["topicName"].as_str().unwrap(),
                publish["datatype"].as_str().unwrap()
            ),
            Ok(InputTopic::Activation)
        );
    }

    #[test]
    fn inputs_are_checked_by_topic_and_type() {
        let c = Catalogue::new(&names(), false).unwrap();
        assert_eq!(
            c.input("/m/activation", "muscle_actuator_msgs/ActivationCommand"),
            Ok(InputTopic::Activation)
        );
        assert_eq!(
            c.input("/m/flexor/cmd_activation", "std_msgs/msg/Float64"),
            Ok(InputTopic::MuscleCommand(0))
        );
        assert!(c.input("/m/activation", "std_msgs/msg/Float64").is_err());
        assert!(c.input("/m/state", STATE_TYPE).is_err());
    }
}
