//! How a study's reasons print their figures and comparisons, and a reader
//! that checks them.
//!
//! A reason is a claim too: every comparison it prints must hold for the
//! figures it prints. Figures carry three significant digits
//! ([`figure`]); a comparison prints the quantity, the operator the values
//! call for and the bound ([`vs_upper`], [`vs_lower`]), with more digits
//! only where three would make the two figures equal or reverse their order,
//! so that `a > b` is never printed as `1.00e-3 > 1.00e-3`.
//!
//! [`comparisons`] reads every comparison back out of a text, so that a test
//! can check each one holds. The grammar it accepts:
//!
//! ```text
//! comparison := NUMBER WORD{0,3} OPERATOR WORD{0,3} NUMBER
//! OPERATOR   := "<" | ">" | "<=" | ">="        (a token of its own)
//! NUMBER     := [+-]? digits [. digits] [(e|E) [+-]? digits] | inf | NaN
//! WORD       := a token that starts with a letter ("allowance", "ulps", "E0")
//! ```
//!
//! Tokens are separated by whitespace; a number may carry opening brackets
//! before it and closing brackets or `,;:` after it. Any other token made
//! only of `<`, `>`, `=`, `≤`, `≥` and `≠` (`=<`, `=>`, `<<`, `≤`, ...) is an
//! error, not skipped, and so is an operator without a number within three
//! words on each side; `=` alone (`h = 1e-3`) is not a comparison, and
//! arrows such as `->` are not tokens of their own.

/// `x` to three significant digits: decimal between 0.1 and 1000
/// (`0.137`, `3.90`, `231`), scientific otherwise (`6.97e-2`).
pub fn figure(x: f64) -> String {
    significant(x, 3)
}

/// `x` exactly, as its shortest round-trip digits: plain from `1e-5` to
/// below `1e16` (`0.1`, `7.3`, `100000`), scientific outside (`1e300`,
/// `5e-324`, `1.2594140651547697e19`), never a 300-digit integer. For a
/// value a user typed, which must read back as typed.
pub fn exact(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// An order (an exponent of `h`): two decimals, `2.00`, so that an order
/// near zero reads `0.00` rather than its noise.
pub fn order(p: f64) -> String {
    // a tiny negative estimate prints as 0.00, not -0.00
    format!("{:.2}", if p.abs() < 0.005 { 0.0 } else { p })
}

/// `x` to `digits` significant digits (at least one), in the notation of
/// [`figure`].
pub fn significant(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".to_string();
    }
    let scientific = format!("{x:.prec$e}", prec = digits - 1);
    // the magnitude after rounding (999.6 rounds into the next decade)
    let rounded: f64 = scientific.parse().unwrap_or(x);
    let magnitude = rounded.abs().log10().floor() as i64;
    if (-1..3).contains(&magnitude) && magnitude < digits as i64 {
        let decimals = (digits as i64 - 1 - magnitude) as usize;
        format!("{rounded:.decimals$}")
    } else {
        scientific
    }
}

/// `a` and `b` to three significant digits, or to as many more as it takes
/// for the printed figures to compare as the values do.
pub fn pair(a: f64, b: f64) -> (String, String) {
    pair_from(a, b, 3)
}

/// `a` and `b` to `digits` significant digits, or to as many more as it
/// takes for the printed figures to compare as the values do.
pub fn pair_from(a: f64, b: f64, digits: usize) -> (String, String) {
    for digits in digits.max(1)..=17 {
        let (sa, sb) = (significant(a, digits), significant(b, digits));
        let (pa, pb) = (parse(&sa), parse(&sb));
        if pa.partial_cmp(&pb) == a.partial_cmp(&b) {
            return (sa, sb);
        }
    }
    (format!("{a:e}"), format!("{b:e}"))
}

fn parse(s: &str) -> f64 {
    s.parse().unwrap_or(f64::NAN)
}

/// `a` against the upper bound `b`: `"a > label b"` when `a` exceeds it,
/// `"a <= label b"` otherwise (`label` names the bound: `"allowance"`,
/// `"round-off allowance"`; empty for none).
pub fn vs_upper(a: f64, label: &str, b: f64) -> String {
    let (sa, sb) = pair(a, b);
    let op = if a > b { ">" } else { "<=" };
    join(&sa, op, label, &sb)
}

/// `a` against the lower bound `b`: `"a < label b"` when `a` falls short of
/// it, `"a >= label b"` otherwise.
pub fn vs_lower(a: f64, label: &str, b: f64) -> String {
    let (sa, sb) = pair(a, b);
    let op = if a < b { "<" } else { ">=" };
    join(&sa, op, label, &sb)
}

fn join(a: &str, op: &str, label: &str, b: &str) -> String {
    if label.is_empty() {
        format!("{a} {op} {b}")
    } else {
        format!("{a} {op} {label} {b}")
    }
}

/// A comparison read from a text.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// The number before the operator.
    pub left: f64,
    /// `<`, `>`, `<=` or `>=`.
    pub operator: &'static str,
    /// The number after it.
    pub right: f64,
    /// The words from the left number to the right one, as printed.
    pub text: String,
}

impl Comparison {
    /// The printed figures satisfy the operator (false for a NaN).
    pub fn holds(&self) -> bool {
        match self.operator {
            "<" => self.left < self.right,
            ">" => self.left > self.right,
            "<=" => self.left <= self.right,
            ">=" => self.left >= self.right,
            _ => false,
        }
    }
}

/// Most words between a number and its operator (see the module grammar).
pub const MAX_WORDS: usize = 3;

/// Every comparison in `text`, or why one could not be read (see the
/// module documentation for the grammar).
pub fn comparisons(text: &str) -> Result<Vec<Comparison>, String> {
    let tokens: Vec<&str> = text.split_whitespace().collect();
    let mut found = Vec::new();
    for (i, &token) in tokens.iter().enumerate() {
        let operator = match token {
            "<" => "<",
            ">" => ">",
            "<=" => "<=",
            ">=" => ">=",
            t if t.chars().all(|c| "<>=≤≥≠".contains(c)) && t != "=" => {
                return Err(format!(
                    "`{t}` is not one of the comparisons <, >, <=, >= (in `{}`)",
                    context(&tokens, i)
                ));
            }
            _ => continue,
        };
        let unreadable = |side: &str| {
            format!(
                "no number within {MAX_WORDS} words {side} `{operator}` (in `{}`)",
                context(&tokens, i)
            )
        };
        let left = (1..=MAX_WORDS + 1)
            .map_while(|k| i.checked_sub(k).map(|j| (j, tokens[j])))
            .find_map(|(j, t)| match number(t) {
                Some(x) => Some(Ok((j, x))),
                None if is_word(t) => None,
                None => Some(Err(())),
            });
        let Some(Ok((from, left))) = left else {
            return Err(unreadable("before"));
        };
        let right =
            (i + 1..tokens.len())
                .take(MAX_WORDS + 1)
                .find_map(|j| match number(tokens[j]) {
                    Some(x) => Some(Ok((j, x))),
                    None if is_word(tokens[j]) => None,
                    None => Some(Err(())),
                });
        let Some(Ok((to, right))) = right else {
            return Err(unreadable("after"));
        };
        found.push(Comparison {
            left,
            operator,
            right,
            text: tokens[from..=to].join(" "),
        });
    }
    Ok(found)
}

fn context(tokens: &[&str], i: usize) -> String {
    tokens[i.saturating_sub(6)..(i + 7).min(tokens.len())].join(" ")
}

/// A word: a token that starts with a letter.
fn is_word(token: &str) -> bool {
    token.chars().next().is_some_and(char::is_alphabetic)
}

/// The number a token prints, with brackets before it and brackets or
/// `,;:` after it allowed.
fn number(token: &str) -> Option<f64> {
    let core = token
        .trim_start_matches(['(', '['])
        .trim_end_matches([')', ']', ',', ';', ':']);
    match core {
        "inf" | "+inf" => return Some(f64::INFINITY),
        "-inf" => return Some(f64::NEG_INFINITY),
        "NaN" => return Some(f64::NAN),
        _ => {}
    }
    let body = core.strip_prefix(['+', '-']).unwrap_or(core);
    let (mantissa, exponent) = match body.split_once(['e', 'E']) {
        Some((m, e)) => (m, Some(e)),
        None => (body, None),
    };
    let digits = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_digit());
    let mantissa_ok = match mantissa.split_once('.') {
        Some((a, b)) => {
            (digits(a) || a.is_empty())
                && (digits(b) || b.is_empty())
                && !(a.is_empty() && b.is_empty())
        }
        None => digits(mantissa),
    };
    let exponent_ok = exponent.is_none_or(|e| digits(e.strip_prefix(['+', '-']).unwrap_or(e)));
    (mantissa_ok && exponent_ok)
        .then(|| core.parse().ok())
        .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_have_three_significant_digits() {
        assert_eq!(figure(0.069_734), "6.97e-2");
        assert_eq!(figure(3.899), "3.90");
        assert_eq!(figure(0.137), "0.137");
        assert_eq!(figure(230.89), "231");
        assert_eq!(figure(999.7), "1.00e3");
        assert_eq!(figure(1e-12), "1.00e-12");
        assert_eq!(figure(0.0), "0");
        assert_eq!(figure(99.96), "100");
        assert_eq!(significant(231.0, 2), "2.3e2");
        assert_eq!(significant(0.638, 2), "0.64");
        assert_eq!(order(-0.001), "0.00");
    }

    #[test]
    fn a_comparison_gets_the_digits_that_keep_it_true() {
        // three digits would print 1.00e-3 > 1.00e-3
        assert_eq!(
            vs_upper(1.0004e-3, "allowance", 1.0001e-3),
            "1.0004e-3 > allowance 1.0001e-3"
        );
        assert_eq!(vs_upper(2.0, "", 3.0), "2.00 <= 3.00");
        assert_eq!(vs_lower(3.899, "", 3.9), "3.899 < 3.900");
        assert_eq!(vs_lower(4.0, "claim", 4.0), "4.00 >= claim 4.00");
    }

    #[test]
    fn the_reader_finds_every_comparison_and_checks_it() {
        let text = "max |J^T Omega J - Omega| = 6.97e-2 > allowance 3.10e-12 at h = 2.09e-2; \
                    return error 2.79e16 ulps > allowance 4.29e4 ulps, (g = 1.00) \
                    and 1.2e-9 <= round-off allowance 2.2e-9: h -> 0";
        let found = comparisons(text).expect("readable");
        assert_eq!(found.len(), 3, "{found:?}");
        assert_eq!(
            (found[0].left, found[0].operator, found[0].right),
            (6.97e-2, ">", 3.10e-12)
        );
        assert_eq!((found[1].left, found[1].right), (2.79e16, 4.29e4));
        assert_eq!(
            (found[2].left, found[2].operator, found[2].right),
            (1.2e-9, "<=", 2.2e-9)
        );
        assert!(found.iter().all(Comparison::holds));
        // a reversed operator is read, and does not hold
        let reversed = comparisons("residual 6.97e-2 < allowance 3.10e-12").unwrap();
        assert!(!reversed[0].holds());
        // the defect the user found: two maxima of different quantities
        assert!(!comparisons("residual 6.97e-2 > 2.70e0").unwrap()[0].holds());
    }

    #[test]
    fn an_unreadable_comparison_is_an_error_not_skipped() {
        for text in [
            "the error exceeds => 3e-4",
            "1.0 ≤ 2.0",
            "a > b",
            "error 1e-3 > the allowance of this scene 2e-3",
            "[1.0, 2.0] > order",
            "1e-3 > |J| 2e-3",
        ] {
            assert!(comparisons(text).is_err(), "{text}");
        }
        assert_eq!(comparisons("h = 1e-3, h -> 0, x=>y").unwrap(), vec![]);
    }
}
