//! Generated `const` tables (generator: `reference/ghs/gen_tables.py`; rerun it and commit
//! the output when a table's range or resolution changes).

pub mod g1_table;
pub mod gauss_legendre;
