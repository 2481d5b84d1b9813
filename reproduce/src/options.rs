//! The `estimate` options a table's run sets, typed ([`Opt`]): each sets its field of the run's
//! `Request` as its flag does, and shows itself as that flag (the tables print every run as a
//! command a person can type). No command line is written to be run or parsed: the request is
//! built field by field; a test checks that the flags shown ask the CLI for the same request.

use clap::ValueEnum;
use estimator::cli::flag_name;
use estimator::loss::LossKind;
use estimator::physics::{Integrator, ModelRef, RolloutStart};
use estimator::Request;

/// One option of a run, as `estimate`'s flag of the same name.
#[derive(Debug, Clone, PartialEq)]
pub enum Opt {
    Seed(u64),
    /// A built-in model by name, or `auto`: the choice among the candidates.
    Model(&'static str),
    Dt(f64),
    /// Starting values by parameter name.
    Init(Vec<(String, f64)>),
    SingleStart,
    Loss(LossKind),
    Integrator(Integrator),
    RolloutStart(RolloutStart),
    Epochs(usize),
    Ensemble(usize),
    InclineDeg(f64),
    /// The recording's physical quantity at times on its timeline (seconds, value).
    Reference(&'static [(f64, f64)]),
    /// A length in the picture (`X1,Y1:X2,Y2=METRES`).
    Stick(&'static str),
}

/// `v`'s name on the command line (`frames` for `RolloutStart::Frames`).
pub fn value_name<V: ValueEnum>(v: &V) -> String {
    v.to_possible_value()
        .expect("no skipped variants")
        .get_name()
        .to_string()
}

impl Opt {
    /// The field of `estimate`'s arguments this option sets (its clap id).
    fn id(&self) -> &'static str {
        match self {
            Opt::Seed(_) => "seed",
            Opt::Model(_) => "model",
            Opt::Dt(_) => "dt",
            Opt::Init(_) => "init",
            Opt::SingleStart => "single_start",
            Opt::Loss(_) => "loss",
            Opt::Integrator(_) => "integrator",
            Opt::RolloutStart(_) => "rollout_start",
            Opt::Epochs(_) => "epochs",
            Opt::Ensemble(_) => "ensemble",
            Opt::InclineDeg(_) => "incline_deg",
            Opt::Reference(_) => "reference",
            Opt::Stick(_) => "stick",
        }
    }

    /// Its value as the flag takes it (none for a switch).
    fn value(&self) -> Option<String> {
        let pairs = |p: Vec<String>| Some(p.join(","));
        match self {
            Opt::Seed(s) => Some(s.to_string()),
            Opt::Model(m) => Some(m.to_string()),
            Opt::Dt(v) | Opt::InclineDeg(v) => Some(v.to_string()),
            Opt::Init(init) => pairs(init.iter().map(|(n, v)| format!("{n}={v}")).collect()),
            Opt::SingleStart => None,
            Opt::Loss(l) => Some(value_name(l)),
            Opt::Integrator(i) => Some(value_name(i)),
            Opt::RolloutStart(s) => Some(value_name(s)),
            Opt::Epochs(n) | Opt::Ensemble(n) => Some(n.to_string()),
            Opt::Reference(times) => {
                pairs(times.iter().map(|(t, v)| format!("{t}s={v}")).collect())
            }
            Opt::Stick(s) => Some(s.to_string()),
        }
    }

    /// As a person types it: the flag (its name from its one definition) and its value.
    pub fn shown(&self) -> String {
        let flag = flag_name(self.id());
        self.value().map_or(flag.clone(), |v| format!("{flag} {v}"))
    }

    /// Sets its field of `req`, as `EstimateArgs::request` does for its flag.
    pub fn apply(&self, req: &mut Request) -> anyhow::Result<()> {
        let t = &mut req.training;
        match self {
            Opt::Seed(s) => t.seed = *s,
            Opt::Model("auto") => (req.choose, req.load.model) = (true, None),
            Opt::Model(m) => {
                let model = ModelRef::by_name(m).ok_or_else(|| anyhow::anyhow!("no model {m}"))?;
                (req.choose, req.load.model) = (false, Some(model));
            }
            Opt::Dt(dt) => req.load.dt = Some(*dt),
            Opt::Init(init) => req.init.clone_from(init),
            Opt::SingleStart => t.single_start = true,
            Opt::Loss(l) => t.loss = *l,
            Opt::Integrator(i) => req.integrator = *i,
            Opt::RolloutStart(s) => req.rollout_start = *s,
            Opt::Epochs(n) => t.epochs = *n,
            Opt::Ensemble(n) => t.ensemble = *n,
            Opt::InclineDeg(d) => req.calibration.incline_deg = Some(*d),
            Opt::Reference(times) => {
                req.calibration.times = times.to_vec();
                req.load.recording.measured_at = times.iter().map(|p| p.0).collect();
            }
            Opt::Stick(s) => {
                let stick = estimator::calibration::Stick::parse(s).map_err(anyhow::Error::msg)?;
                req.calibration.stick = Some(stick);
            }
        }
        Ok(())
    }
}

/// `opts` as a person types them, one after another.
pub fn shown(opts: &[Opt]) -> String {
    opts.iter().map(Opt::shown).collect::<Vec<_>>().join(" ")
}

/// The run of `opts` on `data`: `base` (where the report goes, the device, the threads) with
/// the model chosen where `estimate` would choose it (a recording, a bare `.npy`) and each option
/// applied.
pub fn request(
    data: &std::path::Path,
    base: impl FnOnce(&mut Request),
    opts: &[Opt],
) -> anyhow::Result<Request> {
    let mut req = Request::new(data);
    req.choose = estimator::choice::chosen_without_model(data);
    base(&mut req);
    for o in opts {
        o.apply(&mut req)?;
    }
    Ok(req)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use estimator::EstimateArgs;

    /// What the CLI asks for on `data` with `shown` and the base's flags.
    fn cli(data: &str, shown: &str, out: &str) -> Request {
        let mut line = vec!["estimate", data];
        line.extend(shown.split_whitespace());
        line.extend(["--quiet", "--out", out, "--threads", "1"]);
        EstimateArgs::try_parse_from(&line)
            .unwrap()
            .validate()
            .unwrap()
            .request()
            .unwrap()
    }

    #[test]
    fn every_option_asks_what_its_flag_asks() {
        let dir = tempfile::tempdir().unwrap();
        let set = dir.path().join("set");
        std::fs::create_dir(&set).unwrap();
        std::fs::write(set.join("meta.json"), "{}").unwrap();
        let out = dir.path().join("out");
        let base = |r: &mut Request| {
            (r.quiet, r.out, r.training.threads) = (true, out.clone(), 1);
        };
        let cases: Vec<(&str, Vec<Opt>)> = vec![
            ("set", vec![]),
            ("clip.mp4", vec![]),
            (
                "set",
                vec![
                    Opt::Seed(3),
                    Opt::Init(vec![("gamma0".into(), 16.0), ("gamma1".into(), 0.32)]),
                    Opt::SingleStart,
                    Opt::Loss(LossKind::ResidualFloor),
                    Opt::Integrator(Integrator::Euler),
                    Opt::RolloutStart(RolloutStart::Frames),
                    Opt::Epochs(40),
                    Opt::Ensemble(5),
                ],
            ),
            (
                "x.npy",
                vec![Opt::Dt(0.0333333), Opt::Model("damped-oscillator")],
            ),
            ("set", vec![Opt::Model("auto")]),
            (
                "roll.avi",
                vec![
                    Opt::InclineDeg(10.3),
                    Opt::Reference(&[(0.3, 0.076), (0.8, 0.36)]),
                ],
            ),
        ];
        for (input, opts) in cases {
            let data = if input == "set" {
                set.clone()
            } else {
                dir.path().join(input)
            };
            let typed = request(&data, base, &opts).unwrap();
            let line = shown(&opts);
            let asked = cli(data.to_str().unwrap(), &line, out.to_str().unwrap());
            assert_eq!(typed, asked, "{input} {line}");
        }
    }

    #[test]
    fn options_show_as_flags() {
        let opts = [
            Opt::Init(vec![("k".into(), 10.0)]),
            Opt::Reference(&[(3.933, 0.0), (6.5, 1.975)]),
            Opt::SingleStart,
            Opt::Integrator(Integrator::Euler),
        ];
        assert_eq!(
            shown(&opts),
            "--init k=10 --reference 3.933s=0,6.5s=1.975 --single-start --integrator euler"
        );
    }
}
