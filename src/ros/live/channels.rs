//! What the live view offers: the node's published topics as channels (with the recordings'
//! `ros2msg` schemas), the input topics a client may publish on, and the two services; which
//! ones, the endpoints' table says ([`crate::ros::endpoints::Live`]).

use super::error::LiveError;
use crate::ros::endpoints::{Endpoint, Live, Names, Service};
use muscle_actuator_recording::msgs::definition;
use muscle_actuator_recording::recording::schema::ros2msg_schema;
use serde_json::{json, Value};

pub(crate) use crate::ros::endpoints::{Outlet, OUTLETS};

/// An input topic clients may publish on, under its resolved name.
#[derive(Debug, Clone)]
pub(crate) struct InputInfo {
    pub(crate) topic: String,
    pub(crate) endpoint: Endpoint,
    /// The instance (the k-th `~/<muscle>/...` topic).
    pub(crate) k: usize,
    pub(crate) type_name: &'static str,
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

/// Why a client cannot publish on a topic; names and types quoted as excerpts.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub(crate) enum InputRefused {
    /// An input topic, of another type.
    #[error("{topic} takes {expected}, not {given}")]
    WrongType {
        /// The topic.
        topic: String,
        /// Its type.
        expected: String,
        /// The type the client gave.
        given: String,
    },
    /// Not an input topic of this node.
    #[error("{topic} is not an input topic of this node (inputs: {inputs})")]
    NotAnInput {
        /// The topic.
        topic: String,
        /// The input topics, joined.
        inputs: String,
    },
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

/// Everything the live view serves, resolved once at start-up.
#[derive(Debug, Clone)]
pub(crate) struct Catalogue {
    pub(crate) channels: Vec<ChannelInfo>,
    /// The input topics.
    pub(crate) inputs: Vec<InputInfo>,
    /// `advertiseServices`, as sent to each client.
    pub(crate) services_json: String,
}

impl Catalogue {
    /// The channels, inputs and services of the endpoints the node has, under their resolved
    /// names; a channel's id is its [`Outlet`]'s index + 1.
    pub(crate) fn new(names: &Names) -> Result<Self, LiveError> {
        let mut channels = Vec::new();
        let mut inputs = Vec::new();
        let mut services = Vec::new();
        for r in names.in_table_order() {
            let type_name = r.spec().type_name;
            match r.spec().live {
                Live::No => {}
                Live::Outlet => {
                    let Some(outlet) = Outlet::of(r.endpoint) else {
                        continue;
                    };
                    channels.push(ChannelInfo {
                        outlet,
                        id: outlet.index() as u32 + 1,
                        topic: r.name.clone(),
                        type_name,
                        schema: ros2msg_schema(type_name, &definition)
                            .map_err(LiveError::Schema)?,
                    });
                }
                Live::Input => inputs.push(InputInfo {
                    topic: r.name.clone(),
                    endpoint: r.endpoint,
                    k: r.k,
                    type_name,
                }),
                Live::Service(service) => services.push((service, r.name.as_str(), type_name)),
            }
        }
        let services_json = services_json(&services)?;
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

    /// The input topic `topic` of type `type_name` (endpoint and instance), or why a client
    /// cannot publish on it.
    pub(crate) fn input(
        &self,
        topic: &str,
        type_name: &str,
    ) -> Result<(Endpoint, usize), InputRefused> {
        // Clients name types `pkg/msg/Type` or `pkg/Type`.
        let normal = match type_name.split('/').collect::<Vec<_>>()[..] {
            [pkg, ty] => format!("{pkg}/msg/{ty}"),
            _ => type_name.to_string(),
        };
        let excerpt = muscle_actuator_core::text::excerpt;
        match self.inputs.iter().find(|i| i.topic == topic) {
            Some(i) if i.type_name == normal => Ok((i.endpoint, i.k)),
            Some(i) => Err(InputRefused::WrongType {
                topic: excerpt(topic),
                expected: i.type_name.to_string(),
                given: excerpt(type_name),
            }),
            None => Err(InputRefused::NotAnInput {
                topic: excerpt(topic),
                inputs: excerpt(
                    &self
                        .inputs
                        .iter()
                        .map(|i| i.topic.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                ),
            }),
        }
    }
}

/// A service's request or response description, in the form of both the current and the older
/// specification (`requestSchema` / `responseSchema`).
fn part(schema_name: &str, lookup_name: &str) -> Result<(Value, String), LiveError> {
    let schema = ros2msg_schema(lookup_name, &service_part).map_err(LiveError::Schema)?;
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

/// `advertiseServices` for (service, resolved name, `pkg/srv/Type`).
fn services_json(served: &[(Service, &str, &str)]) -> Result<String, LiveError> {
    let mut services = Vec::new();
    for &(service, name, ty) in served {
        let mut parts = ty.split('/');
        let (pkg, srv) = (
            parts.next().unwrap_or_default(),
            parts.next_back().unwrap_or_default(),
        );
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

    use crate::ros::endpoints::{Endpoint as E, ENDPOINTS};
    use muscle_actuator_recording::runs::STATE_TYPE;

    /// A node `/m` (`prefix`) with one muscle, `/clock` when `clock`.
    fn names_under(prefix: &str, clock: bool) -> Names {
        let mut n = Names::default();
        for (e, name) in [
            (E::Activation, format!("{prefix}/activation")),
            (E::ActivationArray, format!("{prefix}/activation_array")),
            (E::MuscleCommand, format!("{prefix}/flexor/cmd_activation")),
            (E::Load, format!("{prefix}/external_load")),
            (E::State, format!("{prefix}/state")),
            (E::JointStates, "/joint_states".into()),
            (E::Diagnostics, "/diagnostics".into()),
            (E::Reset, format!("{prefix}/reset")),
            (E::Step, format!("{prefix}/step")),
            (E::Rosout, "/rosout".into()),
        ] {
            n.add(e, 0, name);
        }
        if clock {
            n.add(E::ClockOut, 0, "/clock".into());
        }
        n
    }

    fn names() -> Names {
        names_under("/m", false)
    }

    /// Every endpoint the table serves live is advertised (a channel, an input or a service)
    /// under its resolved name, with its type.
    #[test]
    fn every_live_endpoint_is_advertised() {
        let mut n = Names::default();
        for s in ENDPOINTS {
            n.add(s.endpoint, 0, format!("/t/{:?}", s.endpoint));
        }
        let c = Catalogue::new(&n).unwrap();
        let advertised: Value = serde_json::from_str(&c.advertise_json()).unwrap();
        let services: Value = serde_json::from_str(&c.services_json).unwrap();
        let mut live = 0;
        for s in ENDPOINTS {
            let name = format!("/t/{:?}", s.endpoint);
            let found = match s.live {
                Live::No => continue,
                Live::Outlet => advertised["channels"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .any(|ch| ch["topic"] == name.as_str() && ch["schemaName"] == s.type_name),
                Live::Input => c.input(&name, s.type_name).is_ok(),
                Live::Service(_) => services["services"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .any(|sv| sv["name"] == name.as_str() && sv["type"] == s.type_name),
            };
            assert!(
                found,
                "{:?} ({name}) is not in the live view's advertisement",
                s.endpoint
            );
            live += 1;
        }
        assert_eq!(c.channels.len(), OUTLETS);
        assert!(live >= 11, "{live}");
    }

    #[test]
    fn channels_carry_the_recordings_schemas() {
        let c = Catalogue::new(&names_under("/m", true)).unwrap();
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
        let state = muscle_actuator_recording::runs::channel("/m/state", STATE_TYPE).unwrap();
        assert_eq!(c.channels[0].schema, state.schema);
        assert!(c.channels[4]
            .schema
            .starts_with("builtin_interfaces/Time clock\n"));
        assert!(Catalogue::new(&names()).unwrap().channel(5).is_none());
    }

    #[test]
    fn services_carry_their_parts() {
        let c = Catalogue::new(&names()).unwrap();
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
        use muscle_actuator_recording::recording::schema::field_names;
        let layout: Value =
            serde_json::from_str(include_str!("../../../docs/foxglove-layout.json")).unwrap();
        let c = Catalogue::new(&names_under("/muscle_actuator", false)).unwrap();
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
            Ok((E::Activation, 0))
        );
    }

    #[test]
    fn inputs_are_checked_by_topic_and_type() {
        let c = Catalogue::new(&names()).unwrap();
        assert_eq!(
            c.input("/m/activation", "muscle_actuator_msgs/ActivationCommand"),
            Ok((E::Activation, 0))
        );
        assert_eq!(
            c.input("/m/flexor/cmd_activation", "std_msgs/msg/Float64"),
            Ok((E::MuscleCommand, 0))
        );
        assert!(c.input("/m/activation", "std_msgs/msg/Float64").is_err());
        assert!(c.input("/m/state", STATE_TYPE).is_err());
    }
}
