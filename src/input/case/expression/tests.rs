//! The expression parser: precedence, associativity, functions, and the
//! column of every error.

use super::{Expression, Variable};

const P: [f64; 4] = [2.0, 3.0, 5.0, 7.0];

fn at(text: &str, p: [f64; 4]) -> f64 {
    Expression::parse(text)
        .unwrap_or_else(|e| panic!("{text}: {e}"))
        .value(p)
}

fn v(text: &str) -> f64 {
    at(text, P)
}

/// The error's column and that its message holds `says`.
fn refused(text: &str, column: usize, says: &str) {
    let e = Expression::parse(text).expect_err(text);
    assert_eq!(e.column, column, "{text}: {e}");
    assert!(e.message.contains(says), "{text}: {e}");
}

#[test]
fn precedence_is_that_of_mathematics() {
    assert_eq!(v("1 + 2 * 3"), 7.0);
    assert_eq!(v("(1 + 2) * 3"), 9.0);
    assert_eq!(v("2 * 3 ^ 2"), 18.0);
    assert_eq!(v("8 / 2 / 2"), 2.0); // left-associative
    assert_eq!(v("8 - 2 - 1"), 5.0);
    assert_eq!(v("1 - 2 + 3"), 2.0);
    // the sign binds looser than the power, tighter than the product
    assert_eq!(v("-2 ^ 2"), -4.0);
    assert_eq!(v("(-2) ^ 2"), 4.0);
    assert_eq!(v("-2 * 3"), -6.0);
    assert_eq!(v("2 * -3"), -6.0);
    assert_eq!(v("--2"), 2.0);
    assert_eq!(v("+2 - -2"), 4.0);
}

#[test]
fn power_is_right_associative_and_takes_a_signed_exponent() {
    assert_eq!(v("2 ^ 3 ^ 2"), 512.0);
    assert_eq!(v("(2 ^ 3) ^ 2"), 64.0);
    assert_eq!(v("2 ^ -1"), 0.5);
    assert_eq!(v("2 ^ -1 ^ 2"), 0.5); // 2^(-(1^2))
    assert_eq!(v("4 ^ 0.5 * 3"), 6.0);
}

#[test]
fn numbers_take_fractions_and_exponents() {
    assert_eq!(v("1.5e3"), 1500.0);
    assert_eq!(v("2E-2"), 0.02);
    assert_eq!(v(".25"), 0.25);
    assert_eq!(v("3."), 3.0);
    assert_eq!(v("1e+2"), 100.0);
}

#[test]
fn variables_read_the_point() {
    assert_eq!(v("x"), 2.0);
    assert_eq!(v("y"), 3.0);
    assert_eq!(v("z"), 5.0);
    assert_eq!(v("r"), 7.0);
    assert_eq!(v("1 - 0.02*(r - 10)"), 1.0 - 0.02 * (7.0 - 10.0));
    assert_eq!(v("x*y - z/r"), 6.0 - 5.0 / 7.0);
    let e = Expression::parse("r + 2*x - r*z").unwrap();
    assert_eq!(
        e.variables(),
        vec![(Variable::R, 1), (Variable::X, 7), (Variable::Z, 13)]
    );
}

#[test]
fn functions_give_their_values() {
    assert_eq!(v("sqrt(16)"), 4.0);
    assert_eq!(v("exp(0)"), 1.0);
    assert_eq!(v("ln(exp(2))"), 2.0);
    assert_eq!(v("sin(0) + cos(0)"), 1.0);
    assert!((v("sin(pi/2)") - 1.0).abs() < 1e-15);
    assert_eq!(v("abs(-3)"), 3.0);
    assert_eq!(v("min(x, y, -1)"), -1.0);
    assert_eq!(v("max(x, y)"), 3.0);
    assert_eq!(v("max(1, min(4, 2))"), 2.0);
    assert_eq!(v("2*sqrt(x*8)^2"), 32.0);
    assert_eq!(v("exp(-x^2)"), (-4.0f64).exp());
}

#[test]
fn syntax_errors_name_the_column() {
    refused("", 1, "is empty");
    refused("   ", 4, "is empty");
    refused("1 + q", 5, "unknown name \"q\"");
    refused("1 + xy", 5, "unknown name \"xy\"");
    refused("(1 + x", 1, "'(' is not closed");
    refused("2 * (1 + (x)", 5, "'(' is not closed");
    refused("1 + x)", 6, "')' closes no '('");
    refused("1 +", 4, "ends where");
    refused("1 + * 2", 5, "expected a number");
    refused("2 x", 3, "expected an operator");
    refused("1 # 2", 3, "'#' is not part");
    refused("1e", 3, "exponent has no digits");
    refused("1e400", 1, "not a finite number");
    refused(". + 1", 1, "'.' without digits");
    refused("sqrt 2", 1, "needs its argument");
    refused("sqrt(1, 2)", 1, "takes one argument, given 2");
    refused("2 + max(1)", 5, "two or more arguments, given 1");
    refused("x(2)", 1, "a variable, not a function");
    refused("sin(x", 4, "'(' is not closed");
    refused("min(x y)", 7, "expected ')'");
    refused("()", 2, "')' where");
    // multibyte characters count as one column
    refused("1 + é", 5, "'é' is not part");
}

#[test]
fn depth_and_length_are_bounded() {
    let deep = format!("{}1{}", "(".repeat(200), ")".repeat(200));
    let e = Expression::parse(&deep).expect_err("deep");
    assert!(e.message.contains("nested deeper"), "{e}");
    // 64 levels of nesting are the most, 65 too many
    use super::MAX_DEPTH;
    let nest = |n: usize| format!("{}1{}", "(".repeat(n), ")".repeat(n));
    assert!(Expression::parse(&nest(MAX_DEPTH)).is_ok());
    assert!(Expression::parse(&nest(MAX_DEPTH + 1)).is_err());
    assert!(Expression::parse(&format!("{}1", "-".repeat(MAX_DEPTH))).is_ok());
    assert!(Expression::parse(&"-".repeat(100)).is_err());
    let long = format!("1{}", " + 1".repeat(300));
    let e = Expression::parse(&long).expect_err("long");
    assert!(e.message.contains("at most"), "{e}");
    // just within the depth: 60 parentheses
    assert_eq!(v(&format!("{}2{}", "(".repeat(60), ")".repeat(60))), 2.0);
}

#[test]
fn an_undefined_value_names_the_operation_at_fault() {
    let e = Expression::parse("1 + 1/(x - 2)").unwrap();
    let u = e.checked(P).expect_err("1/0");
    assert_eq!(u.column, 6, "{u:?}");
    assert!(u.message.contains("the division"), "{u:?}");
    assert_eq!(e.checked([4.0, 0.0, 0.0, 0.0]), Ok(1.5));
    let e = Expression::parse("2 * sqrt(y - 4)").unwrap();
    let u = e.checked(P).expect_err("sqrt(-1)");
    assert_eq!(u.column, 5, "{u:?}");
    assert!(u.message.contains("sqrt(-1) is NaN"), "{u:?}");
    let e = Expression::parse("ln(x - 2)").unwrap();
    assert!(e.checked(P).unwrap_err().message.contains("-inf"));
    let e = Expression::parse("(-x) ^ 0.5").unwrap();
    assert_eq!(e.checked(P).unwrap_err().column, 6);
    let e = Expression::parse("exp(1000) - exp(1000)").unwrap();
    assert_eq!(e.checked(P).unwrap_err().column, 1);
}
