//! Typed input errors that name the offending field.

/// A bad input: the JSON path of the field (e.g. `queries[3].wi`) and what is wrong.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SpecError {
    /// The file could not be read.
    #[error("{path}: cannot read: {msg}")]
    Io {
        /// File path.
        path: String,
        /// OS error text.
        msg: String,
    },
    /// The text is not valid JSON.
    #[error("{path}: malformed JSON: {msg}")]
    Json {
        /// File path.
        path: String,
        /// Parser message with line/column.
        msg: String,
    },
    /// A field is missing, unknown, of the wrong type or out of range.
    #[error("{field}: {msg}")]
    Field {
        /// JSON path of the field.
        field: String,
        /// What is wrong.
        msg: String,
    },
}

impl SpecError {
    /// A field error.
    pub fn field(field: impl Into<String>, msg: impl Into<String>) -> SpecError {
        SpecError::Field {
            field: field.into(),
            msg: msg.into(),
        }
    }
}
