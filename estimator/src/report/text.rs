//! The report as text: the table printed at the end of a run and `metrics.csv`.

use super::Report;
use crate::digits::significant;

impl Report {
    /// The closing table: parameter, estimate, ground truth, relative error.
    pub fn table(&self) -> String {
        let noise = self.run.training_noise.map_or(String::new(), |s| {
            format!(", fresh noise σ {s:.2} on the training frames")
        });
        let mut s = format!(
            "{} on {} ({}, {} integrator, {} epochs, best {}{noise}, {:.1} s on {})\n",
            self.run.model,
            self.run.input,
            self.run.config.loss.name(),
            self.run.config.integrator.name(),
            self.run.epochs_run,
            self.run.best_epoch,
            self.run.wall_time_s,
            self.run.device
        );
        s += &format!(
            "{:<20} {:>12} {:>12} {:>8} {:>12} {:>12}\n",
            "parameter", "estimate", "± std. err.", "unit", "truth", "rel. error"
        );
        for p in &self.run.parameters {
            let truth = p.truth.map_or("-".into(), |t| format!("{t:.6}"));
            let err = p
                .relative_error
                .map_or("-".into(), |e| format!("{:+.3} %", e * 100.0));
            let se = p
                .standard_error
                .map_or("-".into(), |e| format!("± {}", significant(e)));
            s += &format!(
                "{:<20} {:>12.6} {:>12} {:>8} {:>12} {:>12}\n",
                p.name, p.estimate, se, p.unit, truth, err
            );
        }
        for p in &self.run.parameters {
            if let Some(both) = p.routes_phrase() {
                s += &format!("{}: {both}\n", p.name);
            }
        }
        if let Some(c) = &self.run.cross_check {
            s += &format!(
                "cross-check: {} from the amplitude decay of {} swings (appendix A.6): {:.4} ± {:.4} \
                 (learned {:.4}: {})\n",
                c.name,
                c.peaks.len(),
                c.estimate,
                c.std_error,
                c.learned,
                if c.agrees {
                    "within 2 standard errors"
                } else {
                    "outside 2 standard errors"
                }
            );
        }
        s.trim_end().to_string()
    }

    /// `metrics.csv`: one row per epoch.
    pub fn metrics_csv(&self) -> String {
        let names: Vec<&str> = self
            .run
            .block_parameters
            .iter()
            .map(String::as_str)
            .collect();
        let mut s = format!(
            "epoch,train_loss,val_loss,val_mse,val_rel_mse,latent_std,{},lr,lr_phys,elapsed_s,frames\n",
            names.join(",")
        );
        for r in &self.run.history {
            let params: Vec<String> = r.parameters.iter().map(|v| format!("{v}")).collect();
            s += &format!(
                "{},{},{},{},{},{},{},{},{},{:.4},{}\n",
                r.epoch,
                r.train_loss,
                r.val_loss,
                r.val_mse,
                r.val_rel_mse,
                r.latent_std,
                params.join(","),
                r.lr,
                r.lr_phys,
                r.elapsed_s,
                r.frames
            );
        }
        s
    }
}
