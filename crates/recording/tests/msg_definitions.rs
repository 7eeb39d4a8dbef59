//! The `.msg` files in `msg/msg/` are the single source of truth: the Rust message types of the
//! node must match them field for field (name, order, type, array-ness), recursively through
//! nested messages. The Rust side is read through serde (what actually goes on the wire), with
//! a serializer that records the field names and primitive types.

use muscle_actuator_core::sim::{JointSnapshot, MuscleSnapshot, MUSCLE_FIELD_COUNT};
use muscle_actuator_recording::msgs::muscle_actuator_msgs::{
    ActivationCommand, ActuatorState, ExternalLoad, MuscleState,
};
use muscle_actuator_recording::msgs::Time;
use muscle_actuator_recording::msgs::{
    DiagnosticArray, DiagnosticStatus, Header, JointState, KeyValue, TriggerRequest,
    TriggerResponse,
};
use serde::ser::{self, Serialize};
use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;

// ---------------------------------------------------------------------------------------------
// The Rust side: a serializer that records the shape of a value.

#[derive(Debug, Clone, PartialEq)]
enum Shape {
    Prim(&'static str),
    Seq(Box<Shape>),
    Struct(String, Vec<(String, Shape)>),
    /// An empty sequence: the element type cannot be seen.
    Unknown,
}

#[derive(Debug)]
struct Unsupported(String);
impl fmt::Display for Unsupported {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}
impl std::error::Error for Unsupported {}
impl ser::Error for Unsupported {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Unsupported(msg.to_string())
    }
}

struct Rec;

struct SeqRec(Option<Shape>);
struct StructRec(String, Vec<(String, Shape)>);

type R = Result<Shape, Unsupported>;

fn unsupported(what: &str) -> R {
    Err(Unsupported(format!("{what} is not a ROS 2 message type")))
}

impl ser::Serializer for Rec {
    type Ok = Shape;
    type Error = Unsupported;
    type SerializeSeq = SeqRec;
    type SerializeTuple = SeqRec;
    type SerializeTupleStruct = ser::Impossible<Shape, Unsupported>;
    type SerializeTupleVariant = ser::Impossible<Shape, Unsupported>;
    type SerializeMap = ser::Impossible<Shape, Unsupported>;
    type SerializeStruct = StructRec;
    type SerializeStructVariant = ser::Impossible<Shape, Unsupported>;

    fn serialize_bool(self, _: bool) -> R {
        Ok(Shape::Prim("bool"))
    }
    fn serialize_i8(self, _: i8) -> R {
        Ok(Shape::Prim("int8"))
    }
    fn serialize_i16(self, _: i16) -> R {
        Ok(Shape::Prim("int16"))
    }
    fn serialize_i32(self, _: i32) -> R {
        Ok(Shape::Prim("int32"))
    }
    fn serialize_i64(self, _: i64) -> R {
        Ok(Shape::Prim("int64"))
    }
    fn serialize_u8(self, _: u8) -> R {
        Ok(Shape::Prim("uint8"))
    }
    fn serialize_u16(self, _: u16) -> R {
        Ok(Shape::Prim("uint16"))
    }
    fn serialize_u32(self, _: u32) -> R {
        Ok(Shape::Prim("uint32"))
    }
    fn serialize_u64(self, _: u64) -> R {
        Ok(Shape::Prim("uint64"))
    }
    fn serialize_f32(self, _: f32) -> R {
        Ok(Shape::Prim("float32"))
    }
    fn serialize_f64(self, _: f64) -> R {
        Ok(Shape::Prim("float64"))
    }
    fn serialize_char(self, _: char) -> R {
        unsupported("char")
    }
    fn serialize_str(self, _: &str) -> R {
        Ok(Shape::Prim("string"))
    }
    fn serialize_bytes(self, _: &[u8]) -> R {
        Ok(Shape::Seq(Box::new(Shape::Prim("uint8"))))
    }
    fn serialize_none(self) -> R {
        unsupported("Option")
    }
    fn serialize_some<T: ?Sized + Serialize>(self, _: &T) -> R {
        unsupported("Option")
    }
    fn serialize_unit(self) -> R {
        unsupported("()")
    }
    fn serialize_unit_struct(self, _: &'static str) -> R {
        unsupported("a unit struct")
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> R {
        unsupported("an enum")
    }
    fn serialize_newtype_struct<T: ?Sized + Serialize>(self, _: &'static str, v: &T) -> R {
        v.serialize(Rec)
    }
    fn serialize_newtype_variant<T: ?Sized + Serialize>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> R {
        unsupported("an enum")
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<SeqRec, Unsupported> {
        Ok(SeqRec(None))
    }
    fn serialize_tuple(self, _: usize) -> Result<SeqRec, Unsupported> {
        Ok(SeqRec(None))
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, Unsupported> {
        Err(Unsupported("tuple struct".into()))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, Unsupported> {
        Err(Unsupported("enum".into()))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, Unsupported> {
        Err(Unsupported("map".into()))
    }
    fn serialize_struct(self, name: &'static str, _: usize) -> Result<StructRec, Unsupported> {
        Ok(StructRec(name.into(), vec![]))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, Unsupported> {
        Err(Unsupported("enum".into()))
    }
}

impl ser::SerializeSeq for SeqRec {
    type Ok = Shape;
    type Error = Unsupported;
    fn serialize_element<T: ?Sized + Serialize>(&mut self, v: &T) -> Result<(), Unsupported> {
        let s = v.serialize(Rec)?;
        if self.0.is_none() {
            self.0 = Some(s);
        }
        Ok(())
    }
    fn end(self) -> R {
        Ok(Shape::Seq(Box::new(self.0.unwrap_or(Shape::Unknown))))
    }
}
impl ser::SerializeTuple for SeqRec {
    type Ok = Shape;
    type Error = Unsupported;
    fn serialize_element<T: ?Sized + Serialize>(&mut self, v: &T) -> Result<(), Unsupported> {
        ser::SerializeSeq::serialize_element(self, v)
    }
    fn end(self) -> R {
        ser::SerializeSeq::end(self)
    }
}
impl ser::SerializeStruct for StructRec {
    type Ok = Shape;
    type Error = Unsupported;
    fn serialize_field<T: ?Sized + Serialize>(
        &mut self,
        key: &'static str,
        v: &T,
    ) -> Result<(), Unsupported> {
        self.1.push((key.into(), v.serialize(Rec)?));
        Ok(())
    }
    fn end(self) -> R {
        Ok(Shape::Struct(self.0, self.1))
    }
}

fn shape_of<T: Serialize>(v: &T) -> Shape {
    v.serialize(Rec)
        .expect("message types serialize as structs")
}

// ---------------------------------------------------------------------------------------------
// The .msg side.

/// Definitions of the standard types the node uses (ROS 2 kilted), `pkg/Type` -> text.
fn standard_definitions() -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    let mut add = |k: &str, v: &str| {
        m.insert(k.to_string(), v.to_string());
    };
    add("builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n");
    add(
        "std_msgs/Header",
        "builtin_interfaces/Time stamp\nstring frame_id\n",
    );
    add(
        "sensor_msgs/JointState",
        "std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\n\
         float64[] effort\n",
    );
    add("diagnostic_msgs/KeyValue", "string key\nstring value\n");
    add(
        "diagnostic_msgs/DiagnosticStatus",
        "byte OK=0\nbyte WARN=1\nbyte ERROR=2\nbyte STALE=3\nbyte level\nstring name\n\
         string message\nstring hardware_id\nKeyValue[] values\n",
    );
    add(
        "diagnostic_msgs/DiagnosticArray",
        "std_msgs/Header header\nDiagnosticStatus[] status\n",
    );
    // An empty structure carries one placeholder byte in the ROS 2 IDL.
    add(
        "std_srvs/TriggerRequest",
        "uint8 structure_needs_at_least_one_member\n",
    );
    add("std_srvs/TriggerResponse", "bool success\nstring message\n");
    m
}

fn msg_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("msg")
        .join("msg")
}

fn project_definitions() -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    for entry in std::fs::read_dir(msg_dir()).expect("msg/msg exists") {
        let path = entry.expect("readable dir entry").path();
        if path.extension().and_then(|e| e.to_str()) == Some("msg") {
            let stem = path
                .file_stem()
                .and_then(|s| s.to_str())
                .expect("utf-8 file name")
                .to_string();
            let text = std::fs::read_to_string(&path).expect("readable .msg");
            m.insert(format!("muscle_actuator_msgs/{stem}"), text);
        }
    }
    m
}

/// One field of a .msg: (name, type as written).
fn parse_fields(text: &str) -> Vec<(String, String)> {
    text.lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .filter(|l| !l.is_empty())
        .filter(|l| !l.contains('=')) // constants
        .map(|l| {
            let mut parts = l.split_whitespace();
            let ty = parts.next().expect("a type").to_string();
            let name = parts.next().expect("a field name").to_string();
            assert!(
                parts.next().is_none(),
                "default values are not used here: {l:?}"
            );
            (name, ty)
        })
        .collect()
}

fn primitive(ty: &str) -> Option<&'static str> {
    Some(match ty {
        "bool" => "bool",
        "byte" | "char" | "uint8" => "uint8",
        "int8" => "int8",
        "int16" => "int16",
        "uint16" => "uint16",
        "int32" => "int32",
        "uint32" => "uint32",
        "int64" => "int64",
        "uint64" => "uint64",
        "float32" => "float32",
        "float64" => "float64",
        "string" => "string",
        _ => return None,
    })
}

/// The shape a .msg type prescribes, resolved through `defs` (`pkg/Type`).
fn expected_shape(pkg: &str, ty: &str, defs: &BTreeMap<String, String>) -> Shape {
    if let Some(elem) = ty
        .strip_suffix(']')
        .and_then(|t| t.rsplit_once('[').map(|(e, _)| e))
    {
        return Shape::Seq(Box::new(expected_shape(pkg, elem, defs)));
    }
    if let Some(p) = primitive(ty) {
        return Shape::Prim(p);
    }
    let (pkg, name) = match ty.split_once('/') {
        Some((p, n)) => (p.to_string(), n.to_string()),
        None if ty == "Header" => ("std_msgs".into(), "Header".into()),
        None => (pkg.to_string(), ty.to_string()),
    };
    let key = format!("{pkg}/{name}");
    let text = defs
        .get(&key)
        .unwrap_or_else(|| panic!("no definition of {key}"));
    let fields = parse_fields(text)
        .into_iter()
        .map(|(n, t)| (n, expected_shape(&pkg, &t, defs)))
        .collect();
    Shape::Struct(name, fields)
}

fn all_defs() -> BTreeMap<String, String> {
    let mut d = standard_definitions();
    d.extend(project_definitions());
    d
}

/// Compares, with a path in the message for the first difference.
fn compare(path: &str, rust: &Shape, msg: &Shape) -> Result<(), String> {
    match (rust, msg) {
        (Shape::Prim(a), Shape::Prim(b)) if a == b => Ok(()),
        (Shape::Seq(a), Shape::Seq(b)) => compare(&format!("{path}[]"), a, b),
        (Shape::Struct(rn, rf), Shape::Struct(mn, mf)) => {
            if rn != mn {
                return Err(format!("{path}: Rust type {rn} stands for .msg type {mn}"));
            }
            let rnames: Vec<&str> = rf.iter().map(|(n, _)| n.as_str()).collect();
            let mnames: Vec<&str> = mf.iter().map(|(n, _)| n.as_str()).collect();
            if rnames != mnames {
                return Err(format!(
                    "{path} ({mn}): fields differ:\n  Rust: {rnames:?}\n  .msg: {mnames:?}"
                ));
            }
            for ((n, a), (_, b)) in rf.iter().zip(mf) {
                compare(&format!("{path}.{n}"), a, b)?;
            }
            Ok(())
        }
        (Shape::Unknown, _) => Err(format!(
            "{path}: empty sequence in the Rust sample; give it one element"
        )),
        (a, b) => Err(format!("{path}: Rust has {a:?}, the .msg says {b:?}")),
    }
}

fn check<T: Serialize>(pkg_type: &str, sample: &T) {
    let defs = all_defs();
    let (pkg, ty) = pkg_type.split_once('/').expect("pkg/Type");
    let want = expected_shape(pkg, ty, &defs);
    let got = shape_of(sample);
    // The Rust struct for a service part is named like the part (TriggerRequest).
    if let Err(e) = compare(ty, &got, &want) {
        panic!("{pkg_type}: the Rust type does not match its definition: {e}");
    }
}

fn header() -> Header {
    Header {
        stamp: Time::ZERO,
        frame_id: String::new(),
    }
}

fn muscle() -> MuscleState {
    MuscleState {
        name: "flexor".into(),
        state: MuscleSnapshot::default(),
    }
}

// ---------------------------------------------------------------------------------------------

#[test]
fn the_interface_package_has_the_four_messages() {
    let defs = project_definitions();
    let names: Vec<&str> = defs.keys().map(|k| k.as_str()).collect();
    assert_eq!(
        names,
        [
            "muscle_actuator_msgs/ActivationCommand",
            "muscle_actuator_msgs/ActuatorState",
            "muscle_actuator_msgs/ExternalLoad",
            "muscle_actuator_msgs/MuscleState",
        ]
    );
    let cmake = std::fs::read_to_string(msg_dir().join("../CMakeLists.txt")).unwrap();
    for n in [
        "ActivationCommand",
        "ExternalLoad",
        "MuscleState",
        "ActuatorState",
    ] {
        assert!(
            cmake.contains(&format!("\"msg/{n}.msg\"")),
            "CMakeLists.txt does not generate {n}"
        );
    }
    let pkg = std::fs::read_to_string(msg_dir().join("../package.xml")).unwrap();
    assert!(pkg.contains("<name>muscle_actuator_msgs</name>"));
}

#[test]
fn activation_command_matches() {
    check(
        "muscle_actuator_msgs/ActivationCommand",
        &ActivationCommand {
            header: header(),
            muscle: vec!["flexor".into()],
            excitation: vec![0.5],
        },
    );
}

#[test]
fn external_load_matches() {
    check(
        "muscle_actuator_msgs/ExternalLoad",
        &ExternalLoad {
            header: header(),
            joint: vec!["elbow".into()],
            torque: vec![1.0],
        },
    );
}

#[test]
fn muscle_state_matches() {
    check("muscle_actuator_msgs/MuscleState", &muscle());
}

#[test]
fn actuator_state_matches() {
    check(
        "muscle_actuator_msgs/ActuatorState",
        &ActuatorState {
            header: header(),
            model: "huxley".into(),
            tick: 1,
            joint: vec!["elbow".into()],
            joints: vec![JointSnapshot::default()],
            stiffness_matrix: vec![0.0],
            muscles: vec![muscle()],
        },
    );
}

/// The messages built from the one field list survive CDR both ways, field for field, and a
/// message whose per-joint arrays disagree with its joints is refused.
#[test]
fn actuator_state_round_trips_through_cdr() {
    let joint = |k: f64| JointSnapshot::from_values([1.0 + k, 2.0 + k, 3.0 + k, 4.0 + k, 5.0 + k]);
    let mut values = [0.0; MUSCLE_FIELD_COUNT];
    for (k, v) in values.iter_mut().enumerate() {
        *v = k as f64 + 0.25;
    }
    let msg = ActuatorState {
        header: header(),
        model: "hill".into(),
        tick: 7,
        joint: vec!["shoulder".into(), "elbow".into()],
        joints: vec![joint(0.0), joint(10.0)],
        stiffness_matrix: vec![1.0, 0.5, 0.5, 2.0],
        muscles: vec![MuscleState {
            name: "BIClong".into(),
            state: MuscleSnapshot::from_values(values),
        }],
    };
    let bytes = muscle_actuator_recording::recording::encode_cdr(&msg).unwrap();
    let back: ActuatorState = muscle_actuator_recording::recording::decode_cdr(&bytes).unwrap();
    assert_eq!(back, msg);
    assert_eq!(back.column(1), vec![2.0, 12.0]);
    assert_eq!(back.muscles[0].state.get("crossbridge_energy"), Some(15.25));

    let mut bad = msg.clone();
    bad.stiffness_matrix.pop();
    let bytes = muscle_actuator_recording::recording::encode_cdr(&bad).unwrap();
    let e = muscle_actuator_recording::recording::decode_cdr::<ActuatorState>(&bytes).unwrap_err();
    assert!(e.to_string().contains("stiffness_matrix"), "{e}");
}

#[test]
fn standard_types_match() {
    check(
        "sensor_msgs/JointState",
        &JointState {
            header: header(),
            name: vec!["elbow".into()],
            position: vec![0.0],
            velocity: vec![0.0],
            effort: vec![0.0],
        },
    );
    check(
        "diagnostic_msgs/DiagnosticArray",
        &DiagnosticArray {
            header: header(),
            status: vec![DiagnosticStatus {
                level: 0,
                name: "n".into(),
                message: "m".into(),
                hardware_id: "h".into(),
                values: vec![KeyValue {
                    key: "k".into(),
                    value: "v".into(),
                }],
            }],
        },
    );
    check(
        "std_srvs/TriggerRequest",
        &TriggerRequest {
            structure_needs_at_least_one_member: 0,
        },
    );
    check(
        "std_srvs/TriggerResponse",
        &TriggerResponse {
            success: true,
            message: String::new(),
        },
    );
}

#[test]
fn the_comparison_catches_a_difference() {
    // A reordered or retyped field must fail: the check can fail.
    #[derive(serde::Serialize)]
    struct ExternalLoad {
        header: Header,
        torque: Vec<f64>,
        joint: Vec<String>,
    }
    let defs = all_defs();
    let want = expected_shape("muscle_actuator_msgs", "ExternalLoad", &defs);
    let got = shape_of(&ExternalLoad {
        header: header(),
        torque: vec![0.0],
        joint: vec!["elbow".into()],
    });
    assert!(compare("ExternalLoad", &got, &want).is_err());

    #[derive(serde::Serialize)]
    struct MuscleState {
        name: String,
        excitation: f32,
    }
    let got = shape_of(&MuscleState {
        name: String::new(),
        excitation: 0.0,
    });
    let want = Shape::Struct(
        "MuscleState".into(),
        vec![
            ("name".into(), Shape::Prim("string")),
            ("excitation".into(), Shape::Prim("float64")),
        ],
    );
    assert!(compare("MuscleState", &got, &want).is_err());
}

/// The messages document themselves: each starts with a description comment, every float field
/// states its unit (or says it is dimensionless), and `ActuatorState` names every model the
/// program has, and no other, in its `MODEL_*` constants.
#[test]
fn messages_document_units_and_model_names() {
    for entry in std::fs::read_dir(msg_dir()).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        assert!(
            text.starts_with("# "),
            "{name} starts without a description"
        );
        for line in text.lines().filter(|l| l.starts_with("float64")) {
            let comment = line.split_once('#').map(|(_, c)| c).unwrap_or("");
            let has_unit = [
                "rad",
                "N m",
                "N/m",
                "N",
                "m/s",
                " m",
                "J",
                "dimensionless",
                " h",
            ]
            .iter()
            .any(|u| comment.contains(u));
            assert!(has_unit, "{name}: no unit in {line:?}");
        }
    }
    let text = std::fs::read_to_string(msg_dir().join("ActuatorState.msg")).unwrap();
    let constants: Vec<(String, String)> = text
        .lines()
        .filter_map(|l| l.strip_prefix("string MODEL_"))
        .map(|l| {
            let (name, value) = l.split_once('=').unwrap();
            (name.to_string(), value.trim_matches('"').to_string())
        })
        .collect();
    // One constant per entry of MODELS, in its order, named after the model.
    let models: Vec<(String, String)> = muscle_actuator_core::physics::models::ModelKind::all()
        .map(|m| {
            let name = m.name().to_ascii_uppercase().replace('-', "_");
            (name, m.name().to_string())
        })
        .collect();
    assert_eq!(constants, models);
}
