//! The expression grammar: numbers, names, `+ - * / ^` (`^` binds tightest and to the right,
//! above unary minus: `-x^2` is `-(x^2)`), parentheses and calls `f(a, b)`. Errors carry the
//! 1-based column of the offending character.

use super::{Expr, Func};

/// The deepest nesting an expression may have (a bound on the parser's recursion).
pub const MAX_NESTING: usize = 200;

/// The most tokens an expression may have: a flat sum of tens of thousands of terms is a tree
/// as deep as it is long, which every pass over it (derivatives, the tape, dropping it) would
/// walk recursively.
pub const MAX_TOKENS: usize = 1000;

/// A parse or name error: the 1-based column and what is wrong there.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    pub column: usize,
    pub message: String,
}

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Num(f64),
    Name(String),
    Sym(char),
    End,
}

fn lex(text: &str) -> Result<Vec<(Token, usize)>, ParseError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let column = i + 1;
        if c.is_whitespace() {
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
                    i = j;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let s: String = chars[start..i].iter().collect();
            let v: f64 = s.parse().map_err(|_| ParseError {
                column,
                message: format!("'{s}' is not a number"),
            })?;
            out.push((Token::Num(v), column));
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push((Token::Name(chars[start..i].iter().collect()), column));
        } else if "+-*/^(),".contains(c) {
            out.push((Token::Sym(c), column));
            i += 1;
        } else {
            return Err(ParseError {
                column,
                message: format!("unexpected character '{c}'"),
            });
        }
    }
    out.push((Token::End, chars.len() + 1));
    Ok(out)
}

/// A recursive-descent parser over the tokens; `lookup` turns a name into a variable index.
struct Parser<'a> {
    tokens: Vec<(Token, usize)>,
    at: usize,
    /// Nesting so far (parentheses, signs, exponents), bounded by [`MAX_NESTING`].
    depth: usize,
    lookup: &'a dyn Fn(&str) -> Option<usize>,
}

impl Parser<'_> {
    fn peek(&self) -> &Token {
        &self.tokens[self.at].0
    }
    fn column(&self) -> usize {
        self.tokens[self.at].1
    }
    fn error<T>(&self, message: impl Into<String>) -> Result<T, ParseError> {
        Err(ParseError {
            column: self.column(),
            message: message.into(),
        })
    }
    fn eat(&mut self, c: char) -> bool {
        if *self.peek() == Token::Sym(c) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    fn sum(&mut self) -> Result<Expr, ParseError> {
        let mut e = self.product()?;
        loop {
            if self.eat('+') {
                e = Expr::sum(e, self.product()?);
            } else if self.eat('-') {
                e = Expr::difference(e, self.product()?);
            } else {
                return Ok(e);
            }
        }
    }

    fn product(&mut self) -> Result<Expr, ParseError> {
        let mut e = self.unary()?;
        loop {
            if self.eat('*') {
                e = Expr::product(e, self.unary()?);
            } else if self.eat('/') {
                e = Expr::quotient(e, self.unary()?);
            } else {
                return Ok(e);
            }
        }
    }

    fn unary(&mut self) -> Result<Expr, ParseError> {
        if self.depth >= MAX_NESTING {
            return self.error(format!("nested more than {MAX_NESTING} levels deep"));
        }
        self.depth += 1;
        let e = self.signed();
        self.depth -= 1;
        e
    }

    fn signed(&mut self) -> Result<Expr, ParseError> {
        if self.eat('-') {
            return Ok(Expr::negate(self.unary()?));
        }
        if self.eat('+') {
            return self.unary();
        }
        self.power()
    }

    fn power(&mut self) -> Result<Expr, ParseError> {
        let base = self.atom()?;
        if self.eat('^') {
            // Right-associative, and the exponent may carry its own sign: 2^-x.
            let exponent = self.unary()?;
            return Ok(Expr::pow(base, exponent));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Expr, ParseError> {
        let column = self.column();
        match self.peek().clone() {
            Token::Num(v) => {
                self.at += 1;
                Ok(Expr::Num(v))
            }
            Token::Sym('(') => {
                self.at += 1;
                let e = self.sum()?;
                if !self.eat(')') {
                    return self.error("expected ')'");
                }
                Ok(e)
            }
            Token::Name(name) => {
                self.at += 1;
                if let Some(func) = Func::by_name(&name) {
                    if !self.eat('(') {
                        return self.error(format!("{name} is a function: write {name}(...)"));
                    }
                    let mut args = vec![self.sum()?];
                    while self.eat(',') {
                        args.push(self.sum()?);
                    }
                    if !self.eat(')') {
                        return self.error("expected ')' or ','");
                    }
                    if args.len() != func.arity() {
                        return Err(ParseError {
                            column,
                            message: format!(
                                "{name} takes {} argument(s), not {}",
                                func.arity(),
                                args.len()
                            ),
                        });
                    }
                    return Ok(Expr::call(func, args));
                }
                if name == "pi" {
                    return Ok(Expr::Num(std::f64::consts::PI));
                }
                match (self.lookup)(&name) {
                    Some(i) => Ok(Expr::Var(i)),
                    None => Err(ParseError {
                        column,
                        message: format!("unknown name '{name}'"),
                    }),
                }
            }
            Token::End => self.error("the expression ends too early"),
            Token::Sym(c) => self.error(format!("unexpected '{c}'")),
        }
    }
}

/// Parses `text`, turning names into variable indices with `lookup` (`pi` and the functions
/// are known already).
pub fn parse(text: &str, lookup: &dyn Fn(&str) -> Option<usize>) -> Result<Expr, ParseError> {
    let tokens = lex(text)?;
    if tokens.len() > MAX_TOKENS {
        return Err(ParseError {
            column: tokens[MAX_TOKENS].1,
            message: format!(
                "the expression has {} tokens (numbers, names, operators); at most {MAX_TOKENS} \
                 are taken",
                tokens.len() - 1
            ),
        });
    }
    let mut p = Parser {
        tokens,
        at: 0,
        depth: 0,
        lookup,
    };
    let e = p.sum()?;
    if *p.peek() != Token::End {
        return p.error("unexpected text after the expression");
    }
    Ok(e)
}
