//! The recording crate's copies of the message definitions (crates/recording/msg/, which its
//! recordings' `ros2msg` schemas embed, so that the crate builds from its own folder) are the
//! interface package's own (msg/msg/, which colcon builds and rclpy peers use), byte for byte,
//! and there is one copy for every definition.

use std::path::Path;

#[test]
fn the_recording_crates_message_definitions_are_the_interface_packages() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let names = |dir: &Path| {
        let mut n: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        n.sort();
        n
    };
    let package = root.join("msg/msg");
    let copies = root.join("crates/recording/msg");
    assert_eq!(names(&package), names(&copies));
    assert_eq!(names(&package).len(), 4);
    for name in names(&package) {
        assert_eq!(
            std::fs::read(package.join(&name)).unwrap(),
            std::fs::read(copies.join(&name)).unwrap(),
            "{name}: the copy in crates/recording/msg/ differs from msg/msg/"
        );
    }
}
