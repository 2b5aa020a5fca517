//! The pure arithmetic functions (`jason.functions`, the `math` library and `.length`),
//! evaluated inside expressions by [`function`], with Java's rounding and list conventions.

use super::{elements, jason_text, utf16_len, FUNCTIONS};
use crate::model::arith::ArithError;
use crate::model::Term;

/// Evaluates the pure arithmetic function `name` on `args` (already evaluated terms).
///
/// Returns `None` when `name` with that arity is not in [`FUNCTIONS`] (Jason's
/// `FunctionRegister.getFunction` finds no function). Otherwise the number, or why there is
/// none: an argument not ground (Jason leaves the term unevaluated), an argument of the
/// wrong type (Jason's `JasonException`), or a result that is not a finite number (as in
/// [`crate::model::arith`]: `math.sqrt(-1)`, `math.log(0)`, `math.average([])`).
pub fn function(name: &str, args: &[Term]) -> Option<Result<Term, String>> {
    if !FUNCTIONS
        .iter()
        .any(|&(f, arity)| f == name && arity == args.len())
    {
        return None;
    }
    if let Some(t) = args.iter().find(|t| !t.is_ground()) {
        return Some(Err(format!("{name}: the argument {t} is not ground")));
    }
    Some(evaluate(name, args).and_then(|v| {
        if v.is_finite() {
            Ok(Term::num(v))
        } else {
            Err(format!("{name}: {}", ArithError::NotFinite))
        }
    }))
}

fn number_arg(name: &str, t: &Term) -> Result<f64, String> {
    t.as_f64()
        .ok_or_else(|| format!("{name}: the argument '{}' is not numeric", jason_text(t)))
}

fn list_arg(name: &str, t: &Term) -> Result<Vec<Term>, String> {
    elements(t).ok_or_else(|| format!("{name} is not implemented for type '{}'", jason_text(t)))
}

/// The numbers among a list's elements (the `math` list functions skip the others).
fn numbers(name: &str, t: &Term) -> Result<Vec<f64>, String> {
    Ok(list_arg(name, t)?.iter().filter_map(Term::as_f64).collect())
}

/// Java's `Math.round`: `floor(x + 1/2)` computed exactly (so `0.49999999999999994` rounds
/// to 0 and `-2.5` to -2), saturating at the `long` range, NaN to 0.
fn java_round(x: f64) -> f64 {
    if x.is_nan() {
        return 0.0;
    }
    let f = x.floor();
    // `x - f` is exact: for |x| >= 1 by Sterbenz's lemma, for smaller |x| the result's
    // spacing is finer than x's near 1/2.
    let r = if x - f >= 0.5 { f + 1.0 } else { f };
    r.clamp(i64::MIN as f64, i64::MAX as f64)
}

/// The function's value; `name` and the arity are known to be in [`FUNCTIONS`].
fn evaluate(name: &str, args: &[Term]) -> Result<f64, String> {
    let unary = |f: fn(f64) -> f64| number_arg(name, &args[0]).map(f);
    match name {
        "math.abs" => unary(f64::abs),
        "math.acos" => unary(f64::acos),
        "math.asin" => unary(f64::asin),
        "math.atan" => unary(f64::atan),
        "math.ceil" => unary(f64::ceil),
        "math.cos" => unary(f64::cos),
        "math.floor" => unary(f64::floor),
        "math.log" => unary(f64::ln),
        "math.round" => unary(java_round),
        "math.sin" => unary(f64::sin),
        "math.sqrt" => unary(f64::sqrt),
        "math.tan" => unary(f64::tan),
        "math.e" => Ok(std::f64::consts::E),
        "math.pi" => Ok(std::f64::consts::PI),
        ".length" => match &args[0] {
            Term::Str(x) => Ok(utf16_len(x) as f64),
            t => elements(t).map(|e| e.len() as f64).ok_or_else(|| {
                format!("the argument '{}' is not a list or a string", jason_text(t))
            }),
        },
        "math.max" | "math.min" => {
            let is_max = name == "math.max";
            if let Some(x) = args[0].as_f64() {
                // `Max.java` reads the second argument whenever the first is a number.
                let second = args.get(1).ok_or_else(|| format!("{name}: one number"))?;
                let y = number_arg(name, second)?;
                return Ok(if is_max { x.max(y) } else { x.min(y) });
            }
            // Lists: Jason starts from `Double.MIN_VALUE` (the least positive double, so
            // `math.max([-3])` is 4.9E-324) and `Double.MAX_VALUE`.
            let start = if is_max { f64::from_bits(1) } else { f64::MAX };
            Ok(numbers(name, &args[0])?.into_iter().fold(start, |acc, n| {
                if (is_max && n > acc) || (!is_max && n < acc) {
                    n
                } else {
                    acc
                }
            }))
        }
        "math.sum" => Ok(numbers(name, &args[0])?.iter().sum()),
        "math.average" => {
            // `Average.java`: 0/0 for no numbers, which is not a finite result.
            let ns = numbers(name, &args[0])?;
            Ok(ns.iter().sum::<f64>() / ns.len() as f64)
        }
        "math.mean" => {
            let ns = numbers(name, &args[0])?;
            if ns.is_empty() {
                return Err(format!("{name}: no numbers in '{}'", jason_text(&args[0])));
            }
            Ok(ns.iter().sum::<f64>() / ns.len() as f64)
        }
        "math.median" => {
            let l = list_arg(name, &args[0])?;
            let mut ns: Vec<f64> = l.iter().filter_map(Term::as_f64).collect();
            if ns.len() != l.len() || ns.is_empty() {
                return Err(format!(
                    "{name} needs a non-empty list of numbers, not '{}'",
                    jason_text(&args[0])
                ));
            }
            ns.sort_by(f64::total_cmp);
            let n = ns.len();
            Ok(if n.is_multiple_of(2) {
                (ns[n / 2 - 1] + ns[n / 2]) / 2.0
            } else {
                ns[n / 2]
            })
        }
        "math.std_dev" => {
            // `StdDev.java`: the sample deviation, NaN (not finite) for fewer than two numbers.
            let ns = numbers(name, &args[0])?;
            let n = ns.len() as f64;
            let mean = ns.iter().sum::<f64>() / n;
            let squares: f64 = ns.iter().map(|x| (x - mean) * (x - mean)).sum();
            Ok((squares / (n - 1.0)).sqrt())
        }
        _ => unreachable!("{name} is in FUNCTIONS"),
    }
}
