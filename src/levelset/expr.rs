//! User expressions in `x` and `y` (`"x^2 + y^2 - 0.25"`), and with [`Expr::parse_with`] also in
//! `z` and the time `t`, parsed by recursive descent and compiled to a postfix program evaluated
//! on a small stack.
//!
//! Grammar (`^` binds tighter than unary minus and is right-associative, so `-x^2 = -(x^2)` and
//! `2^3^2 = 2^9`):
//! ```text
//! expr   := term (('+' | '-') term)*
//! term   := unary (('*' | '/') unary)*
//! unary  := ('-' | '+') unary | power
//! power  := atom ('^' unary)?
//! atom   := number | variable | 'pi' | func '(' expr (',' expr)* ')' | '(' expr ')'
//! func   := sqrt abs sin cos tan exp log (one argument) | min max atan2 (two arguments)
//! ```
//! The variables are `x` and `y` ([`Expr::parse`]) or the set named by [`Variables`]
//! ([`Expr::parse_with`]): `x y z` for 3D shapes, `x y t` for time-dependent velocity fields.
//! Numbers accept a fraction and an exponent (`1e-3`, `.5`, `2.5E+2`). Errors name the 1-based
//! column and the problem ("unexpected ')' at column 7"). Parsing never panics; nesting deeper
//! than [`MAX_DEPTH`] is an error rather than a stack overflow.

use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};

/// Maximum nesting depth (parentheses, unary signs, powers, function calls).
pub const MAX_DEPTH: usize = 200;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Op {
    Num(f64),
    X,
    Y,
    Z,
    T,
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    F1(F1),
    F2(F2),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum F1 {
    Sqrt,
    Abs,
    Sin,
    Cos,
    Tan,
    Exp,
    Log,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum F2 {
    Min,
    Max,
    Atan2,
}

/// A compiled expression in `x` and `y`.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    source: String,
    program: Vec<Op>,
    max_stack: usize,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Tok {
    Num(f64),
    Ident(usize, usize), // char range [start, end) in the source
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    LParen,
    RParen,
    Comma,
    End,
}

fn describe(t: Tok, chars: &[char]) -> String {
    match t {
        Tok::Num(_) => "number".into(),
        Tok::Ident(a, b) => format!("'{}'", chars[a..b].iter().collect::<String>()),
        Tok::Plus => "'+'".into(),
        Tok::Minus => "'-'".into(),
        Tok::Star => "'*'".into(),
        Tok::Slash => "'/'".into(),
        Tok::Caret => "'^'".into(),
        Tok::LParen => "'('".into(),
        Tok::RParen => "')'".into(),
        Tok::Comma => "','".into(),
        Tok::End => "end of input".into(),
    }
}

/// Splits the source into tokens with their 1-based columns.
fn tokenize(chars: &[char], src: &str) -> Result<Vec<(Tok, usize)>> {
    let err = |col: usize, msg: String| {
        Error::InvalidInput(format!("expression '{src}': {msg} at column {col}"))
    };
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let col = i + 1;
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        let single = match c {
            '+' => Some(Tok::Plus),
            '-' => Some(Tok::Minus),
            '*' => Some(Tok::Star),
            '/' => Some(Tok::Slash),
            '^' => Some(Tok::Caret),
            '(' => Some(Tok::LParen),
            ')' => Some(Tok::RParen),
            ',' => Some(Tok::Comma),
            _ => None,
        };
        if let Some(t) = single {
            out.push((t, col));
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    while j < chars.len() && chars[j].is_ascii_digit() {
                        j += 1;
                    }
                    i = j;
                } else {
                    return Err(err(
                        col,
                        "malformed number (exponent without digits)".into(),
                    ));
                }
            }
            let text: String = chars[start..i].iter().collect();
            match text.parse::<f64>() {
                Ok(v) if v.is_finite() => out.push((Tok::Num(v), col)),
                Ok(_) => return Err(err(col, format!("number '{text}' is out of range"))),
                Err(_) => return Err(err(col, format!("malformed number '{text}'"))),
            }
        } else if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push((Tok::Ident(start, i), col));
        } else {
            return Err(err(col, format!("unexpected character '{c}'")));
        }
    }
    out.push((Tok::End, chars.len() + 1));
    Ok(out)
}

struct Parser<'a> {
    src: &'a str,
    chars: &'a [char],
    toks: Vec<(Tok, usize)>,
    pos: usize,
    depth: usize,
    program: Vec<Op>,
    vars: Variables,
}

impl Parser<'_> {
    fn peek(&self) -> (Tok, usize) {
        self.toks[self.pos]
    }

    fn bump(&mut self) -> (Tok, usize) {
        let t = self.toks[self.pos];
        if self.pos + 1 < self.toks.len() {
            self.pos += 1;
        }
        t
    }

    fn error(&self, col: usize, msg: impl Into<String>) -> Error {
        Error::InvalidInput(format!(
            "expression '{}': {} at column {col}",
            self.src,
            msg.into()
        ))
    }

    fn unexpected(&self, (t, col): (Tok, usize)) -> Error {
        self.error(col, format!("unexpected {}", describe(t, self.chars)))
    }

    fn enter(&mut self, col: usize) -> Result<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.error(col, format!("nesting deeper than {MAX_DEPTH}")));
        }
        Ok(())
    }

    fn expr(&mut self) -> Result<()> {
        self.term()?;
        loop {
            let op = match self.peek().0 {
                Tok::Plus => Op::Add,
                Tok::Minus => Op::Sub,
                _ => return Ok(()),
            };
            self.bump();
            self.term()?;
            self.program.push(op);
        }
    }

    fn term(&mut self) -> Result<()> {
        self.unary()?;
        loop {
            let op = match self.peek().0 {
                Tok::Star => Op::Mul,
                Tok::Slash => Op::Div,
                _ => return Ok(()),
            };
            self.bump();
            self.unary()?;
            self.program.push(op);
        }
    }

    fn unary(&mut self) -> Result<()> {
        let (t, col) = self.peek();
        match t {
            Tok::Minus | Tok::Plus => {
                self.bump();
                self.enter(col)?;
                self.unary()?;
                self.depth -= 1;
                if t == Tok::Minus {
                    self.program.push(Op::Neg);
                }
                Ok(())
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<()> {
        self.atom()?;
        if let (Tok::Caret, col) = self.peek() {
            self.bump();
            self.enter(col)?;
            self.unary()?;
            self.depth -= 1;
            self.program.push(Op::Pow);
        }
        Ok(())
    }

    fn atom(&mut self) -> Result<()> {
        let tok = self.bump();
        match tok.0 {
            Tok::Num(v) => self.program.push(Op::Num(v)),
            Tok::LParen => {
                self.enter(tok.1)?;
                self.expr()?;
                self.depth -= 1;
                let close = self.bump();
                if close.0 != Tok::RParen {
                    return Err(self.error(
                        close.1,
                        format!(
                            "expected ')' to close '(' at column {}, found {}",
                            tok.1,
                            describe(close.0, self.chars)
                        ),
                    ));
                }
            }
            Tok::Ident(a, b) => {
                let name: String = self.chars[a..b].iter().collect();
                self.ident(&name, tok.1)?;
            }
            _ => return Err(self.unexpected(tok)),
        }
        Ok(())
    }

    fn ident(&mut self, name: &str, col: usize) -> Result<()> {
        let var = match name {
            "x" => Some(Op::X),
            "y" => Some(Op::Y),
            "z" if self.vars.z => Some(Op::Z),
            "t" if self.vars.t => Some(Op::T),
            "pi" => Some(Op::Num(std::f64::consts::PI)),
            _ => None,
        };
        if let Some(op) = var {
            self.program.push(op);
            return Ok(());
        }
        let f1 = match name {
            "sqrt" => Some(F1::Sqrt),
            "abs" => Some(F1::Abs),
            "sin" => Some(F1::Sin),
            "cos" => Some(F1::Cos),
            "tan" => Some(F1::Tan),
            "exp" => Some(F1::Exp),
            "log" => Some(F1::Log),
            _ => None,
        };
        let f2 = match name {
            "min" => Some(F2::Min),
            "max" => Some(F2::Max),
            "atan2" => Some(F2::Atan2),
            _ => None,
        };
        let arity = match (f1, f2) {
            (Some(_), _) => 1,
            (_, Some(_)) => 2,
            _ => {
                return Err(self.error(
                    col,
                    format!(
                        "unknown name '{name}' (variables: {}, pi; functions: sqrt abs sin cos tan exp log min max atan2)",
                        self.vars.names()
                    ),
                ))
            }
        };
        let open = self.bump();
        if open.0 != Tok::LParen {
            return Err(self.error(
                open.1,
                format!(
                    "expected '(' after function '{name}', found {}",
                    describe(open.0, self.chars)
                ),
            ));
        }
        self.enter(open.1)?;
        let mut n_args = 0;
        loop {
            self.expr()?;
            n_args += 1;
            let next = self.bump();
            match next.0 {
                Tok::Comma => continue,
                Tok::RParen => break,
                _ => {
                    return Err(self.error(
                        next.1,
                        format!(
                            "expected ',' or ')' in the arguments of '{name}', found {}",
                            describe(next.0, self.chars)
                        ),
                    ))
                }
            }
        }
        self.depth -= 1;
        if n_args != arity {
            return Err(self.error(
                col,
                format!("function '{name}' takes {arity} argument(s), got {n_args}"),
            ));
        }
        self.program.push(match (f1, f2) {
            (Some(f), _) => Op::F1(f),
            (_, Some(f)) => Op::F2(f),
            _ => unreachable!("arity was checked above"),
        });
        Ok(())
    }
}

impl Expr {
    /// Parses and compiles `source`. Errors ([`Error::InvalidInput`]) name the column and the
    /// problem.
    pub fn parse(source: &str) -> Result<Expr> {
        Expr::parse_with(source, Variables::XY)
    }

    /// Parses and compiles `source` with the variables `vars` (any other name is an error naming
    /// the valid ones).
    pub fn parse_with(source: &str, vars: Variables) -> Result<Expr> {
        let chars: Vec<char> = source.chars().collect();
        let toks = tokenize(&chars, source)?;
        let mut p = Parser {
            src: source,
            chars: &chars,
            toks,
            pos: 0,
            depth: 0,
            program: Vec::new(),
            vars,
        };
        if p.peek().0 == Tok::End {
            return Err(p.error(1, "empty expression"));
        }
        p.expr()?;
        let last = p.peek();
        if last.0 != Tok::End {
            return Err(p.unexpected(last));
        }
        let program = p.program;
        let mut depth = 0usize;
        let mut max_stack = 0usize;
        for op in &program {
            depth = match op {
                Op::Num(_) | Op::X | Op::Y | Op::Z | Op::T => depth + 1,
                Op::Neg | Op::F1(_) => depth,
                _ => depth - 1,
            };
            max_stack = max_stack.max(depth);
        }
        Ok(Expr {
            source: source.to_string(),
            program,
            max_stack,
        })
    }

    /// The source text.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// Evaluates at `p = (x, y)` (with `z = t = 0`). IEEE semantics: `sqrt(-1)` and `log(0)`
    /// give NaN and `-inf`.
    pub fn eval(&self, p: DVec2) -> f64 {
        self.eval_vars([p.x, p.y, 0.0, 0.0])
    }

    /// Evaluates at `p = (x, y, z)` (with `t = 0`).
    pub fn eval3(&self, p: DVec3) -> f64 {
        self.eval_vars([p.x, p.y, p.z, 0.0])
    }

    /// Evaluates at `p = (x, y)` and time `t` (with `z = 0`).
    pub fn eval_t(&self, p: DVec2, t: f64) -> f64 {
        self.eval_vars([p.x, p.y, 0.0, t])
    }

    /// Evaluates with the variables `[x, y, z, t]`.
    pub fn eval_vars(&self, p: [f64; 4]) -> f64 {
        const SMALL: usize = 32;
        if self.max_stack <= SMALL {
            let mut stack = [0.0f64; SMALL];
            self.run(p, &mut stack)
        } else {
            let mut stack = vec![0.0f64; self.max_stack];
            self.run(p, &mut stack)
        }
    }

    fn run(&self, p: [f64; 4], stack: &mut [f64]) -> f64 {
        let mut n = 0usize;
        for op in &self.program {
            match *op {
                Op::Num(v) => {
                    stack[n] = v;
                    n += 1;
                }
                Op::X | Op::Y | Op::Z | Op::T => {
                    stack[n] = p[match *op {
                        Op::X => 0,
                        Op::Y => 1,
                        Op::Z => 2,
                        _ => 3,
                    }];
                    n += 1;
                }
                Op::Neg => stack[n - 1] = -stack[n - 1],
                Op::F1(f) => {
                    let v = stack[n - 1];
                    stack[n - 1] = match f {
                        F1::Sqrt => v.sqrt(),
                        F1::Abs => v.abs(),
                        F1::Sin => v.sin(),
                        F1::Cos => v.cos(),
                        F1::Tan => v.tan(),
                        F1::Exp => v.exp(),
                        F1::Log => v.ln(),
                    };
                }
                _ => {
                    let (a, b) = (stack[n - 2], stack[n - 1]);
                    n -= 1;
                    stack[n - 1] = match *op {
                        Op::Add => a + b,
                        Op::Sub => a - b,
                        Op::Mul => a * b,
                        Op::Div => a / b,
                        Op::Pow => a.powf(b),
                        Op::F2(F2::Min) => a.min(b),
                        Op::F2(F2::Max) => a.max(b),
                        Op::F2(F2::Atan2) => a.atan2(b),
                        _ => unreachable!("unary ops handled above"),
                    };
                }
            }
        }
        stack[0]
    }
}

/// The variables an expression may use besides `x` and `y` (see [`Expr::parse_with`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Variables {
    /// Whether `z` is a variable (3D shapes).
    pub z: bool,
    /// Whether `t` is a variable (time-dependent fields).
    pub t: bool,
}

impl Variables {
    /// `x`, `y`.
    pub const XY: Variables = Variables { z: false, t: false };
    /// `x`, `y`, `z`.
    pub const XYZ: Variables = Variables { z: true, t: false };
    /// `x`, `y`, `t`.
    pub const XYT: Variables = Variables { z: false, t: true };
    /// `x`, `y`, `z`, `t`.
    pub const XYZT: Variables = Variables { z: true, t: true };

    fn names(self) -> &'static str {
        match (self.z, self.t) {
            (false, false) => "x, y",
            (true, false) => "x, y, z",
            (false, true) => "x, y, t",
            (true, true) => "x, y, z, t",
        }
    }
}

impl std::str::FromStr for Expr {
    type Err = Error;
    fn from_str(s: &str) -> Result<Expr> {
        Expr::parse(s)
    }
}
