//! right uses left only through the re-export in parts/mod.rs.

use crate::parts::Left;

pub struct Right;

pub fn size() -> usize {
    std::mem::size_of::<Left>()
}

/// 21 lines from `fn` to its closing brace; the braces in strings, characters and comments
/// must not end it early or late.
pub fn long_function(x: u32) -> String {
    let open = "{{{ not a block";
    let close = '}';
    let raw = r#"}}"#;
    // } a comment with a brace
    /* { a block comment { with braces */
    let mut s = String::new();
    s.push_str(open);
    s.push(close);
    s.push('\'');
    s.push_str(raw);
    if x > 1 {
        s.push('{');
    }
    for _ in 0..x {
        s.push_str("}");
    }
    let label: &'static str = "lifetime";
    s.push_str(label);
    s
}
