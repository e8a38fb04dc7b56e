//! The structural check every SPIR-V module passes before it reaches the driver.
//!
//! A driver is entitled to crash on a malformed module (handing it one is undefined
//! behaviour in Vulkan), so a damaged module (a truncated file, a stale or foreign build, a
//! flipped bit in an instruction's length) must be refused here, as a typed
//! [`SpirvError::BadShader`], and never passed on. The check walks the instruction stream
//! once: the header (SPIR-V specification §2.3), every instruction's word count against
//! what is left, the memory model, and the `GLCompute` entry points with their names. It is
//! not a validator: `spirv-val` (Debian's `spirv-tools`) checks types, ids and control flow,
//! and rust-gpu runs that validation on the module `build.rs` builds.

use crate::error::{Result, SpirvError};

/// The SPIR-V magic number in the module's first word.
const MAGIC: u32 = 0x0723_0203;
/// Words in the module header: magic, version, generator, id bound, schema.
pub(crate) const HEADER_WORDS: usize = 5;
/// `OpMemoryModel`.
const OP_MEMORY_MODEL: u32 = 14;
/// `OpEntryPoint`.
const OP_ENTRY_POINT: u32 = 15;
/// The `GLCompute` execution model, the only one the shader crate declares.
const GL_COMPUTE: u32 = 5;

/// A module that passed the structural check: its words and its compute entry points.
#[derive(Clone, Debug)]
pub(crate) struct CheckedModule {
    pub(crate) words: Vec<u32>,
    pub(crate) entry_points: Vec<String>,
}

/// Checks `bytes` (a little-endian SPIR-V binary, as rust-gpu writes it) and returns its
/// words and compute entry points, or [`SpirvError::BadShader`] saying what is damaged.
pub(crate) fn check(bytes: &[u8]) -> Result<CheckedModule> {
    let bad = |problem: String| Err(SpirvError::BadShader { problem });
    if !bytes.len().is_multiple_of(4) {
        return bad(format!(
            "{} bytes is not a whole number of words",
            bytes.len()
        ));
    }
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]))
        .collect();
    if words.len() < HEADER_WORDS {
        return bad(format!(
            "{} words, shorter than the {HEADER_WORDS}-word header",
            words.len()
        ));
    }
    if words[0] != MAGIC {
        return bad(if words[0].swap_bytes() == MAGIC {
            "big-endian module; the host loads little-endian SPIR-V".into()
        } else {
            format!(
                "first word {:#010x} is not the SPIR-V magic number",
                words[0]
            )
        });
    }
    let (major, minor) = ((words[1] >> 16) & 0xff, (words[1] >> 8) & 0xff);
    if major != 1 || minor > 6 || words[1] & 0xff00_00ff != 0 {
        return bad(format!(
            "version word {:#010x} is not SPIR-V 1.0–1.6",
            words[1]
        ));
    }
    let bound = words[3];
    if bound == 0 {
        return bad("the id bound is 0".into());
    }
    if words[4] != 0 {
        return bad(format!("schema word {} is not 0", words[4]));
    }
    let mut entry_points = Vec::new();
    let mut memory_model = false;
    let mut at = HEADER_WORDS;
    while at < words.len() {
        let count = (words[at] >> 16) as usize;
        let opcode = words[at] & 0xffff;
        if count == 0 {
            return bad(format!("instruction at word {at} has a word count of 0"));
        }
        let left = words.len() - at;
        if count > left {
            return bad(format!(
                "instruction at word {at} (opcode {opcode}) claims {count} words; \
                 {left} are left (truncated module?)"
            ));
        }
        let operands = &words[at + 1..at + count];
        match opcode {
            OP_MEMORY_MODEL => memory_model = true,
            OP_ENTRY_POINT => {
                let [model, id, name @ ..] = operands else {
                    return bad(format!("OpEntryPoint at word {at} has {count} words"));
                };
                if *id >= bound {
                    return bad(format!(
                        "OpEntryPoint at word {at} names id {id}, beyond the bound {bound}"
                    ));
                }
                if *model == GL_COMPUTE {
                    entry_points.push(literal_string(name).ok_or_else(|| {
                        SpirvError::BadShader {
                            problem: format!(
                                "OpEntryPoint at word {at}: the name is not a \
                                 NUL-terminated UTF-8 string"
                            ),
                        }
                    })?);
                }
            }
            _ => {}
        }
        at += count;
    }
    if !memory_model {
        return bad("no OpMemoryModel".into());
    }
    if entry_points.is_empty() {
        return bad("no GLCompute entry point".into());
    }
    Ok(CheckedModule {
        words,
        entry_points,
    })
}

/// A SPIR-V literal string at the start of `words`: UTF-8 bytes, little-endian within each
/// word, ended by a NUL inside the words given.
pub(crate) fn literal_string(words: &[u32]) -> Option<String> {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let end = bytes.iter().position(|&b| b == 0)?;
    String::from_utf8(bytes[..end].to_vec()).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A minimal module: header, `OpMemoryModel`, one `OpEntryPoint GLCompute %1 "main"`.
    fn minimal() -> Vec<u32> {
        let name = u32::from_le_bytes(*b"main");
        vec![
            MAGIC,
            0x0001_0500,
            0,
            2,
            0,
            (3 << 16) | OP_MEMORY_MODEL,
            0,
            1,
            (5 << 16) | OP_ENTRY_POINT,
            GL_COMPUTE,
            1,
            name,
            0,
        ]
    }

    fn bytes(words: &[u32]) -> Vec<u8> {
        words.iter().flat_map(|w| w.to_le_bytes()).collect()
    }

    fn problem(words: &[u32]) -> String {
        match check(&bytes(words)) {
            Err(SpirvError::BadShader { problem }) => problem,
            other => panic!("expected BadShader, got {other:?}"),
        }
    }

    #[test]
    fn a_minimal_module_passes_with_its_entry_point() {
        let m = check(&bytes(&minimal())).unwrap();
        assert_eq!(m.entry_points, ["main"]);
        assert_eq!(m.words, minimal());
    }

    #[test]
    fn each_kind_of_damage_is_named() {
        let mut b = bytes(&minimal());
        b.pop();
        assert!(check(&b).is_err());
        assert!(problem(&minimal()[..3]).contains("header"));
        let mut w = minimal();
        w[0] = MAGIC.swap_bytes();
        assert!(problem(&w).contains("big-endian"));
        w[0] = 0xdead_beef;
        assert!(problem(&w).contains("magic"));
        let mut w = minimal();
        w[1] = 0x0002_0000;
        assert!(problem(&w).contains("version"));
        let mut w = minimal();
        w[3] = 0;
        assert!(problem(&w).contains("bound"));
        let mut w = minimal();
        w[5] = OP_MEMORY_MODEL;
        assert!(problem(&w).contains("word count of 0"));
        let w = minimal();
        assert!(problem(&w[..w.len() - 2]).contains("truncated"));
        let mut w = minimal();
        w[10] = 7;
        assert!(problem(&w).contains("beyond the bound"));
        let mut w = minimal();
        w[12] = u32::from_le_bytes(*b"abcd");
        assert!(problem(&w).contains("NUL-terminated"));
        let mut w = minimal();
        w[9] = 0;
        assert!(problem(&w).contains("no GLCompute"));
        let mut w = minimal();
        w[5] = (3 << 16) | 1;
        assert!(problem(&w).contains("OpMemoryModel"));
    }
}
