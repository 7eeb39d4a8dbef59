//! left uses right directly.

use super::right::Right;

pub struct Left(pub Right);
