//! An unknown key of a configuration table, told as a person would look for it: the key, its
//! line in the file, and the valid key it is nearest to, when one is near (a misspelling).

/// Smallest similarity (normalised Damerau–Levenshtein, 1 = equal) at which a valid key is
/// offered as the one meant: `f_max` for `fmax` or `t_act` for `t_cat` (0.8); nothing for
/// `strength` against the muscle keys.
const NEAR: f64 = 0.6;

/// The unknown key and the valid ones, from serde's message (`unknown field `x`, expected one
/// of `a`, `b`` or `unknown field `x`, expected `a` or `b``).
fn parse(message: &str) -> Option<(&str, Vec<&str>)> {
    let rest = message.strip_prefix("unknown field `")?;
    let (key, rest) = rest.split_once('`')?;
    let valid = rest.split('`').skip(1).step_by(2).collect();
    Some((key, valid))
}

/// The line (1-based) of `key = ...` in the `block`-th `[[muscle]]` table of `text` (or
/// anywhere, when `block` is None), if it is written that way.
fn line_of(text: &str, key: &str, block: Option<usize>) -> Option<usize> {
    let mut blocks_seen = 0;
    let mut in_block = block.is_none();
    for (n, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if t.starts_with("[[muscle]]") {
            blocks_seen += 1;
            in_block = block.is_none_or(|b| blocks_seen == b + 1);
            continue;
        }
        if t.starts_with('[') && block.is_some() {
            in_block = false;
        }
        let is_key = t
            .strip_prefix(key)
            .is_some_and(|r| r.trim_start().starts_with('='));
        if in_block && is_key {
            return Some(n + 1);
        }
    }
    None
}

/// The one valid key `key` abbreviates (`tolerance` for `tol`), if one only.
fn abbreviated<'a>(key: &str, valid: &[&'a str]) -> Option<&'a str> {
    let mut starting = valid
        .iter()
        .filter(|v| key.chars().count() >= 3 && v.starts_with(key));
    match (starting.next(), starting.next()) {
        (Some(v), None) => Some(*v),
        _ => None,
    }
}

/// serde's unknown-field `message` as `unknown key `x` (line N); did you mean `y`?`, or with
/// every valid key when none is near; any other message as it is. The line is looked for in
/// the user's `text`, if given, in the `block`-th `[[muscle]]` table (None: anywhere).
pub(crate) fn reason(message: &str, text: Option<&str>, block: Option<usize>) -> String {
    let Some((key, valid)) = parse(message) else {
        return message.to_string();
    };
    let key_shown = crate::text::excerpt(key);
    let at = text
        .and_then(|t| line_of(t, key, block))
        .map_or(String::new(), |n| format!(" (line {n})"));
    let nearest = valid
        .iter()
        .map(|v| (strsim::normalized_damerau_levenshtein(key, v), *v))
        .filter(|(s, _)| *s >= NEAR)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, v)| v)
        .or_else(|| abbreviated(key, &valid));
    match nearest {
        Some(v) => format!("unknown key `{key_shown}`{at}; did you mean `{v}`?"),
        None => format!(
            "unknown key `{key_shown}`{at}; the keys here: {}",
            valid.join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str =
        "[[muscle]]\nname = \"a\"\nf_max = 1\n\n[[muscle]]\nname = \"b\"\n  fmax = 2\n";

    #[test]
    fn a_misspelt_key_is_told_with_its_line_and_the_key_meant() {
        let m = "unknown field `fmax`, expected one of `mass`, `f_max`, `l_opt`";
        assert_eq!(
            reason(m, Some(TEXT), Some(1)),
            "unknown key `fmax` (line 7); did you mean `f_max`?"
        );
        // Not in the first muscle's table.
        assert_eq!(
            reason(m, Some(TEXT), Some(0)),
            "unknown key `fmax`; did you mean `f_max`?"
        );
    }

    #[test]
    fn a_key_near_none_lists_them_all_uncut() {
        let m = "unknown field `strength`, expected `mass` or `l_opt`";
        assert_eq!(
            reason(m, Some("strength = 2\n"), None),
            "unknown key `strength` (line 1); the keys here: mass, l_opt"
        );
        assert_eq!(reason("invalid type", None, None), "invalid type");
        let m = "unknown field `tol`, expected `tolerance` or `max_substeps`";
        assert_eq!(
            reason(m, None, None),
            "unknown key `tol`; did you mean `tolerance`?"
        );
    }
}
