//! Our MSE+KL rollout loss against the ICML 2026 peer's (arXiv 2606.00115): the central-
//! difference ODE residual plus a floor on each clip's latent spread (`--loss residual+floor`),
//! on the three scenes: accuracy and time.

use crate::options::Opt;
use crate::runner::{DataSpec, Job, Runner};
use crate::table::{Cell, Table};
use estimator::loss::LossKind;

pub fn make(r: &Runner) -> anyhow::Result<Table> {
    let scenes = ["intensity", "position", "scale"];
    let losses = [LossKind::MseKl, LossKind::ResidualFloor];
    let mut t = Table::new(
        "losses",
        "Loss: MSE+KL rollout against residual+floor",
        &[
            ("data", "scenario"),
            ("loss", "loss"),
            ("γ0", "gamma0"),
            ("γ0 error", "gamma0_rel_error"),
            ("γ1", "gamma1"),
            ("γ1 error", "gamma1_rel_error"),
            ("latent R²", "latent_r2"),
            ("epochs", "epochs"),
            ("wall s", "wall_s"),
        ],
    );
    r.begin("losses", scenes.len() * losses.len());
    let mut specs = Vec::new();
    let mut jobs = Vec::new();
    for scene in scenes {
        let spec = DataSpec::new(scene, r.quick());
        specs.push(format!("`{}`", spec.command()));
        for loss in losses {
            jobs.push(Job::new(spec.clone(), vec![Opt::Loss(loss)]));
        }
    }
    let runs = r.estimate_all(&jobs)?;
    let mut runs = runs.iter();
    for scene in scenes {
        for loss in losses {
            let rep = runs.next().expect("a run for every job");
            let (g0, g1) = (rep.value("gamma0"), rep.value("gamma1"));
            t.push(vec![
                Cell::text(scene),
                Cell::text(loss.name()),
                Cell::num(g0.map(|p| p.estimate), 4),
                Cell::rel(g0.and_then(|p| p.relative_error)),
                Cell::num(g1.map(|p| p.estimate), 4),
                Cell::rel(g1.and_then(|p| p.relative_error)),
                Cell::num(rep.latent_vs_truth.as_ref().map(|f| f.r2()), 5),
                Cell::num(Some(rep.epochs_run as f64), 0),
                Cell::num(Some(rep.wall_time_s), 1),
            ]);
        }
    }
    t.note(format!(
        "Data: {} (truth γ0 = 4.0016, γ1 = 0.08).",
        specs.join(", ")
    ));
    t.note(
        "Runs: `estimate DATA --loss mse+kl|residual+floor` (exact block, default starts; the \
         validation metric that picks the epoch is the rollout error for both). residual+floor: \
         mean of (z'' + γ1·z' + γ0·z)² with z' = (z[t+1] − z[t−1])/2dt and z'' = (z[t+1] − 2z[t] \
         + z[t−1])/dt², plus the mean over clips of relu(0.7 − std of the clip's latent)².",
    );
    t.note(
        "The central second difference of cos ωt is −ω²·sinc²(ωdt/2)·cos ωt, so at ω·dt = 0.4 \
         the residual loss's γ0 is biased low by (ωdt)²/12 ≈ 1.3 %; the rollout loss integrates \
         exactly and has no such bias.",
    );
    Ok(t)
}
