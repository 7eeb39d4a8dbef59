//! Test code as a whole (declared `#[cfg(test)] mod tests;`): neither its length nor its
//! import of a higher layer counts.

use crate::top::Top;

#[test]
fn a_long_test_function() {
    assert_eq!(1, 1);
    assert_eq!(2, 2);
    assert_eq!(3, 3);
    assert_eq!(4, 4);
    assert_eq!(5, 5);
    assert_eq!(6, 6);
    assert_eq!(7, 7);
    assert_eq!(8, 8);
    assert_eq!(9, 9);
    assert_eq!(10, 10);
    assert_eq!(11, 11);
    assert_eq!(12, 12);
    assert_eq!(13, 13);
    assert_eq!(14, 14);
    assert_eq!(15, 15);
    assert_eq!(16, 16);
    assert_eq!(17, 17);
    assert_eq!(18, 18);
    assert_eq!(19, 19);
    assert_eq!(20, 20);
    assert_eq!(21, 21);
    assert_eq!(22, 22);
    assert_eq!(23, 23);
    assert_eq!(24, 24);
    assert_eq!(25, 25);
    assert_eq!(26, 26);
    assert_eq!(27, 27);
    assert_eq!(28, 28);
    assert_eq!(29, 29);
    assert_eq!(30, 30);
    assert_eq!(31, 31);
    assert_eq!(32, 32);
    assert_eq!(33, 33);
    assert_eq!(34, 34);
    assert_eq!(35, 35);
    assert_eq!(36, 36);
    assert_eq!(37, 37);
    assert_eq!(38, 38);
    assert_eq!(39, 39);
    assert_eq!(40, 40);
    assert_eq!(41, 41);
    assert_eq!(42, 42);
    assert_eq!(43, 43);
    assert_eq!(44, 44);
    assert_eq!(45, 45);
    let _ = std::mem::size_of::<Top>();
}
