//! A topic is its row in [`ENDPOINTS`](crate::ros::endpoints::ENDPOINTS) plus its handler: the
//! input topic only the tests know (`~/test_excitation`, feature `test-topic`: its row, the file
//! `src/ros/inputs/test_excitation.rs` and that file's `mod` line) is, with no other edit, subscribed on DDS
//! (a peer's message reaches the muscles), listed in the DDS graph and in the rows the
//! interface's documentation must have, published on by a live-view client, recorded (its
//! channel in the MCAP file, with both messages), and replayed bit for bit.
//!
//! It runs the whole node in this process, with a DDS peer and a WebSocket client of its own,
//! so it needs a network of its own: `scripts/test-all.sh` runs it in a loopback-only network
//! namespace (`cargo test --features test-topic --lib -- --ignored one_place`).

use crate::ros::dds::Dds;
use crate::ros::endpoints::docs_table::expected_rows;
use muscle_actuator_recording::msgs::muscle_actuator_msgs::ActuatorState;
use muscle_actuator_recording::msgs::Float64;
use ros2_client::{MessageTypeName, Name, NodeName, NodeOptions};
use std::io::ErrorKind;
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use tungstenite::client::IntoClientRequest;
use tungstenite::Message;

const NODE: &str = "topic_test";
const TOPIC: &str = "/topic_test/test_excitation";
const FLOAT64: &str = "std_msgs/msg/Float64";

/// Waits up to 20 s for `f` to give something.
fn wait_for<T>(what: &str, mut f: impl FnMut() -> Option<T>) -> T {
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        if let Some(t) = f() {
            return t;
        }
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// A port no one listens on now.
fn free_port() -> u16 {
    let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    l.local_addr().unwrap().port()
}

/// A live-view client publishing on the test topic with JSON encoding.
fn live_publish(port: u16, value: f64) {
    let mut req = format!("ws://127.0.0.1:{port}")
        .into_client_request()
        .unwrap();
    req.headers_mut().insert(
        "Sec-WebSocket-Protocol",
        "foxglove.websocket.v1".parse().unwrap(),
    );
    let stream = wait_for("the live view", || {
        TcpStream::connect(("127.0.0.1", port)).ok()
    });
    let (mut ws, _) = tungstenite::client(req, stream).unwrap();
    let advertise = serde_json::json!({"op": "advertise", "channels": [
        {"id": 7, "topic": TOPIC, "encoding": "json", "schemaName": FLOAT64}
    ]});
    ws.send(Message::text(advertise.to_string())).unwrap();
    let mut frame = vec![0x01];
    frame.extend_from_slice(&7u32.to_le_bytes());
    frame.extend_from_slice(format!("{{\"data\": {value}}}").as_bytes());
    ws.send(Message::binary(frame)).unwrap();
    // Any status the server sends back is an error about the client's channel or message.
    ws.get_ref()
        .set_read_timeout(Some(Duration::from_millis(500)))
        .unwrap();
    loop {
        match ws.read() {
            Ok(Message::Text(t)) => assert!(!t.contains("\"op\":\"status\""), "{t}"),
            Ok(_) => {}
            Err(tungstenite::Error::Io(e))
                if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) =>
            {
                break
            }
            Err(e) => panic!("{e}"),
        }
    }
    let _ = ws.close(None);
}

/// The node's recording in `dir`.
fn recording_in(dir: &Path) -> PathBuf {
    let files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "mcap"))
        .collect();
    assert_eq!(files.len(), 1, "{files:?}");
    files[0].clone()
}

/// Every message of `topic` in the MCAP file, read with the `mcap` crate.
fn recorded(path: &Path, topic: &str) -> Vec<Float64> {
    let bytes = std::fs::read(path).unwrap();
    let mut out = Vec::new();
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        if m.channel.topic == topic {
            let schema = m.channel.schema.as_ref().unwrap();
            assert_eq!(schema.name, FLOAT64);
            out.push(muscle_actuator_recording::recording::decode_cdr(&m.data).unwrap());
        }
    }
    out
}

#[test]
#[ignore = "runs a node on DDS: scripts/test-all.sh runs it in a loopback-only network namespace"]
fn one_place_topic_is_subscribed_listed_served_recorded_and_replayed() {
    let row = (
        "sub".to_string(),
        "~/test_excitation".to_string(),
        FLOAT64.to_string(),
    );
    assert!(expected_rows().contains(&row), "not among the docs' rows");

    let dir = std::env::temp_dir().join(format!("topic_test_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let port = free_port();
    let argv: Vec<String> = [
        "--ros-args".to_string(),
        "-r".into(),
        format!("__node:={NODE}"),
        "-p".into(),
        format!("record_dir:={}", dir.display()),
        "-p".into(),
        format!("foxglove_port:={port}"),
    ]
    .to_vec();
    let node = std::thread::spawn(move || crate::ros::node::run(&argv));

    // A DDS peer: publishes on the topic and reads the node's state.
    let dds = Dds::start().unwrap();
    let mut peer = dds
        .context
        .new_node(
            NodeName::new("/", "topic_peer").unwrap(),
            NodeOptions::new().enable_rosout(false),
        )
        .unwrap();
    let qos = crate::ros::dds::qos_reliable(10);
    let topic = |name: &str, pkg: &str, ty: &str| {
        let (ns, base) = name.rsplit_once('/').unwrap();
        peer.create_topic(
            &Name::new(ns, base).unwrap(),
            MessageTypeName::new(pkg, ty),
            &qos,
        )
        .unwrap()
    };
    let excitation = topic(TOPIC, "std_msgs", "Float64");
    let state = topic("/topic_test/state", "muscle_actuator_msgs", "ActuatorState");
    let publisher = peer.create_publisher::<Float64>(&excitation, None).unwrap();
    let states = peer
        .create_subscription::<ActuatorState>(&state, None)
        .unwrap();
    let all_excited = |u: f64| {
        let mut seen = false;
        while let Ok(Some((s, _))) = states.take() {
            seen = !s.muscles.is_empty() && s.muscles.iter().all(|m| m.state.excitation == u);
        }
        seen
    };

    // Subscribed: a peer's message reaches every muscle.
    wait_for("the peer's excitation in the state", || {
        publisher.publish(Float64 { data: 0.7 }).unwrap();
        std::thread::sleep(Duration::from_millis(50));
        all_excited(0.7).then_some(())
    });
    // Listed: the DDS graph holds the topic with its type, as `ros2 topic list -t` shows it.
    wait_for("the topic in the DDS graph", || {
        dds.context
            .discovered_topics()
            .iter()
            .any(|t| {
                t.name == format!("rt{TOPIC}") && t.type_name == "std_msgs::msg::dds_::Float64_"
            })
            .then_some(())
    });
    // Served to the live view: a client's JSON message on it reaches every muscle.
    live_publish(port, 0.3);
    wait_for("the live client's excitation in the state", || {
        all_excited(0.3).then_some(())
    });

    signal_hook::low_level::raise(signal_hook::consts::SIGINT).unwrap();
    node.join().unwrap().unwrap();

    // Recorded as received, from DDS and from the live view.
    let path = recording_in(&dir);
    let values: Vec<f64> = recorded(&path, TOPIC).iter().map(|m| m.data).collect();
    assert!(values.contains(&0.7) && values.contains(&0.3), "{values:?}");
    assert!(values.iter().all(|&u| u == 0.7 || u == 0.3), "{values:?}");
    // Replayed: the inputs as applied give the recorded states again, bit for bit.
    let again = dir.join("again.mcap");
    let s = muscle_actuator_recording::runs::replay(&path, None, &again).unwrap();
    assert!(s.compared > 0 && s.identical == s.compared, "{s:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
