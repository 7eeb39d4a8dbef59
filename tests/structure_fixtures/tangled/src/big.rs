//! 42 lines of non-test code, then a test module longer than any limit.

pub const C1: u32 = 1;
pub const C2: u32 = 2;
pub const C3: u32 = 3;
pub const C4: u32 = 4;
pub const C5: u32 = 5;
pub const C6: u32 = 6;
pub const C7: u32 = 7;
pub const C8: u32 = 8;
pub const C9: u32 = 9;
pub const C10: u32 = 10;
pub const C11: u32 = 11;
pub const C12: u32 = 12;
pub const C13: u32 = 13;
pub const C14: u32 = 14;
pub const C15: u32 = 15;
pub const C16: u32 = 16;
pub const C17: u32 = 17;
pub const C18: u32 = 18;
pub const C19: u32 = 19;
pub const C20: u32 = 20;
pub const C21: u32 = 21;
pub const C22: u32 = 22;
pub const C23: u32 = 23;
pub const C24: u32 = 24;
pub const C25: u32 = 25;
pub const C26: u32 = 26;
pub const C27: u32 = 27;
pub const C28: u32 = 28;
pub const C29: u32 = 29;
pub const C30: u32 = 30;
pub const C31: u32 = 31;
pub const C32: u32 = 32;
pub const C33: u32 = 33;
pub const C34: u32 = 34;
pub const C35: u32 = 35;
pub const C36: u32 = 36;
pub const C37: u32 = 37;
pub const C38: u32 = 38;
pub const C39: u32 = 39;

#[cfg(test)]
mod tests {
    use crate::feeder::Feed;

    #[test]
    fn a_long_test_function() {
        assert_eq!(super::C1 + 1, 1 + 1);
        assert_eq!(super::C1 + 2, 1 + 2);
        assert_eq!(super::C1 + 3, 1 + 3);
        assert_eq!(super::C1 + 4, 1 + 4);
        assert_eq!(super::C1 + 5, 1 + 5);
        assert_eq!(super::C1 + 6, 1 + 6);
        assert_eq!(super::C1 + 7, 1 + 7);
        assert_eq!(super::C1 + 8, 1 + 8);
        assert_eq!(super::C1 + 9, 1 + 9);
        assert_eq!(super::C1 + 10, 1 + 10);
        assert_eq!(super::C1 + 11, 1 + 11);
        assert_eq!(super::C1 + 12, 1 + 12);
        assert_eq!(super::C1 + 13, 1 + 13);
        assert_eq!(super::C1 + 14, 1 + 14);
        assert_eq!(super::C1 + 15, 1 + 15);
        assert_eq!(super::C1 + 16, 1 + 16);
        assert_eq!(super::C1 + 17, 1 + 17);
        assert_eq!(super::C1 + 18, 1 + 18);
        assert_eq!(super::C1 + 19, 1 + 19);
        assert_eq!(super::C1 + 20, 1 + 20);
        assert_eq!(super::C1 + 21, 1 + 21);
        assert_eq!(super::C1 + 22, 1 + 22);
        assert_eq!(super::C1 + 23, 1 + 23);
        assert_eq!(super::C1 + 24, 1 + 24);
        assert_eq!(super::C1 + 25, 1 + 25);
        assert_eq!(super::C1 + 26, 1 + 26);
        assert_eq!(super::C1 + 27, 1 + 27);
        assert_eq!(super::C1 + 28, 1 + 28);
        assert_eq!(super::C1 + 29, 1 + 29);
        assert_eq!(super::C1 + 30, 1 + 30);
        let _ = std::mem::size_of::<Feed>();
    }
}
