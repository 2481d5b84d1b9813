//! A seeded property test of the `NAME=VALUE` parser every program uses (`--set`, `--init`):
//! any text gives pairs or one message, never a panic; lists of distinct names read back as
//! written; a name given twice, a value that is not finite, an empty name are refused.

use physvid_shared::cli::parse_name_values;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, rng_seed: proptest::test_runner::RngSeed::Fixed(30), ..ProptestConfig::default() })]

    #[test]
    fn any_text_parses_or_gives_one_message(text in ".{0,60}") {
        if let Err(e) = parse_name_values(&text) {
            prop_assert!(!e.is_empty() && !e.contains('\n'));
        }
    }

    #[test]
    fn distinct_names_read_back_and_a_repeat_is_refused(
        pairs in proptest::collection::btree_map("[a-z][a-z0-9_]{0,8}", -1e12f64..1e12, 1..6),
        repeat in 0usize..6,
    ) {
        let text: Vec<String> = pairs.iter().map(|(k, v)| format!("{k}={v}")).collect();
        let parsed = parse_name_values(&text.join(",")).unwrap();
        let expected: Vec<(String, f64)> = pairs.iter().map(|(k, v)| (k.clone(), *v)).collect();
        prop_assert_eq!(&parsed, &expected);
        let (k, _) = &expected[repeat % expected.len()];
        let twice = format!("{},{}=1", text.join(","), k);
        let e = parse_name_values(&twice).unwrap_err();
        prop_assert!(e.contains("given twice"), "{}", e);
    }

    #[test]
    fn values_that_are_not_finite_are_refused(v in prop_oneof![Just("nan"), Just("inf"), Just("-inf"), Just("1e999")]) {
        let text = format!("a={}", v);
        prop_assert!(parse_name_values(&text).is_err());
    }
}
