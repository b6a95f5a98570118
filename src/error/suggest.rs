//! "Did you mean …?": the known name nearest a misspelt one, by edit
//! distance, for the messages of unknown keys, models, shapes, sets,
//! obstacles and amplitudes.
//!
//! The distance is the optimal-string-alignment distance of
//! [`strsim::osa_distance`] (Levenshtein with adjacent transpositions, so
//! `poisson_ratoi` is one edit from `poisson_ratio`), on the names
//! lower-cased. A candidate is suggested when it is at most
//! [`max_edits`] edits away, and only the nearest (the first of equals in
//! the given order).

/// The most edits a suggestion may be away from a name of `len`
/// characters: a third of it, at least 1 and at most 3 (`xz` suggests
/// nothing, `poison_ratio` → `poisson_ratio`, one edit).
pub fn max_edits(len: usize) -> usize {
    (len / 3).clamp(1, 3)
}

/// The candidate nearest `word`, if one is near enough ([`max_edits`]) and
/// it is not `word` itself.
pub fn nearest<'a, S: AsRef<str>>(word: &str, candidates: &'a [S]) -> Option<&'a str> {
    let lower = word.to_lowercase();
    let limit = max_edits(word.chars().count());
    candidates
        .iter()
        .map(AsRef::as_ref)
        .filter(|c| *c != word)
        .map(|c| (strsim::osa_distance(&lower, &c.to_lowercase()), c))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

/// `"; did you mean 'poisson_ratio'?"`, or nothing when no candidate is
/// near `word`: the tail of a message about an unknown name.
pub fn hint<S: AsRef<str>>(word: &str, candidates: &[S]) -> String {
    nearest(word, candidates)
        .map(|c| format!("; did you mean '{c}'?"))
        .unwrap_or_default()
}

/// `"there are: a, b, c"` (or `none`) followed by the [`hint`] for `word`:
/// the end of a message about a name that is not among `have`.
pub fn listing<S: AsRef<str>>(word: &str, have: &[S], none: &str) -> String {
    let list = if have.is_empty() {
        none.to_string()
    } else {
        have.iter()
            .map(AsRef::as_ref)
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!("there are: {list}{}", hint(word, have))
}

/// The words of a serde message's `expected …` list (`` expected `a`, `b`
/// or `c` ``, `` expected one of `a`, `b` ``): every back-quoted word after
/// `expected`.
pub fn expected_words(message: &str) -> Vec<&str> {
    let Some((_, list)) = message.split_once("expected ") else {
        return Vec::new();
    };
    list.split('`').skip(1).step_by(2).collect()
}

/// The hint for a serde "unknown field `x`" or "unknown variant `x`"
/// message, from its `expected` list; nothing for other messages.
pub fn serde_hint(message: &str) -> String {
    let unknown = ["unknown field `", "unknown variant `"]
        .iter()
        .find_map(|p| message.split_once(p))
        .and_then(|(_, rest)| rest.split('`').next());
    match unknown {
        Some(word) => hint(word, &expected_words(message)),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_name_within_a_third_of_the_length() {
        let keys = ["youngs_modulus", "poisson_ratio"];
        assert_eq!(nearest("poison_ratio", &keys), Some("poisson_ratio"));
        assert_eq!(nearest("poisson_ratoi", &keys), Some("poisson_ratio"));
        assert_eq!(nearest("young_modulus", &keys), Some("youngs_modulus"));
        assert_eq!(nearest("density", &keys), None);
        assert_eq!(nearest("TOP", &["top", "bottom"]), Some("top"));
        assert_eq!(nearest("ab", &["xy"]), None);
        assert_eq!(max_edits(2), 1);
        assert_eq!(max_edits(12), 3);
    }

    #[test]
    fn the_hint_of_a_serde_message() {
        let m = "unknown field `poison_ratio`, expected `youngs_modulus` or `poisson_ratio`";
        assert_eq!(serde_hint(m), "; did you mean 'poisson_ratio'?");
        let m = "unknown variant `neo_hookian`, expected one of `linear_elastic`, `neo_hookean`";
        assert_eq!(serde_hint(m), "; did you mean 'neo_hookean'?");
        assert_eq!(serde_hint("invalid type: string, expected a number"), "");
        assert_eq!(
            listing("wal", &["wall", "floor"], "none"),
            "there are: wall, floor; did you mean 'wall'?"
        );
        assert_eq!(listing::<&str>("x", &[], "none"), "there are: none");
    }
}
