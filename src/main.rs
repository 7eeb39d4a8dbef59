fn main() {
    println!("muscle_actuator");
}
