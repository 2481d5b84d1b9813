//! Seeded property tests of what issue 50 bounded: a recording's clock over any frame times
//! (a grid or a refusal, never a panic, never more frames off their slots than the refusal's
//! limits), and the model-expression parser over any text, however long (a tree or a message,
//! never a stack overflow).

use physvid_shared::model_file::expr::parse;
use physvid_shared::video::clock::{Clock, END_FRAMES, MAX_MISSING, MAX_MISSING_SHARE};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, rng_seed: proptest::test_runner::RngSeed::Fixed(50), ..ProptestConfig::default() })]

    #[test]
    fn any_frame_times_give_a_grid_or_a_refusal(
        steps in proptest::collection::vec(0.0f64..3.0, 1..300),
        start in -5.0f64..5.0,
    ) {
        let mut times = vec![start];
        for s in &steps {
            times.push(times.last().unwrap() + s);
        }
        match Clock::fit(&times) {
            Ok(c) => {
                prop_assert!(c.interval > 0.0 && c.interval.is_finite());
                // Frames off the grid: a few at the ends left out, a tenth in the middle resampled.
                prop_assert!(c.head <= END_FRAMES && c.tail <= END_FRAMES, "{:?}", c);
                prop_assert!(c.off as f64 <= MAX_MISSING_SHARE * c.slots.len() as f64, "{:?}", c);
                prop_assert!(c.slots.windows(2).all(|w| w[0] <= w[1]));
                prop_assert!(c.slots.windows(2).all(|w| w[1] - w[0] <= MAX_MISSING + 1));
                let frames: Vec<f32> = (0..times.len()).map(|i| i as f32).collect();
                let grid = c.resample(&times, &frames, 1);
                prop_assert_eq!(grid.len(), c.slots.last().unwrap() + 1);
                prop_assert!(grid.iter().all(|v| v.is_finite()));
            }
            Err(u) => prop_assert!(!u.reason().contains('\n')),
        }
    }

    #[test]
    fn an_even_clock_with_rounded_times_is_found_and_left_alone(
        interval in 0.001f64..1.0,
        n in 3usize..400,
        wobble in proptest::collection::vec(-0.04f64..0.04, 400),
    ) {
        let times: Vec<f64> = (0..n).map(|k| (k as f64 + wobble[k]) * interval).collect();
        let c = Clock::fit(&times).unwrap();
        prop_assert!(c.is_even(), "{:?}", c);
        prop_assert!((c.interval / interval - 1.0).abs() < 0.05);
        let frames: Vec<f32> = (0..n).map(|i| i as f32).collect();
        prop_assert_eq!(c.resample(&times, &frames, 1), frames);
    }

    #[test]
    fn any_expression_text_parses_or_gives_a_message(
        text in ".{0,80}",
        repeat in 1usize..40_000,
        op in prop_oneof![Just("+"), Just("*"), Just("-"), Just("^"), Just("("), Just("-(")],
    ) {
        let names = |n: &str| ["x", "v", "k"].iter().position(|m| *m == n);
        if let Err(e) = parse(&text, &names) {
            prop_assert!(!e.message.is_empty());
        }
        let long = format!("x{}", format!("{op}x").repeat(repeat));
        if let Err(e) = parse(&long, &names) {
            prop_assert!(!e.message.is_empty());
        }
    }
}
