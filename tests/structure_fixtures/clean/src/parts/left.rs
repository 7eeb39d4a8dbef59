//! left uses right; right does not use left.

use super::right::Right;

pub struct Left(pub Right);
