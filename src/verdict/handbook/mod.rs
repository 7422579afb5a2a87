//! The standards' own formulas: pure functions of the designer's inputs, in N, mm and MPa.
