//! The calibration flags' values: `--reference` parsed (frames, a recording's times, bodies'
//! positions); a test holds each kind of calibration's flag name (`CalibrationInput::flag`) to
//! its clap definition.

/// `--reference` values: CLIP:FRAME=VALUE triples, SECONDSs=VALUE pairs (a recording's
/// timeline), and CLIP:FRAME=X1/Y1/X2/Y2 body positions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReferencePoints {
    pub values: Vec<(usize, usize, f64)>,
    /// (seconds on the recording's timeline, value).
    pub times: Vec<(f64, f64)>,
    pub positions: Vec<(usize, usize, Vec<f64>)>,
}

/// Parses `--reference 0:0=0.07,12:19=0.01` (clip:frame=physical value) and
/// `--reference 0:0=20/30/44/33` (clip:frame=positions separated by '/').
pub fn parse_reference(text: &str) -> Result<ReferencePoints, String> {
    let mut points = ReferencePoints::default();
    for item in text.split(',').filter(|s| !s.trim().is_empty()) {
        let bad = || {
            format!(
                "'{item}' is not CLIP:FRAME=VALUE, SECONDSs=VALUE or CLIP:FRAME=X1/Y1/X2/Y2 (e.g. 0:0=0.07,3:19=0.01 or 3.0s=0.079)"
            )
        };
        let (at, v) = item.split_once('=').ok_or_else(bad)?;
        if let Some(t) = at.trim().strip_suffix('s') {
            let t: f64 = t.trim().parse().map_err(|_| bad())?;
            let v: f64 = v.trim().parse().map_err(|_| bad())?;
            if !(t.is_finite() && t >= 0.0 && v.is_finite()) {
                return Err(format!(
                    "'{item}': the time must be >= 0 s and the value a finite number"
                ));
            }
            if points.times.iter().any(|&(t2, _)| t2 == t) {
                return Err(format!(
                    "'{item}': the time {t} s is given twice; give each once"
                ));
            }
            points.times.push((t, v));
            continue;
        }
        let (c, f) = at.split_once(':').ok_or_else(bad)?;
        let (c, f) = (
            c.trim().parse().map_err(|_| bad())?,
            f.trim().parse().map_err(|_| bad())?,
        );
        let numbers: Vec<f64> = v
            .split('/')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad())?;
        if let Some(x) = numbers.iter().find(|x| !x.is_finite()) {
            return Err(format!("'{item}': {x} is not a finite number"));
        }
        let taken = points.values.iter().any(|p| (p.0, p.1) == (c, f))
            || points.positions.iter().any(|p| (p.0, p.1) == (c, f));
        if taken {
            return Err(format!(
                "'{item}': clip {c} frame {f} is given twice; give each frame once"
            ));
        }
        match numbers[..] {
            [v] => points.values.push((c, f, v)),
            _ => points.positions.push((c, f, numbers)),
        }
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calibration::CalibrationInput;

    #[test]
    fn every_calibration_names_its_flag() {
        for (c, id) in CalibrationInput::ALL
            .into_iter()
            .zip(["reference", "incline_deg", "g"])
        {
            assert_eq!(c.flag(), super::super::flag_name(id));
        }
    }
    #[test]
    fn references_parse_or_say_what_is_wrong() {
        assert_eq!(
            parse_reference("0:1=0.5").unwrap().values,
            vec![(0, 1, 0.5)]
        );
        let p = parse_reference("0:1=0.5,2:3=1/2/3.5/4").unwrap();
        assert_eq!(p.positions, vec![(2, 3, vec![1.0, 2.0, 3.5, 4.0])]);
        assert!(parse_reference("0=0.5").is_err());
        assert!(parse_reference("0:1=1/x").is_err());
        assert!(parse_reference("0:1=nan").is_err());
        let t = parse_reference("3.0s=0.079, 20.5s=0.012,1:2=0.5").unwrap();
        assert_eq!(t.times, vec![(3.0, 0.079), (20.5, 0.012)]);
        assert_eq!(t.values, vec![(1, 2, 0.5)]);
        assert!(parse_reference("-1s=0.5").is_err());
        assert!(parse_reference("0:1=0.5,0:1=0.5")
            .unwrap_err()
            .contains("twice"));
        assert!(parse_reference("3s=0.1,3.0s=0.2")
            .unwrap_err()
            .contains("twice"));
        assert!(parse_reference("xs=0.5").is_err());
    }

    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 512, rng_seed: proptest::test_runner::RngSeed::Fixed(31), ..ProptestConfig::default() })]

        /// Any text parses or gives one message; distinct frames read back as written.
        #[test]
        fn references_parse_or_say_why(text in ".{0,60}") {
            if let Err(e) = parse_reference(&text) {
                prop_assert!(!e.is_empty() && !e.contains('\n'));
            }
        }

        #[test]
        fn distinct_frames_read_back(
            frames in proptest::collection::btree_map((0usize..50, 0usize..20), -1e6f64..1e6, 1..6),
        ) {
            let text: Vec<String> = frames.iter().map(|((c, f), v)| format!("{c}:{f}={v}")).collect();
            let p = parse_reference(&text.join(",")).unwrap();
            let expected: Vec<(usize, usize, f64)> = frames.iter().map(|(&(c, f), &v)| (c, f, v)).collect();
            prop_assert_eq!(p.values, expected);
        }
    }
}
