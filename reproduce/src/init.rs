//! Robustness to initialisation, which the paper claims without numbers: γ0 started from 0.1 to
//! 100 (γ1 the same factor off its truth: γ0/50) on the three scenes, five training seeds each;
//! the share of runs that end with γ0 within 1 % and γ1 within 10 %, and the median epochs they
//! took to first get there. Our default (a second start read off the frames) against the
//! paper's single start.

use crate::options::Opt;
use crate::runner::{DataSpec, Job, Runner};
use crate::table::{Cell, Table};
use crate::worker::Run;

/// Success: γ0 within 1 %, γ1 within 10 % of the truth.
pub fn success(g0: f64, g1: f64, truth: (f64, f64)) -> bool {
    (g0 - truth.0).abs() <= 0.01 * truth.0 && (g1 - truth.1).abs() <= 0.1 * truth.1.abs()
}

/// The first epoch whose parameters met [`success`].
fn epochs_to_success(rep: &Run, truth: (f64, f64)) -> Option<usize> {
    rep.history
        .iter()
        .find(|e| success(e.parameters[0], e.parameters[1], truth))
        .map(|e| e.epoch)
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    })
}

pub fn make(r: &Runner) -> anyhow::Result<Table> {
    let (scenes, starts, seeds): (&[&str], &[f64], u64) = if r.quick() {
        (&["intensity", "position"], &[0.1, 10.0, 100.0], 1)
    } else {
        (
            &["intensity", "position", "scale"],
            &[0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0],
            5,
        )
    };
    let modes: [(&str, &[Opt]); 2] = [
        ("ours (2 starts)", &[]),
        ("single start", &[Opt::SingleStart]),
    ];
    let mut t = Table::new(
        "init",
        "Robustness to the initial γ0, γ1",
        &[
            ("data", "scenario"),
            ("start", "mode"),
            ("γ0 init", "gamma0_init"),
            ("γ1 init", "gamma1_init"),
            ("successes", "successes"),
            ("runs", "runs"),
            ("median epochs to success", "median_epochs_to_success"),
            ("median γ0", "median_gamma0"),
            ("median γ1", "median_gamma1"),
            ("median wall s", "median_wall_s"),
        ],
    );
    r.begin(
        "init",
        scenes.len() * starts.len() * seeds as usize * modes.len(),
    );
    let mut specs = Vec::new();
    let mut jobs = Vec::new();
    for &scene in scenes {
        let spec = DataSpec::new(scene, r.quick());
        specs.push(format!("`{}`", spec.command()));
        for (_, mode) in modes {
            for &g0 in starts {
                let init = vec![
                    ("gamma0".to_string(), g0),
                    ("gamma1".to_string(), g0 / 50.0),
                ];
                for seed in 0..seeds {
                    let mut opts = vec![Opt::Init(init.clone()), Opt::Seed(seed)];
                    opts.extend(mode.iter().cloned());
                    jobs.push(Job::new(spec.clone(), opts));
                }
            }
        }
    }
    let runs = r.estimate_all(&jobs)?;
    let mut runs = runs.iter();
    for &scene in scenes {
        for (mode, _) in modes {
            for &g0 in starts {
                let g1 = g0 / 50.0;
                let (mut ok, mut epochs, mut v0, mut v1, mut wall) =
                    (0, vec![], vec![], vec![], vec![]);
                for _ in 0..seeds {
                    let rep = runs.next().expect("a run for every job");
                    let truth = (
                        rep.value("gamma0")
                            .and_then(|p| p.truth)
                            .unwrap_or(f64::NAN),
                        rep.value("gamma1")
                            .and_then(|p| p.truth)
                            .unwrap_or(f64::NAN),
                    );
                    let (e0, e1) = (rep.final_values[0], rep.final_values[1]);
                    if success(e0, e1, truth) {
                        ok += 1;
                        if let Some(e) = epochs_to_success(rep, truth) {
                            epochs.push(e as f64);
                        }
                    }
                    v0.push(e0);
                    v1.push(e1);
                    wall.push(rep.wall_time_s);
                }
                t.push(vec![
                    Cell::text(scene),
                    Cell::text(mode),
                    Cell::num(Some(g0), 1),
                    Cell::num(Some(g1), 3),
                    Cell::num(Some(ok as f64), 0),
                    Cell::num(Some(seeds as f64), 0),
                    Cell::num(median(epochs), 1),
                    Cell::num(median(v0), 4),
                    Cell::num(median(v1), 4),
                    Cell::num(median(wall), 1),
                ]);
            }
        }
    }
    t.note(format!("Data: {}.", specs.join(", ")));
    t.note(format!(
        "Runs: `estimate DATA --init gamma0=G0,gamma1=G0/50 --seed S [--single-start]`, seeds \
         0–{}. Success: the kept γ0 within 1 % and γ1 within 10 % of the truth (4.0016, 0.08). \
         Epochs to success: the first epoch whose parameters met it, counting the 8 probe epochs \
         of the kept start; the discarded start's probe is not counted.",
        seeds - 1
    ));
    t.note(
        "Ours: a second start, γ0 and γ1 read off the frames' principal components by the exact \
         two-step recurrence, is probed beside --init and the better kept by validation error. \
         Single start: the paper's protocol, training only from --init.",
    );
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn success_needs_both_parameters_and_median_handles_even_counts() {
        let truth = (4.0016, 0.08);
        assert!(success(4.03, 0.087, truth));
        assert!(!success(4.05, 0.08, truth));
        assert!(!success(4.0, 0.09, truth));
        assert_eq!(median(vec![3.0, 1.0, 2.0, 10.0]), Some(2.5));
        assert_eq!(median(vec![]), None);
    }
}
