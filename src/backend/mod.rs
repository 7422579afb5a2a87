//! Linear-algebra backends. `serial`: faer sparse LU with symbolic reuse.

pub mod serial;
