//! The README's Rust examples are the kernel's doc tests, verbatim: each ```rust block of
//! `README.md` must appear in `docs/bsdf.md` (a doc test through `bsdf::BsdfGuide`) or in
//! the crate documentation of `kernel/src/lib.rs`, so an example a reader copies has run.

const README: &str = include_str!("../../README.md");
const BSDF_GUIDE: &str = include_str!("../../docs/bsdf.md");
const LIB: &str = include_str!("../src/lib.rs");

/// The bodies of the fenced blocks of `text` that open with `opening`.
fn blocks<'a>(text: &'a str, opening: &str) -> Vec<&'a str> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(start) = rest.find(opening) {
        let body = &rest[start + opening.len()..];
        let Some(end) = body.find("\n```") else { break };
        out.push(&body[..end]);
        rest = &body[end + 4..];
    }
    out
}

/// The crate documentation (`//!` lines) without its comment markers.
fn crate_doc(source: &str) -> String {
    source
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .map(|l| l.strip_prefix(' ').unwrap_or(l))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn readme_rust_examples_are_doc_tests() {
    let lib_doc = crate_doc(LIB);
    let tested: Vec<&str> = blocks(BSDF_GUIDE, "```rust\n")
        .into_iter()
        .chain(blocks(&lib_doc, "```\n"))
        .collect();
    let examples = blocks(README, "```rust\n");
    assert!(
        examples.len() >= 2,
        "{} Rust examples in the README",
        examples.len()
    );
    for (i, example) in examples.iter().enumerate() {
        assert!(
            tested.iter().any(|t| t == example),
            "README Rust example {i} is not a doc test verbatim:\n{example}"
        );
    }
}
