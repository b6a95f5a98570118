//! Messages in the user's words: the Rust type names that serde and the
//! file-format crates put in their messages (`expected f64`, `expected
//! usize`) replaced by what a case file writes (`a number`, `a whole
//! number ≥ 0`).

/// (Rust's words, the user's), longest first where one holds another.
const PLAIN: [(&str, &str); 12] = [
    ("expected finite f32", "expected a finite number"),
    ("expected f64", "expected a number"),
    ("expected f32", "expected a number"),
    ("expected usize", "expected a whole number ≥ 0"),
    ("expected u64", "expected a whole number ≥ 0"),
    ("expected u32", "expected a whole number ≥ 0"),
    ("expected u16", "expected a whole number ≥ 0"),
    ("expected u8", "expected a whole number ≥ 0"),
    ("expected i64", "expected a whole number"),
    ("expected i32", "expected a whole number"),
    ("floating point `", "number `"),
    (" which is Nan", ""),
];

/// `message` with Rust's type names replaced by the user's words
/// ([`PLAIN`]).
pub fn plain(message: &str) -> String {
    PLAIN
        .iter()
        .fold(message.to_string(), |m, (rust, user)| m.replace(rust, user))
}

#[cfg(test)]
mod tests {
    #[test]
    fn type_names_become_words() {
        assert_eq!(
            super::plain("invalid type: string \"100\", expected f64"),
            "invalid type: string \"100\", expected a number"
        );
        assert_eq!(
            super::plain("invalid value: integer `-1`, expected usize"),
            "invalid value: integer `-1`, expected a whole number ≥ 0"
        );
        assert_eq!(
            super::plain("expected finite f32, got NaN which is Nan"),
            "expected a finite number, got NaN"
        );
    }
}
