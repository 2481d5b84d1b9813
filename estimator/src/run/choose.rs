//! The model's choice: every candidate model fitted in turn on the same clips, ranked by what
//! the evidence favours (`choice`), the chosen one's report and clips kept.

use super::{estimate, loaded, Estimation, Watch};
use crate::choice;
use crate::choice::ChoiceRequest;
use crate::config::Request;
use crate::error::EstimateError;
use crate::verdict;
use physvid_shared::term;
use std::time::Instant;

/// Whether `req` chooses its model: asked to (`choose`), or no model named on an input that
/// names none (`choice::names_no_model`).
pub fn chooses(req: &Request) -> bool {
    req.choose || (req.load.model.is_none() && choice::names_no_model(&req.load))
}

/// Fits every candidate model and keeps the one the evidence favours (`choice`), with the
/// ranking in its report; writes nothing.
pub fn choose(req: &Request, watch: Watch) -> anyhow::Result<Estimation> {
    let begun = Instant::now();
    let (models, cut) = choice::candidates(&ChoiceRequest::of(req))?;
    let tries: Vec<Request> = models
        .into_iter()
        .map(|m| choice::candidate_request(req, m, cut.as_ref()))
        .collect();
    let cut = cut.map(|c| c.why);
    let quiet = req.quiet;
    let (mut fits, mut summaries, mut errors) = (Vec::new(), Vec::new(), Vec::new());
    for (i, a) in tries.iter().enumerate() {
        let model = a.load.model.expect("a candidate names its model");
        let start = Instant::now();
        // Only the report is kept: a candidate's clips are hundreds of MB (the phone spring's
        // 707 clips of 20 frames, 317 MB; all five held to the end took 2 GB), and the chosen
        // one's are loaded again once the ranking is made.
        let fit = estimate(a, watch).map(|e| e.report);
        let summary = choice::summary(
            model,
            fit.as_ref()
                .map(|r| (&r.run, &r.verdict))
                .map_err(|e| e.to_string()),
        );
        // A candidate that fails says so in the ranking: a refusal every candidate shares
        // (the input's) stays one line.
        if !quiet && fit.is_ok() {
            term::eprint_line(&format!(
                "model choice {}/{}: {} ({:.1} s)",
                i + 1,
                tries.len(),
                summary.line(),
                start.elapsed().as_secs_f64()
            ));
        }
        summaries.push(summary);
        fits.push(fit.map_err(|e| errors.push(e)).ok());
    }
    let Some(mut ranked) = choice::rank::rank(summaries) else {
        // The same refusal from every candidate is the input's, and stands alone; else the
        // first is named.
        let first = errors.remove(0);
        if errors.iter().all(|e| e.to_string() == first.to_string()) {
            return Err(first);
        }
        return Err(EstimateError::NoEstimate(format!(
            "no candidate model gave an estimate ({}); pass --model",
            first
        ))
        .into());
    };
    let i = tries
        .iter()
        .position(|a| a.load.model.is_some_and(|m| m.name() == ranked.chosen))
        .expect("the chosen model is a candidate");
    let mut chosen = match req.training.ensemble {
        1 => Estimation {
            report: fits[i].take().expect("the chosen candidate was fitted"),
            data: loaded(&tries[i])?.1,
        },
        k => {
            let mut a = tries[i].clone();
            a.training.ensemble = k;
            estimate(&a, watch)?
        }
    };
    chosen.report.run.config.quiet = quiet;
    ranked.wall_time_s = begun.elapsed().as_secs_f64();
    ranked.cut = cut;
    chosen.report.verdict =
        verdict::judge(&chosen.report.run).with(choice::close::close_call(&ranked));
    chosen.report.model_choice = Some(ranked);
    Ok(chosen)
}
