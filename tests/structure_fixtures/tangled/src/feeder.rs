//! Top-level cycle, one way: feeder uses store (and big, which only big's tests use back).

use crate::big::C1;
use crate::store::Shelf;

pub struct Feed {
    pub shelf: Shelf,
    pub count: [u8; C1 as usize],
}
