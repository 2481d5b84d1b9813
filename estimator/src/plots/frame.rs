//! `frame.jpg`: a frame of the recording (`video::still`'s JPEG) with the object's track drawn
//! where it was seen (its chosen law's span in blue, the rest in white; a brightness's region
//! boxed in blue) and the stick or the plane given in orange: what a person checks at a glance
//! (did the tool follow the thing I meant, does the stick lie along the length I meant), and
//! the picture the docs show.

use crate::track::TrackRoute;
use plotters::prelude::*;

/// The stick's and the plane's colour (report.html's too).
const ORANGE: RGBColor = RGBColor(240, 140, 0);
/// The JPEG's quality (a photograph's: a tenth of a PNG's bytes, the lines still sharp).
const QUALITY: u8 = 88;
/// The chosen law's span.
const SPAN: RGBColor = RGBColor(0, 180, 216);

/// `jpeg` (a frame whose displayed size is `displayed`) with `route`'s track and scale drawn.
pub fn frame_jpeg(
    jpeg: &[u8],
    displayed: (usize, usize),
    route: &TrackRoute,
) -> Result<Vec<u8>, String> {
    let img = image::load_from_memory_with_format(jpeg, image::ImageFormat::Jpeg)
        .map_err(|e| e.to_string())?
        .to_rgb8();
    let (w, h) = img.dimensions();
    // The JPEG may be smaller than the frame as displayed (`video::still`'s longest side).
    let k = w as f64 / displayed.0.max(1) as f64;
    let at = |(x, y): (f64, f64)| ((x * k).round() as i32, (y * k).round() as i32);
    let wide = ((w.max(h) as f64) / 300.0).ceil().max(1.0) as u32;
    let mut buf = img.into_raw();
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        let fail = |e: DrawingAreaErrorKind<_>| e.to_string();
        let t = &route.track;
        let span = route
            .chosen_span()
            .map_or(0..0, |l| l.first..l.first + l.samples);
        for (i, p) in t.x.iter().zip(&t.y).enumerate() {
            let colour = if span.contains(&i) { SPAN } else { WHITE };
            root.draw(&Circle::new(at((*p.0, *p.1)), wide + 1, colour.filled()))
                .map_err(fail)?;
        }
        // A brightness: the box of the region whose light is read.
        if let Some((x0, y0, x1, y1)) = t.region {
            root.draw(&Rectangle::new(
                [at((x0, y0)), at((x1, y1))],
                SPAN.stroke_width(wide),
            ))
            .map_err(fail)?;
        }
        if let Some(s) = route.stick {
            let (a, b) = (at(s.from), at(s.to));
            root.draw(&PathElement::new(vec![a, b], ORANGE.stroke_width(wide + 1)))
                .map_err(fail)?;
            for end in [a, b] {
                root.draw(&Circle::new(end, 3 * wide, ORANGE.stroke_width(wide)))
                    .map_err(fail)?;
            }
        }
        if let Some(p) = route.plane {
            let mut corners: Vec<(i32, i32)> = p.corners.iter().map(|c| at(*c)).collect();
            corners.push(corners[0]);
            root.draw(&PathElement::new(
                corners.clone(),
                ORANGE.stroke_width(wide + 1),
            ))
            .map_err(fail)?;
            root.draw(&Circle::new(
                corners[0],
                3 * wide,
                ORANGE.stroke_width(wide),
            ))
            .map_err(fail)?;
        }
        root.present().map_err(fail)?;
    }
    let img = image::RgbImage::from_raw(w, h, buf).expect("buffer matches size");
    let mut jpeg = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, QUALITY)
        .encode_image(&img)
        .map_err(|e| e.to_string())?;
    Ok(jpeg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calibration::Stick;
    use crate::track::metres::tests::tossed;

    #[test]
    fn the_track_and_the_stick_are_drawn_where_they_lie() {
        // A grey 400×300 frame shown at 800×600: everything drawn at half its coordinates.
        let grey = image::RgbImage::from_pixel(400, 300, image::Rgb([60, 60, 60]));
        let mut jpeg = std::io::Cursor::new(Vec::new());
        grey.write_to(&mut jpeg, image::ImageFormat::Jpeg).unwrap();
        let route = tossed().with_stick(Stick::parse("100,500:700,500=1").unwrap());
        let out = frame_jpeg(jpeg.get_ref(), (800, 600), &route).unwrap();
        let out = image::load_from_memory(&out).unwrap().to_rgb8();
        assert_eq!(out.dimensions(), (400, 300));
        // The stick along y = 250 from x = 50 to 350; the toss's first sample (10, 200) at
        // (5, 100), before its law's span: white.
        let p = out.get_pixel(200, 250);
        assert!(p[0] > 200 && p[2] < 80, "{p:?}");
        assert!(out.get_pixel(5, 100).0.iter().all(|c| *c > 200));
        assert!(out.get_pixel(200, 20).0.iter().all(|c| c.abs_diff(60) < 10));
    }
}
