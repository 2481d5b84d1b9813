//! `change.png`: a recording's picture over time, as the survey measured it: the share of each
//! frame that differs from the background (each pixel's median, the frame's level taken out),
//! the object's usual share and the share beyond which something else takes the picture (a
//! hand), with the span the model was fitted on shaded. Where the fit starts and ends, and why
//! (a hand letting go, still frames, a release), is what a person checks here first.

use super::{chart, legend, range, render_png, PANEL_HEIGHT};
use crate::data::summary::RecordingSummary;
use plotters::prelude::*;

/// The figure for `r`, where its survey measured the frames' departures (`--crop auto` on a
/// recording of 16 frames or more).
pub fn change_png(r: &RecordingSummary) -> Option<Result<Vec<u8>, String>> {
    let survey = r.survey.as_ref()?;
    let d = survey.change.as_ref()?;
    let fps = if r.timeline_fps > 0.0 {
        r.timeline_fps
    } else {
        r.fps
    };
    let time = |k: usize| survey.first_s + k as f64 / fps;
    let last = time(d.shares.len().saturating_sub(1));
    let kept = (
        r.start.unwrap_or(survey.first_s),
        r.end.unwrap_or(last).min(last),
    );
    let pct: Vec<f64> = d.shares.iter().map(|s| 100.0 * s).collect();
    Some(render_png(PANEL_HEIGHT + 100, |root| {
        let x = (
            survey.first_s..last.max(survey.first_s + 1e-3),
            "time in the recording (s)",
        );
        let top = range(pct.iter().copied().chain([100.0 * d.limit])).end;
        let caption = "the picture's change: share of each frame that differs from the background";
        let mut c = chart(&root, caption, x, (0.0..top, "% of the frame"))?;
        let span = RGBColor(70, 130, 180).mix(0.18);
        c.draw_series(std::iter::once(Rectangle::new(
            [(kept.0, 0.0), (kept.1, top)],
            span.filled(),
        )))
        .map_err(|e| e.to_string())?
        .label(format!("fitted: {:.2}–{:.2} s", kept.0, kept.1))
        .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], span.filled()));
        let line = |v: f64, color: RGBColor| {
            LineSeries::new(
                [(survey.first_s, 100.0 * v), (last, 100.0 * v)],
                color.stroke_width(1),
            )
        };
        let grey = RGBColor(120, 120, 120);
        c.draw_series(line(d.object, grey))
            .map_err(|e| e.to_string())?
            .label("the object's usual share")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], grey));
        c.draw_series(line(d.limit, RED))
            .map_err(|e| e.to_string())?
            .label("beyond: something else in the picture (a hand)")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
        c.draw_series(LineSeries::new(
            pct.iter().enumerate().map(|(k, &v)| (time(k), v)),
            BLACK.stroke_width(1),
        ))
        .map_err(|e| e.to_string())?;
        legend(&mut c)
    }))
}
