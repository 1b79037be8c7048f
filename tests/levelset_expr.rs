//! The expression parser: values, precedence, error messages with columns, and fuzzing.

use anisomesh::levelset::{Expr, Shape};
use anisomesh::{DVec2, DVec3};
use proptest::prelude::*;

fn eval(src: &str, x: f64, y: f64) -> f64 {
    Expr::parse(src)
        .unwrap_or_else(|e| panic!("{src}: {e}"))
        .eval(DVec2::new(x, y))
}

#[test]
fn values_and_precedence() {
    let (x, y) = (0.3, -1.7);
    let cases: &[(&str, f64)] = &[
        ("x^2 + y^2 - 0.25", x * x + y * y - 0.25),
        ("1e-3", 1e-3),
        ("2.5E+2 + .5", 250.5),
        ("-x^2", -(x * x)),
        ("2^3^2", 512.0),
        ("2^-1", 0.5),
        ("-2^2", -4.0),
        ("(1 + 2) * 3 - 4 / 2", 7.0),
        ("1 - 2 - 3", -4.0),
        ("8 / 4 / 2", 1.0),
        ("--x", x),
        ("+y", y),
        ("pi", std::f64::consts::PI),
        ("sqrt(x*x + y*y) - 0.5", x.hypot(y) - 0.5),
        ("abs(y) + exp(0) + log(1)", y.abs() + 1.0),
        ("sin(pi/2) + cos(0) + tan(0)", 2.0),
        ("min(x, y) + max(x, y)", x + y),
        ("atan2(y, x)", y.atan2(x)),
        (
            "max(abs(x) - 0.2, abs(y) - 1)",
            (x.abs() - 0.2).max(y.abs() - 1.0),
        ),
        ("x*y*2", x * y * 2.0),
    ];
    for &(src, want) in cases {
        let got = eval(src, x, y);
        assert!((got - want).abs() < 1e-14, "{src}: {got} vs {want}");
    }
    let e: Expr = "x - y".parse().unwrap();
    assert_eq!(e.distance(DVec2::new(2.0, 1.0)), 1.0);
    assert_eq!(e.name(), "x - y");
}

#[test]
fn errors_name_the_column_and_the_problem() {
    let cases: &[(&str, &str)] = &[
        ("x + (y))", "unexpected ')' at column 8"),
        (
            "(x + y",
            "expected ')' to close '(' at column 1, found end of input at column 7",
        ),
        ("x + ", "unexpected end of input at column 5"),
        ("", "empty expression at column 1"),
        ("x $ y", "unexpected character '$' at column 3"),
        ("foo(x)", "unknown name 'foo'"),
        (
            "min(x)",
            "function 'min' takes 2 argument(s), got 1 at column 1",
        ),
        ("sqrt(x, y)", "function 'sqrt' takes 1 argument(s), got 2"),
        (
            "sqrt x",
            "expected '(' after function 'sqrt', found 'x' at column 6",
        ),
        (
            "1e",
            "malformed number (exponent without digits) at column 1",
        ),
        ("1.2.3", "malformed number '1.2.3' at column 1"),
        ("1e999", "out of range"),
        ("2 * * 3", "unexpected '*' at column 5"),
    ];
    for &(src, want) in cases {
        let err = Expr::parse(src).unwrap_err().to_string();
        assert!(err.contains(want), "{src:?}: got {err:?}, want {want:?}");
    }
    // "x y": the second name is the unexpected token.
    let err = Expr::parse("x y").unwrap_err().to_string();
    assert!(err.contains("unexpected 'y' at column 3"), "{err}");
    // Deep nesting is an error, not a stack overflow.
    let deep = format!("{}x{}", "(".repeat(100_000), ")".repeat(100_000));
    assert!(Expr::parse(&deep)
        .unwrap_err()
        .to_string()
        .contains("nesting"));
    let minus = format!("{}x", "-".repeat(100_000));
    assert!(Expr::parse(&minus).is_err());
    // A right-associative power chain nests: 150 levels are fine, 1000 are refused.
    let chain = vec!["x"; 150].join("^");
    assert_eq!(eval(&chain, 1.0, 0.0), 1.0);
    assert!(Expr::parse(&vec!["x"; 1000].join("^")).is_err());
    // Long flat expressions (deep evaluation stack, no nesting) are fine.
    let sum = vec!["1"; 10_000].join("+");
    assert_eq!(eval(&sum, 0.0, 0.0), 10_000.0);
}

/// A random expression tree printed with full parentheses, and its reference value.
fn arb_expr() -> impl Strategy<Value = (String, f64)> {
    let leaf = prop_oneof![
        (-100.0f64..100.0).prop_map(|v| (format!("({v:e})"), v)),
        Just(("x".to_string(), 0.7)),
        Just(("y".to_string(), -1.3)),
    ];
    leaf.prop_recursive(6, 64, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone())
                .prop_map(|((a, va), (b, vb))| (format!("({a}+{b})"), va + vb)),
            (inner.clone(), inner.clone())
                .prop_map(|((a, va), (b, vb))| (format!("({a} - {b})"), va - vb)),
            (inner.clone(), inner.clone())
                .prop_map(|((a, va), (b, vb))| (format!("({a}*{b})"), va * vb)),
            (inner.clone(), inner.clone())
                .prop_map(|((a, va), (b, vb))| (format!("max({a},{b})"), va.max(vb))),
            inner.clone().prop_map(|(a, va)| (format!("-{a}"), -va)),
            inner.prop_map(|(a, va)| (format!("abs({a})"), va.abs())),
        ]
    })
}

proptest! {
    #[test]
    fn never_panics_on_random_text(s in "\\PC{0,40}") {
        let _ = Expr::parse(&s).map(|e| e.eval(DVec2::new(0.5, -0.5)));
    }

    #[test]
    fn never_panics_on_random_tokens(
        toks in proptest::collection::vec(
            prop_oneof![
                Just("x"), Just("y"), Just("pi"), Just("1.5"), Just("2e-3"), Just("+"), Just("-"),
                Just("*"), Just("/"), Just("^"), Just("("), Just(")"), Just(","), Just("sqrt"),
                Just("min"), Just("atan2"), Just("e"), Just("."), Just(" "),
            ],
            0..30,
        )
    ) {
        let s: String = toks.concat();
        if let Ok(e) = Expr::parse(&s) {
            let _ = e.eval(DVec2::new(0.25, 2.0));
        } else {
            let msg = Expr::parse(&s).unwrap_err().to_string();
            prop_assert!(msg.contains("column"), "{}", msg);
        }
    }

    #[test]
    fn parsed_trees_evaluate_like_the_reference((src, want) in arb_expr()) {
        let got = Expr::parse(&src).unwrap().eval(DVec2::new(0.7, -1.3));
        // Same operations in the same order: bit-identical (or both NaN).
        prop_assert!(got == want || (got.is_nan() && want.is_nan()), "{} -> {} vs {}", src, got, want);
    }
}

#[test]
fn z_and_t_only_where_asked_for() {
    use anisomesh::levelset::Variables;
    // In plain 2D parsing, z and t are unknown names and the message lists the valid ones.
    let err = Expr::parse("x + z").unwrap_err().to_string();
    assert!(
        err.contains("unknown name 'z'") && err.contains("x, y, pi"),
        "{err}"
    );
    assert!(Expr::parse("t * x").is_err());
    let e3 = Expr::parse_with("x^2 + y^2 + z^2 - 0.25", Variables::XYZ).unwrap();
    assert!((e3.eval3(DVec3::new(0.5, 0.0, 0.0))).abs() < 1e-15);
    assert!((e3.eval3(DVec3::new(0.0, 0.0, 1.0)) - 0.75).abs() < 1e-15);
    let et = Expr::parse_with("sin(pi*x) * cos(pi*t/8)", Variables::XYT).unwrap();
    assert!((et.eval_t(DVec2::new(0.5, 0.0), 8.0) + 1.0).abs() < 1e-15);
    let err = Expr::parse_with("z", Variables::XYT)
        .unwrap_err()
        .to_string();
    assert!(err.contains("x, y, t"), "{err}");
    let all = Expr::parse_with("x + 2*y + 4*z + 8*t", Variables::XYZT).unwrap();
    assert_eq!(all.eval_vars([1.0, 1.0, 1.0, 1.0]), 15.0);
}
