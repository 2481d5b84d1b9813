//! `track.png`: the object's own track (its position along its motion's axis against time, or
//! a brightness's grey level, each sample shaded by its quality) with each law fitted where it
//! holds, the chosen law's span shaded: the second route's evidence, and what a person checks
//! first on a recording.

use super::{chart, legend, range, render_png, PANEL_HEIGHT};
use crate::track::{Reading, TrackRoute};
use plotters::prelude::*;

/// The figure for `route`.
pub fn track_png(route: &TrackRoute) -> Result<Vec<u8>, String> {
    let t = &route.track;
    render_png(PANEL_HEIGHT + 100, |root| {
        let first = t.t.first().copied().unwrap_or(0.0);
        let last = t.t.last().copied().unwrap_or(1.0).max(first + 1e-3);
        let y = range(t.along.iter().copied());
        let (caption, unit) = match t.reading {
            Reading::Brightness => (
                "the brightness of what changes in place, and the law fitted",
                "grey level",
            ),
            _ => (
                "the object's track: position along its motion's axis, and the laws fitted",
                "pixels",
            ),
        };
        let mut c = chart(&root, caption, (first..last, "time (s)"), (y.clone(), unit))?;
        if let Some(l) = route.chosen_span() {
            let span = RGBColor(70, 130, 180).mix(0.18);
            c.draw_series(std::iter::once(Rectangle::new(
                [(l.first_s, y.start), (l.last_s, y.end)],
                span.filled(),
            )))
            .map_err(|e| e.to_string())?
            .label(format!(
                "chosen: {} over {:.2}–{:.2} s",
                l.law.name(),
                l.first_s,
                l.last_s
            ))
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], span.filled()));
        }
        c.draw_series(
            t.t.iter()
                .zip(&t.along)
                .zip(&t.quality)
                .map(|((&s, &u), &q)| {
                    let shade = (200.0 * (1.0 - q.clamp(0.0, 1.0))) as u8;
                    Circle::new((s, u), 2, RGBColor(shade, shade, shade).filled())
                }),
        )
        .map_err(|e| e.to_string())?
        .label("the track (lighter: lower quality)")
        .legend(|(x, y)| Circle::new((x + 10, y), 3, BLACK.filled()));
        for (law, color) in route.laws.iter().zip([RED, RGBColor(0, 150, 0)]) {
            let times = &t.t[law.first..law.first + law.samples];
            c.draw_series(LineSeries::new(
                times.iter().copied().zip(law.curve.iter().copied()),
                color.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?
            .label(format!(
                "{}{}",
                law.law.name(),
                if law.holds { "" } else { " (does not hold)" }
            ))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        }
        legend(&mut c)
    })
}
