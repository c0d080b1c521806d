//! Derived quantities of a campaign: arithmetic expressions over the factor
//! names (`+ - * / ^`, unary minus, parentheses, numbers such as `2.5e-3`).
//!
//! Hand-written (a recursive-descent parser of ~150 lines) rather than a
//! crate: the grammar is five operators, the workspace takes no new
//! dependency for it, and the errors can name the campaign key and the
//! unknown name the way the rest of bumpsim does.
//!
//! ```
//! use bumpsim_campaign::expr::Expr;
//! let e = Expr::parse("2 * (m1 + m2) ^ 2 / 4").unwrap();
//! assert_eq!(e.names(), vec!["m1", "m2"]);
//! let value = e.eval(&|n: &str| Some(if n == "m1" { 1.0 } else { 3.0 })).unwrap();
//! assert_eq!(value, 8.0);
//! ```

/// A parsed expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A number.
    Number(f64),
    /// A name (a factor or an earlier derived quantity).
    Name(String),
    /// Unary minus.
    Negate(Box<Expr>),
    /// A binary operation: operator (`+ - * / ^`) and operands.
    Binary(char, Box<Expr>, Box<Expr>),
}

/// Why an expression does not parse or evaluate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExprError {
    /// A syntax error at a character position.
    #[error("at character {position}: {message}")]
    Syntax {
        /// 1-based position.
        position: usize,
        /// What is wrong.
        message: String,
    },
    /// A name with no value.
    #[error("unknown name '{name}'")]
    Unknown {
        /// The name.
        name: String,
    },
    /// A result that is not a finite number (division by zero, overflow).
    #[error("the value is not finite ({value})")]
    NotFinite {
        /// The value.
        value: f64,
    },
}

struct Parser<'a> {
    chars: Vec<(usize, char)>,
    at: usize,
    text: &'a str,
    /// Nesting of parentheses and unary minus (bounded: no stack overflow).
    depth: usize,
}

/// Deepest nesting of parentheses and signs an expression may have.
pub const MAX_DEPTH: usize = 64;

impl Expr {
    /// Parses `text`.
    pub fn parse(text: &str) -> Result<Expr, ExprError> {
        let mut parser = Parser {
            chars: text.char_indices().collect(),
            at: 0,
            text,
            depth: 0,
        };
        let expr = parser.sum()?;
        match parser.peek() {
            None => Ok(expr),
            Some(c) => Err(parser.error(&format!("unexpected '{c}'"))),
        }
    }

    /// The names used, each once, in order of appearance.
    pub fn names(&self) -> Vec<&str> {
        let mut names = Vec::new();
        self.collect_names(&mut names);
        names
    }

    fn collect_names<'a>(&'a self, names: &mut Vec<&'a str>) {
        match self {
            Expr::Number(_) => {}
            Expr::Name(n) if !names.contains(&n.as_str()) => names.push(n),
            Expr::Name(_) => {}
            Expr::Negate(e) => e.collect_names(names),
            Expr::Binary(_, a, b) => {
                a.collect_names(names);
                b.collect_names(names);
            }
        }
    }

    /// Evaluates with the values `lookup` gives for names.
    pub fn eval(&self, lookup: &dyn Fn(&str) -> Option<f64>) -> Result<f64, ExprError> {
        let value = match self {
            Expr::Number(v) => *v,
            Expr::Name(n) => lookup(n).ok_or_else(|| ExprError::Unknown { name: n.clone() })?,
            Expr::Negate(e) => -e.eval(lookup)?,
            Expr::Binary(op, a, b) => apply(*op, a.eval(lookup)?, b.eval(lookup)?),
        };
        match value.is_finite() {
            true => Ok(value),
            false => Err(ExprError::NotFinite { value }),
        }
    }
}

fn apply(op: char, a: f64, b: f64) -> f64 {
    match op {
        '+' => a + b,
        '-' => a - b,
        '*' => a * b,
        '/' => a / b,
        _ => a.powf(b),
    }
}

impl Parser<'_> {
    /// The next character after white space.
    fn peek(&mut self) -> Option<char> {
        while self.raw().is_some_and(char::is_whitespace) {
            self.at += 1;
        }
        self.raw()
    }

    /// The next character as it is.
    fn raw(&self) -> Option<char> {
        self.chars.get(self.at).map(|&(_, c)| c)
    }

    fn error(&self, message: &str) -> ExprError {
        let position = self
            .chars
            .get(self.at)
            .map_or(self.text.chars().count(), |&(i, _)| {
                self.text[..i].chars().count()
            })
            + 1;
        ExprError::Syntax {
            position,
            message: message.into(),
        }
    }

    /// sum := product (('+' | '-') product)*
    fn sum(&mut self) -> Result<Expr, ExprError> {
        let mut left = self.product()?;
        while let Some(op @ ('+' | '-')) = self.peek() {
            self.at += 1;
            left = Expr::Binary(op, Box::new(left), Box::new(self.product()?));
        }
        Ok(left)
    }

    /// product := unary (('*' | '/') unary)*
    fn product(&mut self) -> Result<Expr, ExprError> {
        let mut left = self.unary()?;
        while let Some(op @ ('*' | '/')) = self.peek() {
            self.at += 1;
            left = Expr::Binary(op, Box::new(left), Box::new(self.unary()?));
        }
        Ok(left)
    }

    /// unary := '-' unary | power
    fn unary(&mut self) -> Result<Expr, ExprError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.error(&format!("nested deeper than {MAX_DEPTH}")));
        }
        let result = match self.peek() {
            Some('-') => {
                self.at += 1;
                self.unary().map(|e| Expr::Negate(Box::new(e)))
            }
            _ => self.power(),
        };
        self.depth -= 1;
        result
    }

    /// power := atom ('^' unary)?   (right-associative, binds tighter than unary minus on its left)
    fn power(&mut self) -> Result<Expr, ExprError> {
        let base = self.atom()?;
        if self.peek() == Some('^') {
            self.at += 1;
            return Ok(Expr::Binary('^', Box::new(base), Box::new(self.unary()?)));
        }
        Ok(base)
    }

    /// atom := number | name | '(' sum ')'
    fn atom(&mut self) -> Result<Expr, ExprError> {
        match self.peek() {
            Some('(') => {
                self.at += 1;
                let inner = self.sum()?;
                if self.peek() != Some(')') {
                    return Err(self.error("expected ')'"));
                }
                self.at += 1;
                Ok(inner)
            }
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_alphabetic() || c == '_' => Ok(Expr::Name(self.word())),
            Some(c) => Err(self.error(&format!("unexpected '{c}'"))),
            None => Err(self.error("unexpected end of the expression")),
        }
    }

    fn word(&mut self) -> String {
        let mut word = String::new();
        while let Some(c) = self.raw().filter(|c| c.is_alphanumeric() || *c == '_') {
            word.push(c);
            self.at += 1;
        }
        word
    }

    fn number(&mut self) -> Result<Expr, ExprError> {
        let start = self.at;
        let mut text = String::new();
        while let Some(c) = self.raw() {
            let exponent_sign = (c == '+' || c == '-') && text.ends_with(['e', 'E']);
            if !(c.is_ascii_digit() || c == '.' || c == 'e' || c == 'E' || exponent_sign) {
                break;
            }
            text.push(c);
            self.at += 1;
        }
        text.parse().map(Expr::Number).map_err(|_| {
            self.at = start;
            self.error(&format!("'{text}' is not a number"))
        })
    }
}

/// Whether `name` is a plain identifier as an expression reads one
/// (letters, digits, `_`; not starting with a digit): the rule of factor,
/// derived quantity and response names.
pub fn is_name(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_alphabetic() || c == '_')
        && chars.all(|c| c.is_alphanumeric() || c == '_')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(text: &str) -> f64 {
        Expr::parse(text).unwrap().eval(&|_| Some(2.0)).unwrap()
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(value("1 + 2 * 3"), 7.0);
        assert_eq!(value("(1 + 2) * 3"), 9.0);
        assert_eq!(value("2 ^ 3 ^ 2"), 512.0);
        assert_eq!(value("-2 ^ 2"), -4.0);
        assert_eq!(value("8 / 2 / 2"), 2.0);
        assert_eq!(value("1.5e3 - 1e-3 * 1000"), 1499.0);
        assert_eq!(value("x * 1e+2"), 200.0);
    }

    #[test]
    fn errors_name_the_place() {
        let e = Expr::parse("1 + * 2").unwrap_err();
        assert_eq!(e.to_string(), "at character 5: unexpected '*'");
        assert!(Expr::parse("(1 + 2").is_err());
        assert!(Expr::parse("1 2").is_err());
        assert!(Expr::parse("").is_err());
        let deep = format!("{}1{}", "(".repeat(100_000), ")".repeat(100_000));
        assert!(
            Expr::parse(&deep)
                .unwrap_err()
                .to_string()
                .contains("nested deeper")
        );
        assert!(Expr::parse(&"-".repeat(100_000)).is_err());
        let unknown = Expr::parse("a + 1").unwrap().eval(&|_| None).unwrap_err();
        assert_eq!(unknown, ExprError::Unknown { name: "a".into() });
        let zero = Expr::parse("1 / (a - a)").unwrap().eval(&|_| Some(1.0));
        assert!(matches!(zero, Err(ExprError::NotFinite { .. })));
    }
}
