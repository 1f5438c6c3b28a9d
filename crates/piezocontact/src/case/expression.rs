//! Quantities of a case file that may vary in space: a number, or an expression of the
//! position x, y, z (in the case's length unit), parsed once with evalexpr and evaluated where
//! the problem needs it (a traction at the facets' quadrature points, a prescribed
//! displacement at the nodes). evalexpr writes powers `x^2` and functions `math::sin(x)`;
//! integer literals are read as reals here, so that `1/2` is 0.5.

use crate::error::{Error, Result};
use crate::problem::{ScalarField, constant_scalar};
use evalexpr::{
    ContextWithMutableVariables, DefaultNumericTypes, HashMapContext, Node, Value,
    build_operator_tree,
};
use serde::Deserialize;
use std::sync::Arc;

/// A number, or an expression of x, y, z.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum Quantity {
    /// A constant.
    Number(f64),
    /// An expression of the position, e.g. `"-2.0e10 * y"`.
    Expression(String),
}

/// The names of the coordinates, in order.
const AXES: [&str; 3] = ["x", "y", "z"];

impl Quantity {
    /// The quantity as the case file writes it: the number, or the expression.
    pub fn text(&self) -> String {
        match self {
            Self::Number(v) => v.to_string(),
            Self::Expression(text) => format!("\"{text}\""),
        }
    }

    /// The field x ↦ value of this quantity in a d-dimensional mesh, checked at `points`
    /// (a finite value at each); `key` names it in errors.
    pub fn field(&self, key: &str, dim: usize, points: &[&[f64]]) -> Result<ScalarField> {
        let text = match self {
            Self::Number(v) if v.is_finite() => return Ok(constant_scalar(*v)),
            Self::Number(v) => return Err(invalid(key, &format!("{v} is not a finite number"))),
            Self::Expression(text) => text,
        };
        let tree = build_operator_tree::<DefaultNumericTypes>(&reals(text))
            .map_err(|e| invalid(key, &format!("\"{text}\" does not parse: {e}")))?;
        if let Some(name) = tree.iter_variable_identifiers().find(|v| !AXES[..dim].contains(v)) {
            let why = format!(
                "\"{text}\" names '{name}': an expression may name the coordinates {:?} of the {dim}D mesh only",
                &AXES[..dim]
            );
            return Err(invalid(key, &why));
        }
        let tree = Arc::new(tree);
        for point in points {
            match evaluate(&tree, point) {
                Ok(v) if v.is_finite() => {}
                Ok(v) => {
                    return Err(invalid(key, &format!("\"{text}\" is {v} at {point:?}")));
                }
                Err(e) => return Err(invalid(key, &format!("\"{text}\" at {point:?}: {e}"))),
            }
        }
        Ok(Arc::new(move |x: &[f64]| evaluate(&tree, x).unwrap_or(f64::NAN)))
    }
}

/// The error of an invalid quantity at `key`.
fn invalid(key: &str, why: &str) -> Error {
    Error::Input(format!("{key}: {why}"))
}

/// The value of `tree` at the position `x`.
fn evaluate(tree: &Node<DefaultNumericTypes>, x: &[f64]) -> std::result::Result<f64, String> {
    let mut context = HashMapContext::<DefaultNumericTypes>::new();
    for (name, value) in AXES.iter().zip(x) {
        context
            .set_value(name.to_string(), Value::from_float(*value))
            .map_err(|e| e.to_string())?;
    }
    tree.eval_number_with_context(&context).map_err(|e| e.to_string())
}

/// `text` with each integer literal written as a real (`2` → `2.0`), so that evalexpr does
/// not divide integers (`1/2` would be 0); literals with a point or an exponent (`2.5`,
/// `2.0e-1`, `1E3`) and digits inside names (`x2`) are left alone.
fn reals(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len() + 8);
    let mut k = 0;
    while k < chars.len() {
        let in_name = k > 0 && (chars[k - 1].is_alphanumeric() || chars[k - 1] == '_');
        if !chars[k].is_ascii_digit() || in_name {
            out.push(chars[k]);
            k += 1;
            continue;
        }
        let end = literal_end(&chars, k);
        let literal: String = chars[k..end].iter().collect();
        let real = literal.contains(['.', 'e', 'E']);
        out += &literal;
        if !real {
            out += ".0";
        }
        k = end;
    }
    out
}

/// The end of the numeric literal that starts at `start`: digits, a point and digits, an
/// exponent (e or E, a sign, digits).
fn literal_end(chars: &[char], start: usize) -> usize {
    let digits = |mut k: usize| {
        while k < chars.len() && chars[k].is_ascii_digit() {
            k += 1;
        }
        k
    };
    let mut k = digits(start);
    if k < chars.len() && chars[k] == '.' {
        k = digits(k + 1);
    }
    if k < chars.len() && matches!(chars[k], 'e' | 'E') {
        let sign = usize::from(k + 1 < chars.len() && matches!(chars[k + 1], '+' | '-'));
        let exponent = digits(k + 1 + sign);
        if exponent > k + 1 + sign {
            k = exponent;
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(q: &str, dim: usize, x: &[f64]) -> f64 {
        Quantity::Expression(q.into()).field("key", dim, &[]).unwrap()(x)
    }

    /// Expressions read as the formulas they write, with real arithmetic, scientific
    /// notation and functions; numbers are constants.
    #[test]
    fn expressions_are_functions_of_the_position() {
        assert_eq!(at("-2.0e10 * y", 3, &[1.0, 0.5, 2.0]), -1.0e10);
        assert_eq!(at("1/2 * x + 3", 2, &[4.0, 0.0]), 5.0);
        assert_eq!(at("x^2 + y^2 + z^2", 3, &[1.0, 2.0, 2.0]), 9.0);
        assert!((at("math::sin(x)", 2, &[0.5, 0.0]) - 0.5f64.sin()).abs() < 1e-15);
        assert_eq!(at("2e3", 2, &[0.0, 0.0]), 2000.0);
        let constant = Quantity::Number(3.5).field("key", 2, &[]).unwrap();
        assert_eq!(constant(&[1.0, 2.0]), 3.5);
        assert_eq!(reals("10*x2 + 3.5 - 1e4 + 7"), "10.0*x2 + 3.5 - 1e4 + 7.0");
        assert_eq!(reals("-2.0e-1 * (y - 1/2) + 3E+2"), "-2.0e-1 * (y - 1.0/2.0) + 3E+2");
        assert_eq!(at("-2.0e-1 * (y - 1/2)", 2, &[0.0, 1.5]), -0.2);
    }

    /// A syntax error, an unknown variable, a value that is not finite at a point and a
    /// non-finite number are errors naming the key and what is wrong.
    #[test]
    fn bad_expressions_are_errors_naming_the_key() {
        let error = |q: Quantity, dim: usize, points: &[&[f64]]| {
            q.field("boundary.traction.f2", dim, points).err().unwrap().to_string()
        };
        let e = error(Quantity::Expression("2 * (x +".into()), 2, &[]);
        assert!(e.starts_with("boundary.traction.f2: \"2 * (x +\" does not parse"), "{e}");
        let e = error(Quantity::Expression("2 * z".into()), 2, &[]);
        assert!(e.contains("names 'z'") && e.contains("[\"x\", \"y\"]"), "{e}");
        let e = error(Quantity::Expression("1 / x".into()), 2, &[&[0.0, 1.0]]);
        assert!(e.contains("is inf at [0.0, 1.0]"), "{e}");
        let e = error(Quantity::Expression("math::nope(x)".into()), 2, &[&[0.0, 1.0]]);
        assert!(e.contains("at [0.0, 1.0]"), "{e}");
        let e = error(Quantity::Number(f64::NAN), 2, &[]);
        assert!(e.contains("NaN is not a finite number"), "{e}");
    }
}
