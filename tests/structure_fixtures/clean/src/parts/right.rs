//! right uses the bottom layer only.

use crate::base::Unit;

pub struct Right(pub Unit);
