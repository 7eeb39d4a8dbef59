//! What is observable about one muscle and one joint at an instant, defined once: their fields,
//! with units, in the order of `MuscleState.msg` and of `ActuatorState.msg`'s per-joint arrays.
//! [`Mtu`](crate::physics::mtu::Mtu) fills a [`MuscleSnapshot`] directly, every field named
//! (a field added here and filled nowhere is a compile error), its energetics from the
//! stepping's [`EnergeticsOutputs`]; the message
//! conversion, the CSV, the recorder, `compare` and replay iterate these lists
//! (`crates/recording/tests/msg_definitions.rs` keeps them in step with the `.msg` files).

/// Defines a struct of named `f64` observables together with its field list.
macro_rules! observables {
    (
        $(#[$meta:meta])*
        pub struct $name:ident [$count:ident] {
            $( $(#[$fmeta:meta])* $field:ident : $unit:literal, )*
        }
    ) => {
        /// Number of fields of the struct below.
        pub const $count: usize = [$(stringify!($field)),*].len();

        $(#[$meta])*
        #[derive(Debug, Clone, Copy, Default, PartialEq)]
        pub struct $name {
            $( $(#[$fmeta])* pub $field: f64, )*
        }

        impl $name {
            /// The field names, in message order.
            pub const FIELDS: [&'static str; $count] = [$(stringify!($field)),*];
            /// Their units (SI), in the same order.
            pub const UNITS: [&'static str; $count] = [$($unit),*];

            /// The values, in field order.
            pub fn values(&self) -> [f64; $count] {
                [$(self.$field),*]
            }

            /// From values in field order.
            pub fn from_values(v: [f64; $count]) -> Self {
                let [$($field),*] = v;
                Self { $($field),* }
            }

            /// The value of the field called `name`.
            pub fn get(&self, name: &str) -> Option<f64> {
                Self::index_of(name).map(|k| self.values()[k])
            }

            /// The position of the field called `name`.
            pub fn index_of(name: &str) -> Option<usize> {
                Self::FIELDS.iter().position(|f| *f == name)
            }
        }
    };
}

observables! {
    /// State of one muscle–tendon unit after a tick (the fields of `MuscleState.msg` after its
    /// name, SI units).
    pub struct MuscleSnapshot [MUSCLE_FIELD_COUNT] {
        /// Neural excitation u in force during the tick, [0, 1].
        excitation: "1",
        /// Activation a, [0, 1].
        activation: "1",
        /// Tendon force F_SE, N.
        force: "N",
        /// Contractile-element force F_CE, N.
        ce_force: "N",
        /// Parallel-element force F_P (spring only), N.
        pe_force: "N",
        /// Fibre length l_m, m.
        fiber_length: "m",
        /// Fibre lengthening velocity dl_m/dt, m/s.
        fiber_velocity: "m/s",
        /// Tendon length l_t, m.
        tendon_length: "m",
        /// Contractile-element stiffness k_CE, N/m.
        stiffness: "N/m",
        /// Muscle–tendon-unit stiffness (fibre and tendon in series), N/m.
        mtu_stiffness: "N/m",
        /// Distribution-Moment state Q0 (0 for the Hill model).
        q0: "1",
        /// Distribution-Moment state Q1.
        q1: "1",
        /// Distribution-Moment state Q2.
        q2: "1",
        /// Tendon strain energy, J.
        tendon_energy: "J",
        /// Parallel-element strain energy, J.
        fiber_energy: "J",
        /// Cross-bridge elastic energy, J.
        crossbridge_energy: "J",
        /// Metabolic power, W: the bridges' ATP at detachment plus the calcium handling for
        /// the Huxley models, the phenomenological model's for Hill (docs/model.md §11.6).
        metabolic_power: "W",
        /// Activation heat rate (phenomenological: activation and maintenance), W.
        activation_heat_rate: "W",
        /// Shortening and lengthening heat rate (Huxley models: the bridges' heat), W.
        shortening_heat_rate: "W",
        /// Work rate of the contractile element counted in the metabolic power, W (shortening
        /// positive).
        work_rate: "W",
        /// Rate of change of the energy the attached bridges hold (0 for Hill), W; the four
        /// parts above and this sum to the metabolic power.
        bridge_storage_rate: "W",
        /// ATP rate, mol/s (Hill: the metabolic power in ATP at the energy per ATP).
        atp_rate: "mol/s",
        /// Metabolic energy since start (the integral of the metabolic power), J.
        metabolic_energy: "J",
        /// The phenomenological model's metabolic power, for every model, W.
        phenomenological_power: "W",
        /// The phenomenological model's energy since start, J.
        phenomenological_energy: "J",
    }
}

observables! {
    /// State of one joint after a tick (the per-joint arrays of `ActuatorState.msg`, in order).
    pub struct JointSnapshot [JOINT_FIELD_COUNT] {
        /// Angle θ, rad (positive: the direction of the muscles with positive moment arms).
        position: "rad",
        /// Angular velocity ω, rad/s.
        velocity: "rad/s",
        /// Net muscle torque Σ_i r_i F_SE,i, N m.
        torque: "N m",
        /// External load torque in force during the tick, N m.
        external_torque: "N m",
        /// Joint stiffness K_jj (the diagonal of the stiffness matrix), N m/rad.
        stiffness: "N m/rad",
    }
}

/// The energetics fields of a [`MuscleSnapshot`], as the stepping has them: rates at the tick's
/// end from the element that was stepped, energies integrated over the ticks (`sim::energy`).
/// The names and units are the snapshot's.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergeticsOutputs {
    /// Metabolic power, W.
    pub metabolic_power: f64,
    /// Activation heat rate, W.
    pub activation_heat_rate: f64,
    /// Shortening and lengthening heat rate, W.
    pub shortening_heat_rate: f64,
    /// Work rate of the contractile element, W (shortening positive).
    pub work_rate: f64,
    /// Rate of change of the energy the attached bridges hold, W.
    pub bridge_storage_rate: f64,
    /// ATP rate, mol/s.
    pub atp_rate: f64,
    /// Metabolic energy since start, J.
    pub metabolic_energy: f64,
    /// The phenomenological model's metabolic power, W.
    pub phenomenological_power: f64,
    /// The phenomenological model's energy since start, J.
    pub phenomenological_energy: f64,
}
