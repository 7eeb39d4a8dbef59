//! User text as messages quote it: excerpts of names and values, one-line messages, TOML parse
//! errors as `line L, column C: message`.

/// Longest parse error message, characters (it may quote the file).
pub(crate) const MAX_MESSAGE_CHARS: usize = 300;

/// A message on one line (whitespace runs, newlines included, made one space), at most
/// `MAX_MESSAGE_CHARS` characters.
pub fn one_line(message: &str) -> String {
    let flat = message.split_whitespace().collect::<Vec<_>>().join(" ");
    if flat.chars().count() <= MAX_MESSAGE_CHARS {
        flat
    } else {
        let mut e: String = flat.chars().take(MAX_MESSAGE_CHARS - 3).collect();
        e.push_str("...");
        e
    }
}

/// A TOML parse error of `text` as `line L, column C: message` on one line (the parser's own
/// rendering quotes the whole offending line, however long).
pub fn toml_error(e: &toml::de::Error, text: &str) -> String {
    let at = match e.span() {
        Some(span) => {
            let before = &text.as_bytes()[..span.start.min(text.len())];
            let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
            let column = before.len()
                - before
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |i| i + 1)
                + 1;
            format!("TOML parse error at line {line}, column {column}: ")
        }
        None => "TOML parse error: ".into(),
    };
    one_line(&format!("{at}{}", e.message()))
}

/// A user string as quoted in messages: at most 64 characters.
pub fn excerpt(s: &str) -> String {
    if s.chars().count() <= 64 {
        s.to_string()
    } else {
        let mut e: String = s.chars().take(61).collect();
        e.push_str("...");
        e
    }
}
