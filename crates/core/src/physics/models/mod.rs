//! The contractile-element models, one file each, behind
//! [`ContractileModel`](crate::physics::muscle_model::ContractileModel). They are named in
//! [`crate::physics::model::MODELS`].

pub mod distribution_moment;
pub mod hill;
pub mod huxley_pde;
