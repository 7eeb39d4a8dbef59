//! rosbag2's YAML in a recording: a channel's `offered_qos_profiles` and the bag's
//! `metadata.yaml` (the `rosbag2` metadata record's `serialized_metadata`), as serde structs
//! written by `serde_norway`. The keys and their order are those of rosbag2's version-9 metadata
//! (rosbag2_storage `yaml.hpp`, kilted), which rosbag2_storage_mcap stores in the file and
//! `ros2 bag info` and the `rosbags` reader read.

use serde::Serialize;

/// The rosbag2 metadata version written.
pub(crate) const METADATA_VERSION: u32 = 9;
/// The ROS distribution named in the metadata.
pub(crate) const ROS_DISTRO: &str = "kilted";

/// A ROS duration of rosbag2's QoS YAML: seconds and nanoseconds.
#[derive(Debug, Clone, Copy, Serialize)]
struct RosDuration {
    sec: i64,
    nsec: i64,
}

/// rmw's "infinite" duration (`RMW_DURATION_INFINITE`, i64::MAX ns), as rosbag2 writes it.
const INFINITE: RosDuration = RosDuration {
    sec: 9_223_372_036,
    nsec: 854_775_807,
};

/// One offered QoS profile, rosbag2's version-9 form (names of the policies, not numbers).
#[derive(Debug, Clone, Serialize)]
struct QosProfile {
    history: &'static str,
    depth: u32,
    reliability: &'static str,
    durability: &'static str,
    deadline: RosDuration,
    lifespan: RosDuration,
    liveliness: &'static str,
    liveliness_lease_duration: RosDuration,
    avoid_ros_namespace_conventions: bool,
}

/// The `offered_qos_profiles` value of one keep-last(`depth`) endpoint, reliable or best
/// effort, transient-local or volatile, in rosbag2's YAML form (a list of one profile).
pub fn qos_yaml(
    reliable: bool,
    transient_local: bool,
    depth: u32,
) -> Result<String, serde_norway::Error> {
    let profile = QosProfile {
        history: "keep_last",
        depth,
        reliability: if reliable { "reliable" } else { "best_effort" },
        durability: if transient_local {
            "transient_local"
        } else {
            "volatile"
        },
        deadline: INFINITE,
        lifespan: INFINITE,
        liveliness: "automatic",
        liveliness_lease_duration: INFINITE,
        avoid_ros_namespace_conventions: false,
    };
    serde_norway::to_string(&[profile])
}

#[derive(Serialize)]
struct BagFile<'a> {
    rosbag2_bagfile_information: BagInformation<'a>,
}

#[derive(Serialize)]
struct BagInformation<'a> {
    version: u32,
    storage_identifier: &'static str,
    duration: Nanoseconds,
    starting_time: NanosecondsSinceEpoch,
    message_count: u64,
    topics_with_message_count: Vec<TopicWithCount<'a>>,
    compression_format: &'static str,
    compression_mode: &'static str,
    relative_file_paths: [&'static str; 0],
    files: [&'static str; 0],
    custom_data: Option<()>,
    ros_distro: &'static str,
}

#[derive(Serialize)]
struct Nanoseconds {
    nanoseconds: u64,
}

#[derive(Serialize)]
struct NanosecondsSinceEpoch {
    nanoseconds_since_epoch: u64,
}

#[derive(Serialize)]
struct TopicWithCount<'a> {
    topic_metadata: TopicMetadata<'a>,
    message_count: u64,
}

#[derive(Serialize)]
struct TopicMetadata<'a> {
    name: &'a str,
    #[serde(rename = "type")]
    type_name: &'a str,
    serialization_format: &'static str,
    /// A YAML text inside the YAML, as rosbag2 stores it.
    offered_qos_profiles: &'a str,
    type_description_hash: &'a str,
}

/// One topic of a bag, with its message count.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Topic<'a> {
    /// Topic name.
    pub name: &'a str,
    /// Type name `pkg/msg/Type`.
    pub type_name: &'a str,
    /// Its `offered_qos_profiles` text ([`qos_yaml`]).
    pub(crate) qos_yaml: &'a str,
    /// REP-2016 type hash, when known.
    pub type_hash: Option<&'a str>,
    /// Messages recorded.
    pub message_count: u64,
}

/// The bag's `metadata.yaml`: its `topics` (log times from `first` to `last`, ns; both ignored
/// when there are no messages), stored in the MCAP file itself.
pub(crate) fn metadata_yaml(
    topics: &[Topic],
    first: u64,
    last: u64,
) -> Result<String, serde_norway::Error> {
    let total: u64 = topics.iter().map(|t| t.message_count).sum();
    let (start, end) = if total == 0 { (0, 0) } else { (first, last) };
    let bag = BagFile {
        rosbag2_bagfile_information: BagInformation {
            version: METADATA_VERSION,
            storage_identifier: "mcap",
            duration: Nanoseconds {
                nanoseconds: end - start,
            },
            starting_time: NanosecondsSinceEpoch {
                nanoseconds_since_epoch: start,
            },
            message_count: total,
            topics_with_message_count: topics
                .iter()
                .map(|t| TopicWithCount {
                    topic_metadata: TopicMetadata {
                        name: t.name,
                        type_name: t.type_name,
                        serialization_format: "cdr",
                        offered_qos_profiles: t.qos_yaml,
                        type_description_hash: t.type_hash.unwrap_or(""),
                    },
                    message_count: t.message_count,
                })
                .collect(),
            compression_format: "",
            compression_mode: "",
            relative_file_paths: [],
            files: [],
            custom_data: None,
            ros_distro: ROS_DISTRO,
        },
    };
    serde_norway::to_string(&bag)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_norway::Value;

    fn topic<'a>(name: &'a str, hash: Option<&'a str>, qos: &'a str, n: u64) -> Topic<'a> {
        Topic {
            name,
            type_name: "std_msgs/msg/String",
            qos_yaml: qos,
            type_hash: hash,
            message_count: n,
        }
    }

    /// The QoS text reads back as rosbag2's version-9 profile (the keys rosbags' `parse_qos`
    /// and rosbag2's `yaml.hpp` read).
    #[test]
    fn the_qos_profile_reads_back_with_every_policy() {
        let v: Value = serde_norway::from_str(&qos_yaml(false, true, 7).unwrap()).unwrap();
        let p = &v.as_sequence().unwrap()[0];
        assert_eq!(p["history"], "keep_last");
        assert_eq!(p["depth"], 7);
        assert_eq!(p["reliability"], "best_effort");
        assert_eq!(p["durability"], "transient_local");
        assert_eq!(p["liveliness"], "automatic");
        for k in ["deadline", "lifespan", "liveliness_lease_duration"] {
            let ns = p[k]["sec"].as_i64().unwrap() * 1_000_000_000 + p[k]["nsec"].as_i64().unwrap();
            assert_eq!(ns, i64::MAX, "{k}");
        }
        assert_eq!(p["avoid_ros_namespace_conventions"], false);
        assert!(qos_yaml(true, false, 10)
            .unwrap()
            .contains("reliability: reliable\n"));
    }

    /// The metadata reads back with its counts, times and each topic's QoS text unchanged.
    #[test]
    fn the_metadata_reads_back_with_its_topics() {
        let qos = qos_yaml(true, false, 10).unwrap();
        let topics = [
            topic("/a", Some("RIHS01_00"), &qos, 3),
            topic("/b", None, &qos, 0),
        ];
        let y = metadata_yaml(&topics, 5_000, 9_000).unwrap();
        let v: Value = serde_norway::from_str(&y).unwrap();
        let info = &v["rosbag2_bagfile_information"];
        assert_eq!(info["version"], 9);
        assert_eq!(info["storage_identifier"], "mcap");
        assert_eq!(info["duration"]["nanoseconds"], 4_000);
        assert_eq!(info["starting_time"]["nanoseconds_since_epoch"], 5_000);
        assert_eq!(info["message_count"], 3);
        assert_eq!(info["ros_distro"], "kilted");
        assert_eq!(info["compression_format"], "");
        assert!(info["custom_data"].is_null());
        assert_eq!(info["files"].as_sequence().unwrap().len(), 0);
        let topics = info["topics_with_message_count"].as_sequence().unwrap();
        assert_eq!(topics.len(), 2);
        let t = &topics[0]["topic_metadata"];
        assert_eq!(
            (t["name"].as_str(), t["type"].as_str()),
            (Some("/a"), Some("std_msgs/msg/String"))
        );
        assert_eq!(t["offered_qos_profiles"].as_str(), Some(qos.as_str()));
        assert_eq!(t["type_description_hash"], "RIHS01_00");
        assert_eq!(topics[0]["message_count"], 3);
        assert_eq!(topics[1]["topic_metadata"]["type_description_hash"], "");
        // No messages: no times.
        let none = [topic("/a", None, &qos, 0)];
        let v: Value = serde_norway::from_str(&metadata_yaml(&none, 5, 9).unwrap()).unwrap();
        assert_eq!(
            v["rosbag2_bagfile_information"]["duration"]["nanoseconds"],
            0
        );
    }
}
