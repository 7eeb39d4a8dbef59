//! The `muscle_actuator` command line ([`muscle_actuator::cli`]).

fn main() -> std::process::ExitCode {
    muscle_actuator::cli::main()
}
