//! Expressions of a model file: parsed (`parse.rs`) into an `Expr` tree over numbered
//! variables, differentiated symbolically (`diff.rs`) and compiled onto a `Tape` (`tape.rs`) that
//! evaluates on f64 without allocating (the RK4 machinery calls it for every stage).

mod diff;
mod parse;
mod tape;

pub use parse::{parse, ParseError};
pub use tape::{Split, Tape, TapeBuilder};

/// A function callable in an expression.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Func {
    Sqrt,
    Exp,
    Ln,
    Sin,
    Cos,
    Tan,
    Tanh,
    Abs,
    Min,
    Max,
    /// Internal (derivatives of abs): −1, 0 or 1.
    Sign,
    /// Internal (derivatives of min, max): 1 where the argument is ≥ 0, else 0.
    Step,
}

/// The functions a file may call, by name (`log` is the natural logarithm, like `ln`).
pub const FUNCTIONS: &[(&str, Func)] = &[
    ("sqrt", Func::Sqrt),
    ("exp", Func::Exp),
    ("ln", Func::Ln),
    ("log", Func::Ln),
    ("sin", Func::Sin),
    ("cos", Func::Cos),
    ("tan", Func::Tan),
    ("tanh", Func::Tanh),
    ("abs", Func::Abs),
    ("min", Func::Min),
    ("max", Func::Max),
];

impl Func {
    fn by_name(name: &str) -> Option<Func> {
        FUNCTIONS.iter().find(|(n, _)| *n == name).map(|(_, f)| *f)
    }
    fn arity(self) -> usize {
        match self {
            Func::Min | Func::Max => 2,
            _ => 1,
        }
    }
    fn apply(self, a: f64, b: f64) -> f64 {
        match self {
            Func::Sqrt => a.sqrt(),
            Func::Exp => a.exp(),
            Func::Ln => a.ln(),
            Func::Sin => a.sin(),
            Func::Cos => a.cos(),
            Func::Tan => a.tan(),
            Func::Tanh => a.tanh(),
            Func::Abs => a.abs(),
            Func::Min => a.min(b),
            Func::Max => a.max(b),
            Func::Sign => {
                if a > 0.0 {
                    1.0
                } else if a < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            }
            Func::Step => f64::from(u8::from(a >= 0.0)),
        }
    }
}

/// Binary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Op {
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
            Op::Pow => pow(a, b),
        }
    }
}

/// a^b, with small integer exponents multiplied out (exact and defined for a < 0).
fn pow(a: f64, b: f64) -> f64 {
    if b == b.trunc() && b.abs() <= 16.0 {
        a.powi(b as i32)
    } else {
        a.powf(b)
    }
}

/// An expression over variables numbered by the model (states, parameters, then t).
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    Num(f64),
    Var(usize),
    Neg(Box<Expr>),
    Bin(Op, Box<Expr>, Box<Expr>),
    Call(Func, Vec<Expr>),
}

#[allow(clippy::redundant_guards)]
impl Expr {
    fn num(&self) -> Option<f64> {
        match self {
            Expr::Num(v) => Some(*v),
            _ => None,
        }
    }
    /// Constant-folding constructors: the derivatives stay small.
    pub fn sum(a: Expr, b: Expr) -> Expr {
        match (a.num(), b.num()) {
            (Some(x), Some(y)) => Expr::Num(x + y),
            (Some(x), _) if x == 0.0 => b,
            (_, Some(y)) if y == 0.0 => a,
            _ => Expr::Bin(Op::Add, Box::new(a), Box::new(b)),
        }
    }
    pub fn difference(a: Expr, b: Expr) -> Expr {
        match (a.num(), b.num()) {
            (Some(x), Some(y)) => Expr::Num(x - y),
            (Some(x), _) if x == 0.0 => Expr::negate(b),
            (_, Some(y)) if y == 0.0 => a,
            _ => Expr::Bin(Op::Sub, Box::new(a), Box::new(b)),
        }
    }
    pub fn product(a: Expr, b: Expr) -> Expr {
        match (a.num(), b.num()) {
            (Some(x), Some(y)) => Expr::Num(x * y),
            (Some(x), _) | (_, Some(x)) if x == 0.0 => Expr::Num(0.0),
            (Some(x), _) if x == 1.0 => b,
            (_, Some(y)) if y == 1.0 => a,
            _ => Expr::Bin(Op::Mul, Box::new(a), Box::new(b)),
        }
    }
    pub fn quotient(a: Expr, b: Expr) -> Expr {
        match (a.num(), b.num()) {
            (Some(x), Some(y)) if y != 0.0 => Expr::Num(x / y),
            (Some(x), _) if x == 0.0 => Expr::Num(0.0),
            (_, Some(y)) if y == 1.0 => a,
            _ => Expr::Bin(Op::Div, Box::new(a), Box::new(b)),
        }
    }
    pub fn pow(a: Expr, b: Expr) -> Expr {
        match (a.num(), b.num()) {
            (Some(x), Some(y)) => Expr::Num(pow(x, y)),
            (_, Some(y)) if y == 0.0 => Expr::Num(1.0),
            (_, Some(y)) if y == 1.0 => a,
            _ => Expr::Bin(Op::Pow, Box::new(a), Box::new(b)),
        }
    }
    pub fn negate(a: Expr) -> Expr {
        match a {
            Expr::Num(x) => Expr::Num(-x),
            Expr::Neg(inner) => *inner,
            a => Expr::Neg(Box::new(a)),
        }
    }
    pub fn call(f: Func, args: Vec<Expr>) -> Expr {
        if args.iter().all(|a| a.num().is_some()) {
            let a = args[0].num().unwrap_or(0.0);
            let b = args.get(1).and_then(Expr::num).unwrap_or(0.0);
            return Expr::Num(f.apply(a, b));
        }
        Expr::Call(f, args)
    }

    /// Whether variable `v` appears.
    pub fn uses(&self, v: usize) -> bool {
        match self {
            Expr::Num(_) => false,
            Expr::Var(i) => *i == v,
            Expr::Neg(a) => a.uses(v),
            Expr::Bin(_, a, b) => a.uses(v) || b.uses(v),
            Expr::Call(_, args) => args.iter().any(|a| a.uses(v)),
        }
    }

    /// The value at variables `vars`.
    pub fn eval(&self, vars: &[f64]) -> f64 {
        match self {
            Expr::Num(v) => *v,
            Expr::Var(i) => vars[*i],
            Expr::Neg(a) => -a.eval(vars),
            Expr::Bin(op, a, b) => op.apply(a.eval(vars), b.eval(vars)),
            Expr::Call(f, args) => {
                let a = args[0].eval(vars);
                let b = args.get(1).map_or(0.0, |b| b.eval(vars));
                f.apply(a, b)
            }
        }
    }

    /// ∂/∂(variable `v`).
    pub fn derivative(&self, v: usize) -> Expr {
        diff::derivative(self, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vars(name: &str) -> Option<usize> {
        ["x", "v", "a", "b", "t"].iter().position(|n| *n == name)
    }

    #[test]
    fn precedence_and_functions_evaluate_as_written() {
        let at = [2.0, -1.0, 3.0, 0.5, 0.25];
        let cases = [
            ("-x^2", -4.0),
            ("2^3^2", 512.0),
            ("-a*x - b*x^3 - 0.1*v", -6.0 - 4.0 + 0.1),
            ("(x + v) * a / b", 6.0),
            ("sqrt(a*3) + exp(0) + ln(1) + log(1)", 4.0),
            ("min(x, v) + max(x, v) + abs(v)", 2.0),
            ("sin(pi/2) + cos(0) + tan(0) + tanh(0)", 2.0),
            ("2^-1", 0.5),
            ("1e-3*1E3 + .5", 1.5),
            ("t", 0.25),
        ];
        for (text, want) in cases {
            let e = parse(text, &vars).unwrap();
            assert!(
                (e.eval(&at) - want).abs() < 1e-12,
                "{text}: {}",
                e.eval(&at)
            );
            let mut b = TapeBuilder::default();
            b.output(&e);
            let all = b.len();
            let tape = b.finish();
            let mut buf = vec![0.0; tape.buffer_len()];
            tape.run(&at, all, &mut buf);
            assert!(
                (tape.output(0, &buf) - want).abs() < 1e-12,
                "{text} on a tape"
            );
        }
    }

    #[test]
    fn a_sine_and_a_cosine_of_one_argument_share_a_node_and_keep_their_values() {
        let at = [0.7, -1.3, 3.0, 0.5, 0.25];
        // Either order, beside a sine of another argument, one of them in the prefix only.
        let texts = [
            "cos(x) * a",
            "sin(v) + sin(x)",
            "x - sin(x)*cos(v)",
            "cos(x)^2",
        ];
        let mut b = TapeBuilder::default();
        let exprs: Vec<Expr> = texts.iter().map(|t| parse(t, &vars).unwrap()).collect();
        b.output(&exprs[0]);
        let prefix = b.len();
        for e in &exprs[1..] {
            b.output(e);
        }
        let all = b.len();
        let tape = b.finish();
        let mut buf = vec![0.0; tape.buffer_len()];
        // sin_cos agrees with sin and cos (to the bit with glibc; a few ulp allowed elsewhere).
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * (1.0 + b.abs());
        tape.run(&at, prefix, &mut buf);
        assert!(close(tape.output(0, &buf), exprs[0].eval(&at)));
        tape.run(&at, all, &mut buf);
        for (k, e) in exprs.iter().enumerate() {
            let (got, want) = (tape.output(k, &buf), e.eval(&at));
            assert!(close(got, want), "{}: {got} vs {want}", texts[k]);
        }
    }

    #[test]
    fn errors_name_the_column() {
        let err = |t: &str| parse(t, &vars).unwrap_err();
        assert_eq!(err("-a*x - q*v").column, 8);
        assert!(err("-a*x - q*v").message.contains("unknown name 'q'"));
        assert_eq!(err("x + (v").column, 7);
        assert_eq!(err("x $ v").column, 3);
        assert!(err("sin x").message.contains("function"));
        assert!(err("min(x)").message.contains("2 argument"));
        assert!(err("x v").message.contains("after"));
        assert!(err("").message.contains("early"));
        let deep = format!("{}x{}", "(".repeat(300), ")".repeat(300));
        assert!(err(&deep).message.contains("nested more than 200"));
        // Long but flat: a tree as deep as the expression is long, refused before it is built.
        let deep = format!("{}x{}", "(".repeat(100_000), ")".repeat(100_000));
        assert!(err(&deep).message.contains("at most 1000"));
        let flat = vec!["x"; 30_000].join("+");
        let e = err(&flat);
        assert!(e.message.contains("59999 tokens"), "{}", e.message);
        assert!(err(&"-".repeat(300)).message.contains("nested"));
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let texts = [
            "-a*x - b*x^3 - 0.1*v",
            "sqrt(abs(x)) * exp(-b*t) + sin(x*v)/cos(a)",
            "min(x, a) - max(v, b) + x^b + tanh(v) + tan(b) + ln(a)",
        ];
        let at = [0.7, -0.4, 1.3, 0.6, 0.9];
        for text in texts {
            let e = parse(text, &vars).unwrap();
            for v in 0..5 {
                let d = e.derivative(v).eval(&at);
                let h = 1e-6;
                let (mut p, mut m) = (at, at);
                p[v] += h;
                m[v] -= h;
                let fd = (e.eval(&p) - e.eval(&m)) / (2.0 * h);
                assert!(
                    (d - fd).abs() < 1e-6 * (1.0 + fd.abs()),
                    "{text} d/d{v}: {d} vs {fd}"
                );
            }
        }
    }
}
