//! The reader's tests: the issue's Duffing file as written, and each mistake's message.

use super::parse_text;

const DUFFING: &str = r#"
name = "duffing"                     # used in reports
description = "x'' = -a x - b x^3 - c x'"

[parameters]                         # learnable; start is the initial value
a = { start = 1.0, positive = true }
b = { start = 0.1 }
c = { start = 0.1, min = 0.0 }

[state]                              # d/dt of each state variable, from state, parameters, t
x = "v"
v = "-a*x - b*x^3 - c*v"

[observed]
latent = ["x"]                       # what each latent coordinate measures, up to an affine map

[initial]                            # for gen: ranges the initial state is drawn from
x = [0.5, 1.0]
v = [-1.0, 1.0]
"#;

#[test]
fn the_issues_duffing_file_reads_as_written() {
    let f = parse_text(DUFFING).unwrap();
    assert_eq!(f.name, "duffing");
    assert_eq!(f.states, ["x", "v"]);
    assert_eq!(f.observed, [0]);
    assert_eq!(f.parameters[0].min, Some(0.0));
    assert_eq!(f.parameters[2].min, Some(0.0));
    assert_eq!(f.parameters[1].min, None);
    assert_eq!(f.initial[1], Some((-1.0, 1.0)));
    let vars = [0.5, 0.2, 2.0, 1.0, 0.1, 0.0];
    assert!((f.equations[1].eval(&vars) - (-1.0 - 0.125 - 0.02)).abs() < 1e-12);
}

#[test]
fn each_mistake_names_the_key_and_the_problem() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "v = \"-a*x - b*x^3 - c*v\"",
            "v = \"-a*x - q*x^3 - c*v\"",
            "state.v: column 8: unknown name 'q'",
        ),
        (
            "x = \"v\"\nv = \"-a*x - b*x^3 - c*v\"",
            "x = \"v\"",
            "a state variable without an equation",
        ),
        (
            "v = \"-a*x - b*x^3 - c*v\"",
            "v = \"-a*x - b*x^3 - c*v +\"",
            "state.v: column 21: the expression ends too early",
        ),
        (
            "b = { start = 0.1 }",
            "b = { start = 0.1 }\nd = { start = 1.0 }",
            "parameters.d: appears in no equation",
        ),
        (
            "c = { start = 0.1, min = 0.0 }",
            "c = { start = 0.1, min = 2.0, max = 1.0 }",
            "min 2 must be below max 1",
        ),
        (
            "latent = [\"x\"]",
            "latent = [\"y\"]",
            "observed.latent: 'y' is not a state variable",
        ),
        (
            "name = \"duffing\"",
            "name = \"duffing\"\nnmae = \"x\"",
            "nmae: unknown key",
        ),
        (
            "c = { start = 0.1, min = 0.0 }",
            "c = { start = 0.0, min = 0.0 }",
            "parameters.c.start: 0 must lie strictly inside",
        ),
        (
            "a = { start = 1.0, positive = true }",
            "a = { start = 1.0, positive = \"yes\" }",
            "parameters.a.positive: must be true or false",
        ),
        (
            "x = [0.5, 1.0]",
            "x = [1.0, 0.5]",
            "initial.x: min 1 > max 0.5",
        ),
        ("[observed]", "[observed", "toml: line"),
        (
            "latent = [\"x\"]",
            "latent = [\"x\"]\nkl = [\"2\"]",
            "observed.kl: each expression must read an observed variable",
        ),
        (
            "latent = [\"x\"]",
            "latent = [\"x\"]\nkl = [\"v\"]",
            "observed.kl: column 1: unknown name 'v' ('v' is a state variable, which observed.kl cannot read",
        ),
    ];
    for (from, to, want) in cases {
        assert!(super::parse_text(DUFFING).is_ok());
        let text = DUFFING.replacen(from, to, 1);
        assert_ne!(text, DUFFING, "{from}");
        let e = parse_text(&text).unwrap_err().to_string();
        assert!(e.starts_with("test.toml: "), "{e}");
        assert!(e.contains(want), "{want}: got {e}");
        assert!(!e.contains('\n'), "{e}");
    }
}
