//! The top layer: uses parts (through its re-exports) and base.

use crate::base;
use crate::parts::{Left, Right};

pub struct Top(pub Left);

/// An inline module: its `super` is this file.
mod inner {
    pub use super::Top;
}

pub fn top() -> inner::Top {
    Top(Left(Right(base::unit())))
}

#[cfg(test)]
mod tests {
    #[test]
    fn long_test() {
        let _ = super::top(); // 1
        let _ = super::top(); // 2
        let _ = super::top(); // 3
        let _ = super::top(); // 4
        let _ = super::top(); // 5
        let _ = super::top(); // 6
        let _ = super::top(); // 7
        let _ = super::top(); // 8
        let _ = super::top(); // 9
        let _ = super::top(); // 10
        let _ = super::top(); // 11
        let _ = super::top(); // 12
        let _ = super::top(); // 13
        let _ = super::top(); // 14
        let _ = super::top(); // 15
        let _ = super::top(); // 16
        let _ = super::top(); // 17
        let _ = super::top(); // 18
        let _ = super::top(); // 19
        let _ = super::top(); // 20
        let _ = super::top(); // 21
        let _ = super::top(); // 22
        let _ = super::top(); // 23
        let _ = super::top(); // 24
        let _ = super::top(); // 25
        let _ = super::top(); // 26
        let _ = super::top(); // 27
        let _ = super::top(); // 28
        let _ = super::top(); // 29
        let _ = super::top(); // 30
    }
}
