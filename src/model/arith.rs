//! Jason's arithmetic, in one place for the plan compiler's constant folding and for the
//! reasoning cycle.
//!
//! Jason computes on doubles (`NumberTermImpl`, `ArithExpr.ArithmeticOp`): `+`, `-`, `*`,
//! `/` and `**` are IEEE operations, `mod` is Java's `%` on doubles (Rust's `%` on `f64`
//! is the same operation), and `div` is `(int) x / (int) y`: both operands cast to Java
//! `int` (saturating, NaN to 0, as Rust's `as i32`), then an integer division that
//! truncates and wraps on `MIN / -1`. Where Jason would go on with a value that is not a
//! number of the model (`/` or `mod` by zero give infinities and NaN, as does overflow) or
//! throw (`div` by zero raises `ArithmeticException`), the result here is an error. The
//! reasoning cycle does not fail the plan there, as real Jason does neither: it refuses
//! the run (`Note::Beyond`). In Jason 3 the exception of `div` escapes the reasoning cycle
//! (`TransitionSystem.act`/`deliberate` log "*** ERROR in the transition system" and
//! create a new circumstance, dropping every intention and event: recorded in
//! `tests/jason/82-belief-update-errors`).

/// The operators the plan compiler keeps as structures until their operands are bound.
pub const OPERATORS: [&str; 7] = ["+", "-", "*", "/", "div", "mod", "**"];

/// Why an arithmetic expression has no value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArithError {
    /// `div` by zero (Java's `ArithmeticException`).
    DivisionByZero,
    /// An infinite or NaN result (`/` or `mod` by zero, overflow).
    NotFinite,
}

impl std::fmt::Display for ArithError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ArithError::DivisionByZero => "integer division by zero",
            ArithError::NotFinite => "the result is not a finite number",
        })
    }
}

/// `x op y` (or `op x` for unary minus and plus) as Jason computes it; `None` when `op`
/// is not an arithmetic operator of that arity.
pub fn apply(op: &str, args: &[f64]) -> Option<Result<f64, ArithError>> {
    let v = match (op, args) {
        ("-", [x]) => -x,
        ("+", [x]) => *x,
        ("+", [x, y]) => x + y,
        ("-", [x, y]) => x - y,
        ("*", [x, y]) => x * y,
        ("/", [x, y]) => x / y,
        ("mod", [x, y]) => x % y,
        ("div", [x, y]) => {
            let (xi, yi) = (*x as i32, *y as i32);
            if yi == 0 {
                return Some(Err(ArithError::DivisionByZero));
            }
            f64::from(xi.wrapping_div(yi))
        }
        ("**", [x, y]) => x.powf(*y),
        _ => return None,
    };
    Some(if v.is_finite() {
        Ok(v)
    } else {
        Err(ArithError::NotFinite)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ok(op: &str, args: &[f64]) -> f64 {
        apply(op, args).unwrap().unwrap()
    }

    #[test]
    fn operators_compute_as_java_does() {
        assert_eq!(ok("+", &[2.0, 3.0]), 5.0);
        assert_eq!(ok("-", &[2.0, 3.0]), -1.0);
        assert_eq!(ok("-", &[2.0]), -2.0);
        assert_eq!(ok("+", &[2.0]), 2.0);
        assert_eq!(ok("*", &[2.0, 3.0]), 6.0);
        assert_eq!(ok("/", &[7.0, 2.0]), 3.5);
        assert_eq!(ok("div", &[7.0, 2.0]), 3.0);
        assert_eq!(ok("div", &[-7.0, 2.0]), -3.0);
        assert_eq!(ok("div", &[7.9, 2.0]), 3.0);
        assert_eq!(ok("mod", &[7.0, 3.0]), 1.0);
        assert_eq!(ok("mod", &[-7.0, 3.0]), -1.0);
        assert_eq!(ok("mod", &[7.5, 2.0]), 1.5);
        assert_eq!(ok("**", &[2.0, 10.0]), 1024.0);
        // `(int)` saturates: Long.MIN_VALUE becomes Integer.MIN_VALUE, and MIN / -1 wraps.
        assert_eq!(
            ok("div", &[-9223372036854775808.0, -1.0]),
            f64::from(i32::MIN)
        );
        assert_eq!(ok("div", &[1e12, 1.0]), f64::from(i32::MAX));
    }

    #[test]
    fn no_value_is_an_error() {
        assert_eq!(
            apply("div", &[5.0, 0.0]),
            Some(Err(ArithError::DivisionByZero))
        );
        assert_eq!(
            apply("div", &[5.0, 0.5]),
            Some(Err(ArithError::DivisionByZero))
        );
        // Java gives Infinity and NaN here, and goes on with them.
        assert_eq!(apply("/", &[5.0, 0.0]), Some(Err(ArithError::NotFinite)));
        assert_eq!(apply("mod", &[5.0, 0.0]), Some(Err(ArithError::NotFinite)));
        assert_eq!(
            apply("**", &[10.0, 400.0]),
            Some(Err(ArithError::NotFinite))
        );
        assert_eq!(
            apply("*", &[1e300, 1e300]),
            Some(Err(ArithError::NotFinite))
        );
        assert_eq!(apply("max", &[1.0, 2.0]), None);
        assert_eq!(apply("div", &[1.0]), None);
    }
}
