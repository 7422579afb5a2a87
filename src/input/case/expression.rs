//! A function of position written in a case (`[[temperature]] field`,
//! docs/case-schema.md "Temperatures"): parsed once, when the model is built,
//! into a tree that is evaluated at every Gauss point.
//!
//! The grammar, by a recursive descent (one function per rule, lowest
//! precedence first):
//!
//! ```text
//! sum     = product { ("+" | "-") product }          left-associative
//! product = unary { ("*" | "/") unary }              left-associative
//! unary   = ("-" | "+") unary | power
//! power   = primary [ "^" unary ]                    right-associative: 2^3^2 = 2^9
//! primary = number | variable | name "(" sum { "," sum } ")" | "(" sum ")"
//! number  = digits [ "." digits ] [ ("e" | "E") [ "+" | "-" ] digits ]   (or "." digits ...)
//! ```
//!
//! So −2^2 = −(2^2) = −4 and 2^−1 = 0.5, as in mathematics. The variables are
//! x, y, z (mm) and r (mm, the distance from the model's axis) and the
//! constant pi; the functions sqrt, exp, ln, sin, cos (radians), abs (one
//! argument) and min, max (two or more). Every error names the column (from
//! 1, in characters) of the character at fault.

use std::fmt;

/// The longest expression read, in characters.
pub const MAX_LENGTH: usize = 1000;
/// The deepest nesting of parentheses, unary signs and powers: a deeper
/// one is refused (the descent would otherwise exhaust the stack).
pub const MAX_DEPTH: usize = 64;

/// A coordinate an expression reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variable {
    X,
    Y,
    Z,
    /// The distance from the model's axis.
    R,
}

impl Variable {
    /// Its place in a point [x, y, z, r].
    fn index(self) -> usize {
        match self {
            Variable::X => 0,
            Variable::Y => 1,
            Variable::Z => 2,
            Variable::R => 3,
        }
    }

    /// Its name in the expression.
    pub fn name(self) -> &'static str {
        ["x", "y", "z", "r"][self.index()]
    }
}

/// The names of the variables, as listed in messages.
const VARIABLES: [(&str, Variable); 4] = [
    ("x", Variable::X),
    ("y", Variable::Y),
    ("z", Variable::Z),
    ("r", Variable::R),
];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Function {
    Sqrt,
    Exp,
    Ln,
    Sin,
    Cos,
    Abs,
    Min,
    Max,
}

const FUNCTIONS: [(&str, Function); 8] = [
    ("sqrt", Function::Sqrt),
    ("exp", Function::Exp),
    ("ln", Function::Ln),
    ("sin", Function::Sin),
    ("cos", Function::Cos),
    ("abs", Function::Abs),
    ("min", Function::Min),
    ("max", Function::Max),
];

impl Function {
    fn name(self) -> &'static str {
        FUNCTIONS.iter().find(|f| f.1 == self).map_or("?", |f| f.0)
    }

    /// Whether it takes one argument (else two or more).
    fn unary(self) -> bool {
        !matches!(self, Function::Min | Function::Max)
    }

    /// Its value at the arguments' values (one, or two or more: checked
    /// when parsed).
    fn apply(self, mut args: impl Iterator<Item = f64>) -> f64 {
        let a = args.next().unwrap_or(f64::NAN);
        match self {
            Function::Sqrt => a.sqrt(),
            Function::Exp => a.exp(),
            Function::Ln => a.ln(),
            Function::Sin => a.sin(),
            Function::Cos => a.cos(),
            Function::Abs => a.abs(),
            Function::Min => args.fold(a, f64::min),
            Function::Max => args.fold(a, f64::max),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

impl Op {
    fn apply(self, a: f64, b: f64) -> f64 {
        match self {
            Op::Add => a + b,
            Op::Sub => a - b,
            Op::Mul => a * b,
            Op::Div => a / b,
            Op::Pow => a.powf(b),
        }
    }

    fn what(self) -> &'static str {
        match self {
            Op::Add => "the sum",
            Op::Sub => "the difference",
            Op::Mul => "the product",
            Op::Div => "the division",
            Op::Pow => "the power",
        }
    }
}

/// A node of the tree; `column` is where its operator or name stands.
#[derive(Clone, Debug, PartialEq)]
enum Node {
    Number(f64),
    /// A variable and the column where it stands.
    Variable(Variable, usize),
    Negate(Box<Node>),
    Binary {
        op: Op,
        column: usize,
        left: Box<Node>,
        right: Box<Node>,
    },
    Call {
        function: Function,
        column: usize,
        args: Vec<Node>,
    },
}

/// An expression, parsed: [`Expression::value`] at a point.
#[derive(Clone, Debug, PartialEq)]
pub struct Expression {
    root: Node,
}

/// Why a text is no expression, and the column (from 1) of the character
/// at fault.
#[derive(Clone, Debug, PartialEq)]
pub struct SyntaxError {
    pub column: usize,
    pub message: String,
}

impl fmt::Display for SyntaxError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "column {}: {}", self.column, self.message)
    }
}

/// An operation that gave no finite number at a point: its column and what
/// it gave.
#[derive(Clone, Debug, PartialEq)]
pub struct Undefined {
    pub column: usize,
    pub message: String,
}

impl Expression {
    /// The tree of `text` ([the grammar](self)), or the first error.
    pub fn parse(text: &str) -> Result<Expression, SyntaxError> {
        let chars: Vec<char> = text.chars().collect();
        if chars.len() > MAX_LENGTH {
            return Err(SyntaxError {
                column: MAX_LENGTH + 1,
                message: format!(
                    "the expression has {} characters: at most {MAX_LENGTH} are read",
                    chars.len()
                ),
            });
        }
        let tokens = lex(&chars)?;
        let mut p = Parser {
            tokens: &tokens,
            at: 0,
            depth: 0,
        };
        if matches!(p.peek(), Token::End) {
            return Err(
                p.error("is empty: give a function of x, y, z and r (e.g. \"1 - 0.01*x\")".into())
            );
        }
        let root = p.sum()?;
        match p.peek() {
            Token::End => Ok(Expression { root }),
            Token::Close => Err(p.error("this ')' closes no '('".into())),
            _ => Err(p.error("expected an operator (+ - * / ^) or the end".into())),
        }
    }

    /// The value at the point [x, y, z, r] (every operation's result,
    /// finite or not: [`Expression::checked`] says which is not).
    pub fn value(&self, point: [f64; 4]) -> f64 {
        eval(&self.root, &point)
    }

    /// The value at [x, y, z, r] if every operation gives a finite number
    /// there; else the first (innermost, leftmost) that does not.
    pub fn checked(&self, point: [f64; 4]) -> Result<f64, Undefined> {
        check(&self.root, &point)
    }

    /// Every variable the expression reads, with the column of its first
    /// use, in the order of their first use.
    pub fn variables(&self) -> Vec<(Variable, usize)> {
        let mut out = Vec::new();
        collect(&self.root, &mut out);
        out
    }
}

fn eval(node: &Node, p: &[f64; 4]) -> f64 {
    match node {
        Node::Number(v) => *v,
        Node::Variable(v, _) => p[v.index()],
        Node::Negate(a) => -eval(a, p),
        Node::Binary {
            op, left, right, ..
        } => op.apply(eval(left, p), eval(right, p)),
        Node::Call { function, args, .. } => function.apply(args.iter().map(|a| eval(a, p))),
    }
}

fn check(node: &Node, p: &[f64; 4]) -> Result<f64, Undefined> {
    let (v, column, what) = match node {
        Node::Number(v) => return Ok(*v),
        Node::Variable(v, _) => return Ok(p[v.index()]),
        Node::Negate(a) => return check(a, p).map(|v| -v),
        Node::Binary {
            op,
            column,
            left,
            right,
        } => {
            let (a, b) = (check(left, p)?, check(right, p)?);
            (
                op.apply(a, b),
                *column,
                format!("{} of {a} and {b}", op.what()),
            )
        }
        Node::Call {
            function,
            column,
            args,
        } => {
            let vals = args
                .iter()
                .map(|a| check(a, p))
                .collect::<Result<Vec<f64>, _>>()?;
            let shown: Vec<String> = vals.iter().map(|v| v.to_string()).collect();
            (
                function.apply(vals.iter().copied()),
                *column,
                format!("{}({})", function.name(), shown.join(", ")),
            )
        }
    };
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Undefined {
            column,
            message: format!("{what} is {v}"),
        })
    }
}

fn collect(node: &Node, out: &mut Vec<(Variable, usize)>) {
    match node {
        Node::Number(_) => {}
        Node::Variable(v, column) => {
            if !out.iter().any(|o| o.0 == *v) {
                out.push((*v, *column));
            }
        }
        Node::Negate(a) => collect(a, out),
        Node::Binary { left, right, .. } => {
            collect(left, out);
            collect(right, out);
        }
        Node::Call { args, .. } => args.iter().for_each(|a| collect(a, out)),
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Number(f64),
    Name(String),
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    Open,
    Close,
    Comma,
    End,
}

/// The tokens of `chars`, each with its column (from 1); the last is
/// [`Token::End`] one past the text.
fn lex(chars: &[char]) -> Result<Vec<(Token, usize)>, SyntaxError> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let column = i + 1;
        let single = match c {
            '+' => Some(Token::Plus),
            '-' => Some(Token::Minus),
            '*' => Some(Token::Star),
            '/' => Some(Token::Slash),
            '^' => Some(Token::Caret),
            '(' => Some(Token::Open),
            ')' => Some(Token::Close),
            ',' => Some(Token::Comma),
            _ => None,
        };
        if let Some(t) = single {
            out.push((t, column));
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let (v, next) = number(chars, i)?;
            out.push((Token::Number(v), column));
            i = next;
        } else if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push((Token::Name(chars[start..i].iter().collect()), column));
        } else {
            return Err(SyntaxError {
                column,
                message: format!("'{c}' is not part of an expression (numbers, x, y, z, r, pi, + - * / ^, parentheses, commas and the functions sqrt, exp, ln, sin, cos, abs, min, max are)"),
            });
        }
    }
    out.push((Token::End, chars.len() + 1));
    Ok(out)
}

/// The number starting at `chars[i]` and the index after it.
fn number(chars: &[char], start: usize) -> Result<(f64, usize), SyntaxError> {
    let digits = |mut i: usize| {
        while i < chars.len() && chars[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut i = digits(start);
    let whole = i > start;
    let mut fraction = false;
    if i < chars.len() && chars[i] == '.' {
        let j = digits(i + 1);
        fraction = j > i + 1;
        i = j;
    }
    if !whole && !fraction {
        return Err(SyntaxError {
            column: start + 1,
            message: "a '.' without digits is no number".into(),
        });
    }
    if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
        let mut j = i + 1;
        if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
            j += 1;
        }
        let k = digits(j);
        if k == j {
            return Err(SyntaxError {
                column: k + 1,
                message: "the number's exponent has no digits".into(),
            });
        }
        i = k;
    }
    let text: String = chars[start..i].iter().collect();
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok((v, i)),
        _ => Err(SyntaxError {
            column: start + 1,
            message: format!("{text} is not a finite number"),
        }),
    }
}

struct Parser<'a> {
    tokens: &'a [(Token, usize)],
    at: usize,
    depth: usize,
}

impl Parser<'_> {
    fn peek(&self) -> &Token {
        &self.tokens[self.at].0
    }

    fn column(&self) -> usize {
        self.tokens[self.at].1
    }

    fn error(&self, message: String) -> SyntaxError {
        SyntaxError {
            column: self.column(),
            message,
        }
    }

    /// One level deeper, refused past [`MAX_DEPTH`] levels of nesting
    /// (the expression itself is the level before the first).
    fn deeper(&mut self) -> Result<(), SyntaxError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH + 1 {
            return Err(self.error(format!(
                "nested deeper than {MAX_DEPTH} levels (parentheses, signs and powers)"
            )));
        }
        Ok(())
    }

    fn sum(&mut self) -> Result<Node, SyntaxError> {
        let mut left = self.product()?;
        loop {
            let op = match self.peek() {
                Token::Plus => Op::Add,
                Token::Minus => Op::Sub,
                _ => return Ok(left),
            };
            let column = self.column();
            self.at += 1;
            let right = self.product()?;
            left = binary(op, column, left, right);
        }
    }

    fn product(&mut self) -> Result<Node, SyntaxError> {
        let mut left = self.unary()?;
        loop {
            let op = match self.peek() {
                Token::Star => Op::Mul,
                Token::Slash => Op::Div,
                _ => return Ok(left),
            };
            let column = self.column();
            self.at += 1;
            let right = self.unary()?;
            left = binary(op, column, left, right);
        }
    }

    fn unary(&mut self) -> Result<Node, SyntaxError> {
        self.deeper()?;
        let node = match self.peek() {
            Token::Minus => {
                self.at += 1;
                Node::Negate(Box::new(self.unary()?))
            }
            Token::Plus => {
                self.at += 1;
                self.unary()?
            }
            _ => self.power()?,
        };
        self.depth -= 1;
        Ok(node)
    }

    fn power(&mut self) -> Result<Node, SyntaxError> {
        let base = self.primary()?;
        if *self.peek() != Token::Caret {
            return Ok(base);
        }
        let column = self.column();
        self.at += 1;
        // the exponent is a unary: right-associative, and 2^-1 reads
        let exponent = self.unary()?;
        Ok(binary(Op::Pow, column, base, exponent))
    }

    fn primary(&mut self) -> Result<Node, SyntaxError> {
        let column = self.column();
        match self.peek().clone() {
            Token::Number(v) => {
                self.at += 1;
                Ok(Node::Number(v))
            }
            Token::Name(name) => {
                self.at += 1;
                self.name(&name, column)
            }
            Token::Open => {
                self.at += 1;
                let inner = self.sum()?;
                self.close(column)?;
                Ok(inner)
            }
            Token::End => Err(self.error(
                "the expression ends where a number, a variable, a function or '(' is expected"
                    .into(),
            )),
            Token::Close => {
                Err(self
                    .error("')' where a number, a variable, a function or '(' is expected".into()))
            }
            _ => Err(self.error("expected a number, a variable, a function or '('".into())),
        }
    }

    /// The ')' that closes the '(' at column `open`.
    fn close(&mut self, open: usize) -> Result<(), SyntaxError> {
        match self.peek() {
            Token::Close => {
                self.at += 1;
                Ok(())
            }
            Token::End => Err(SyntaxError {
                column: open,
                message: "this '(' is not closed".into(),
            }),
            _ => Err(self.error("expected ')' (or an operator)".into())),
        }
    }

    /// A variable, the constant pi, or a function's call.
    fn name(&mut self, name: &str, column: usize) -> Result<Node, SyntaxError> {
        let at_name = |message: String| SyntaxError { column, message };
        if let Some(&(_, v)) = VARIABLES.iter().find(|(n, _)| *n == name) {
            if *self.peek() == Token::Open {
                return Err(at_name(format!("{name} is a variable, not a function")));
            }
            return Ok(Node::Variable(v, column));
        }
        if name == "pi" {
            return Ok(Node::Number(std::f64::consts::PI));
        }
        let Some(&(_, function)) = FUNCTIONS.iter().find(|(n, _)| *n == name) else {
            let names: Vec<&str> = FUNCTIONS.iter().map(|f| f.0).collect();
            return Err(at_name(format!(
                "unknown name \"{}\" (variables: x, y, z, r; the constant pi; functions: {})",
                crate::error::clip(name),
                names.join(", ")
            )));
        };
        if *self.peek() != Token::Open {
            return Err(at_name(format!(
                "{name} needs its argument(s) in parentheses"
            )));
        }
        let open = self.column();
        self.at += 1;
        self.deeper()?;
        let mut args = vec![self.sum()?];
        while *self.peek() == Token::Comma {
            self.at += 1;
            args.push(self.sum()?);
        }
        self.close(open)?;
        self.depth -= 1;
        let n = args.len();
        if function.unary() && n != 1 {
            return Err(at_name(format!("{name} takes one argument, given {n}")));
        }
        if !function.unary() && n < 2 {
            return Err(at_name(format!(
                "{name} takes two or more arguments, given {n}"
            )));
        }
        Ok(Node::Call {
            function,
            column,
            args,
        })
    }
}

fn binary(op: Op, column: usize, left: Node, right: Node) -> Node {
    Node::Binary {
        op,
        column,
        left: Box::new(left),
        right: Box::new(right),
    }
}

#[cfg(test)]
mod tests;
