//! Errors of the batch core and their C status codes.

use scratchwave_spec::SpecError;

/// The status a C function returns (`SW_STATUS_OK` is 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Success.
    Ok = 0,
    /// A null pointer, a count out of range, or arrays of the wrong length: the message
    /// names the argument.
    InvalidArgument = 1,
    /// The material or scratch JSON (or a file it names) was rejected: the message names the
    /// JSON path.
    InvalidInput = 2,
    /// An internal error (a caught panic): a bug, please report it with the message.
    Internal = 3,
}

/// Why a batch call or a constructor failed.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad argument: the message names it.
    #[error("{0}")]
    Argument(String),
    /// Bad JSON input: the message names the field path.
    #[error(transparent)]
    Input(#[from] SpecError),
    /// A caught panic.
    #[error("internal error: {0}")]
    Internal(String),
}

impl Error {
    /// The C status of this error.
    pub fn status(&self) -> Status {
        match self {
            Error::Argument(_) => Status::InvalidArgument,
            Error::Input(_) => Status::InvalidInput,
            Error::Internal(_) => Status::Internal,
        }
    }

    pub(crate) fn arg(msg: impl Into<String>) -> Error {
        Error::Argument(msg.into())
    }
}
