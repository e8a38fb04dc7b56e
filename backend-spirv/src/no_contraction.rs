//! Rust's floating-point semantics on the driver: every float arithmetic result of the
//! module decorated `NoContraction` before it is loaded.
//!
//! Without the decoration a Vulkan driver may fuse, reassociate and simplify float
//! arithmetic (SPIR-V specification §2.16.1, *Precision and Operation of Floating-Point
//! Operations*; rust-gpu emits no such decoration). Mesa does: its NIR optimiser applies
//! the inexact algebraic rules to every operation not marked exact, among them
//! `(a + b) − a → b`, which deletes the rounding error that Knuth's two-sum recovers. The
//! kernel's two-fold arithmetic (`kernel/src/math/twofold.rs`) then runs at
//! `f32` accuracy: measured on lavapipe (Mesa 25.0.7), the two small sphere lights whose
//! angle to the band the two-fold arithmetic resolves (rows 462 and 464 of
//! `reference/golden/sweep/light.csv`) were 4.8e-4 and 3.5e-3 off the exact integral
//! against the CPU's 2.3e-5 and 6.8e-6, and are 2.3e-5 and 7.1e-6 off with this pass.
//!
//! Decorated: `OpFNegate`, `OpFAdd`, `OpFSub`, `OpFMul`, `OpFDiv`, `OpFRem`, `OpFMod`,
//! `OpVectorTimesScalar`, `OpDot`, and GLSL.std.450's `Fma` and `FMix`, which a driver may
//! lower to a multiply and an add and then simplify. rust-gpu's optimiser has already
//! turned some of the kernel's `a·b + c` into `Fma`, Veltkamp's split `c − (c − a)` among
//! them (fused or evaluated as written, that split stays exact); with every other operation
//! decorated but not the `Fma`s, a small polygon's two-fold height still ran at `f32`
//! accuracy on lavapipe. The driver then evaluates the operations as the module writes
//! them, each rounded once, as Rust does on the CPU; what still differs from the CPU is
//! those `Fma`s and Vulkan's precision for division and the GLSL.std.450 functions.

/// `OpExtInstImport`.
const OP_EXT_INST_IMPORT: u32 = 11;
/// `OpExtInst`.
const OP_EXT_INST: u32 = 12;
/// `OpDecorate`.
const OP_DECORATE: u32 = 71;
/// The `NoContraction` decoration.
const NO_CONTRACTION: u32 = 42;

/// Float arithmetic opcodes whose result is the word after the result type.
const FLOAT_ARITHMETIC: [u32; 9] = [
    127, // OpFNegate
    129, // OpFAdd
    131, // OpFSub
    133, // OpFMul
    136, // OpFDiv
    140, // OpFRem
    141, // OpFMod
    142, // OpVectorTimesScalar
    148, // OpDot
];

/// GLSL.std.450 instructions that a driver may lower to separate multiplies and adds:
/// `FMix` (46) and `Fma` (50).
const GLSL_ARITHMETIC: [u32; 2] = [46, 50];

/// The sections that precede the annotations (SPIR-V §2.4, *Logical Layout of a Module*):
/// capabilities, extensions, imports, memory model, entry points, execution modes, and
/// the debug instructions.
const BEFORE_ANNOTATIONS: [u32; 14] = [17, 10, 11, 14, 15, 16, 331, 2, 3, 4, 5, 6, 7, 330];

/// What [`decorate`] needs of a module: where the annotations start, the float arithmetic
/// results, and the ids already decorated `NoContraction` (sorted).
struct Scan {
    insert_at: usize,
    results: Vec<u32>,
    decorated: Vec<u32>,
}

/// Walks `words` (a module that passed [`crate::module::check`]) once.
fn scan(words: &[u32]) -> Scan {
    let mut glsl = None;
    let mut results = Vec::new();
    let mut decorated = Vec::new();
    let mut insert_at = None;
    let mut at = crate::module::HEADER_WORDS;
    while at < words.len() {
        let count = ((words[at] >> 16) as usize).max(1);
        let opcode = words[at] & 0xffff;
        let operands = words.get(at + 1..at + count).unwrap_or(&[]);
        if insert_at.is_none() && !BEFORE_ANNOTATIONS.contains(&opcode) {
            insert_at = Some(at);
        }
        match (opcode, operands) {
            (OP_EXT_INST_IMPORT, [id, name @ ..])
                if crate::module::literal_string(name).as_deref() == Some("GLSL.std.450") =>
            {
                glsl = Some(*id);
            }
            (OP_DECORATE, [id, NO_CONTRACTION, ..]) => decorated.push(*id),
            (OP_EXT_INST, [_, id, set, instruction, ..])
                if Some(*set) == glsl && GLSL_ARITHMETIC.contains(instruction) =>
            {
                results.push(*id);
            }
            (op, [_, id, ..]) if FLOAT_ARITHMETIC.contains(&op) => results.push(*id),
            _ => {}
        }
        at += count;
    }
    decorated.sort_unstable();
    Scan {
        insert_at: insert_at.unwrap_or(words.len()),
        results,
        decorated,
    }
}

/// `words` (a module that passed [`crate::module::check`]) with an
/// `OpDecorate %r NoContraction` for every float arithmetic result `%r` not already so
/// decorated, placed at the start of the annotations. Ids and everything else are
/// unchanged; a module without float arithmetic comes back as it was.
pub(crate) fn decorate(words: &[u32]) -> Vec<u32> {
    let Scan {
        insert_at,
        mut results,
        decorated,
    } = scan(words);
    results.retain(|id| decorated.binary_search(id).is_err());
    let mut out = Vec::with_capacity(words.len() + 3 * results.len());
    out.extend_from_slice(&words[..insert_at]);
    for id in results {
        out.extend_from_slice(&[(3 << 16) | OP_DECORATE, id, NO_CONTRACTION]);
    }
    out.extend_from_slice(&words[insert_at..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `"GLSL.std.450"` as literal-string words (12 bytes, then a NUL word).
    fn glsl_name() -> Vec<u32> {
        let mut w: Vec<u32> = b"GLSL.std.450"
            .chunks(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        w.push(0);
        w
    }

    /// Header, the GLSL import as `%1`, `OpName`, one existing decoration, a float type,
    /// and a function body with an `OpFAdd`, an `OpIAdd`, an `OpFMul` already decorated,
    /// an `Fma` and a GLSL `Sqrt`.
    fn module() -> Vec<u32> {
        let mut w = vec![0x0723_0203, 0x0001_0500, 0, 20, 0];
        w.push((2 + 4) << 16 | OP_EXT_INST_IMPORT);
        w.push(1);
        w.extend(glsl_name());
        w.extend([(3 << 16) | 14, 0, 1]); // OpMemoryModel
        w.extend([(3 << 16) | 5, 2, 0]); // OpName %2 ""
        w.extend([(3 << 16) | OP_DECORATE, 9, NO_CONTRACTION]);
        w.extend([(3 << 16) | 22, 2, 32]); // %2 = OpTypeFloat 32
        w.extend([(5 << 16) | 129, 2, 5, 3, 4]); // %5 = OpFAdd %2 %3 %4
        w.extend([(5 << 16) | 128, 2, 6, 3, 4]); // %6 = OpIAdd
        w.extend([(5 << 16) | 133, 2, 9, 3, 4]); // %9 = OpFMul (decorated above)
        w.extend([(8 << 16) | OP_EXT_INST, 2, 7, 1, 50, 3, 4, 5]); // %7 = Fma
        w.extend([(6 << 16) | OP_EXT_INST, 2, 8, 1, 31, 3]); // %8 = Sqrt
        w
    }

    #[test]
    fn each_float_result_is_decorated_once_before_the_existing_annotations() {
        let input = module();
        let out = decorate(&input);
        let first_decoration = input
            .iter()
            .position(|&w| w == (3 << 16) | OP_DECORATE)
            .unwrap();
        assert_eq!(out[..first_decoration], input[..first_decoration]);
        let added = [(3 << 16) | OP_DECORATE, 5, NO_CONTRACTION];
        let added_fma = [(3 << 16) | OP_DECORATE, 7, NO_CONTRACTION];
        assert_eq!(out[first_decoration..first_decoration + 3], added);
        assert_eq!(out[first_decoration + 3..first_decoration + 6], added_fma);
        assert_eq!(out[first_decoration + 6..], input[first_decoration..]);
    }

    #[test]
    fn decorating_twice_adds_nothing() {
        let once = decorate(&module());
        assert_eq!(decorate(&once), once);
    }

    #[test]
    fn every_float_result_of_the_shader_module_is_decorated_exactly_once() {
        let words = crate::module::check(crate::SHADER_SPV).unwrap().words;
        let before = scan(&words);
        let out = decorate(&words);
        let after = scan(&out);
        assert!(before.results.len() > 10_000, "{}", before.results.len());
        assert_eq!(after.results, before.results);
        let mut expected = before.results.clone();
        expected.extend(&before.decorated);
        expected.sort_unstable();
        expected.dedup();
        assert_eq!(after.decorated, expected);
        let bytes: Vec<u8> = out.iter().flat_map(|w| w.to_le_bytes()).collect();
        let checked = crate::module::check(&bytes).unwrap();
        assert_eq!(
            checked.entry_points,
            crate::entry_points().collect::<Vec<_>>()
        );
    }
}
