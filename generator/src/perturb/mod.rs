//! Perturbations of rendered clips, the footage of others in miniature (`gen --perturb
//! NAME:LEVEL,...`, levels 1–5): a textured static background, moving distractors, camera
//! shake, brightness drift, a moving light with shadow, an occluder, Gaussian noise. Each is one
//! file implementing [`Perturbation`], listed once in [`PERTURBATIONS`]; `--help` and
//! meta.json's `perturbations` describe them from their `help`. Time scales are relative to the
//! clip's span, so a level means the same for a 1-s and a 19-s clip. Draws come from streams of
//! their own (the clip's, and one shared by every clip for what is static), so a perturbed set's
//! motion is the clean set's, and the clean set's files are unchanged.

mod distractors;
mod drift;
mod light;
mod noise;
mod occluder;
mod shake;
mod texture;

use crate::render::Canvas;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The highest level of every perturbation.
pub const MAX_LEVEL: u8 = 5;

/// One clip being perturbed: its frames (T × C × S × S, values in [0, 1]) and what they show.
pub struct Clip<'a> {
    pub frames: &'a mut [f32],
    pub frames_per_clip: usize,
    pub channels: usize,
    pub size: usize,
    /// Seconds between frames, and the clip's span ((T − 1)·dt).
    pub dt: f64,
    pub canvas: &'a mut Canvas,
}

impl Clip<'_> {
    pub fn span(&self) -> f64 {
        (self.frames_per_clip.saturating_sub(1)).max(1) as f64 * self.dt
    }

    /// Values per frame.
    pub fn frame_len(&self) -> usize {
        self.channels * self.size * self.size
    }

    /// The background's grey in channel `c`: the median of the first frame (most of a frame
    /// is background).
    pub fn background(&self, c: usize) -> f32 {
        let px = self.size * self.size;
        let mut v: Vec<f32> = self.frames[c * px..(c + 1) * px].to_vec();
        v.sort_by(f32::total_cmp);
        v[v.len() / 2]
    }
}

/// A perturbation of rendered clips.
pub trait Perturbation: Sync {
    /// Its name in `--perturb`.
    fn name(&self) -> &'static str;
    /// What it does and what a level means, in one line (for `--help` and meta.json).
    fn help(&self) -> &'static str;
    /// Perturbs `clip` at `level` (1–5): `rng` is the clip's own stream, `fixed` a stream that
    /// starts alike for every clip of the run (a static background, an occluder).
    fn apply(&self, level: u8, clip: &mut Clip, rng: &mut ChaCha8Rng, fixed: &mut ChaCha8Rng);
}

/// Every perturbation, in the order they are applied (what is in the scene first, the camera
/// and the sensor last).
pub static PERTURBATIONS: &[&dyn Perturbation] = &[
    &texture::Texture,
    &occluder::Occluder,
    &distractors::Distractors,
    &light::Light,
    &drift::Drift,
    &shake::Shake,
    &noise::Noise,
];

/// A perturbation at a level.
#[derive(Clone, Copy)]
pub struct Perturbed {
    pub perturbation: &'static dyn Perturbation,
    pub level: u8,
}

impl PartialEq for Perturbed {
    fn eq(&self, other: &Self) -> bool {
        self.perturbation.name() == other.perturbation.name() && self.level == other.level
    }
}

impl std::fmt::Debug for Perturbed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.perturbation.name(), self.level)
    }
}

/// Parses `--perturb NAME:LEVEL[,NAME:LEVEL...]`, in [`PERTURBATIONS`]' order; a name twice,
/// an unknown name or a level outside 1–5 is refused.
pub fn parse(text: &str) -> Result<Vec<Perturbed>, String> {
    let mut out: Vec<Perturbed> = Vec::new();
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (name, level) = item
            .split_once(':')
            .ok_or_else(|| format!("'{item}': give NAME:LEVEL, e.g. shake:3"))?;
        let p = PERTURBATIONS
            .iter()
            .find(|p| p.name() == name.trim())
            .ok_or_else(|| {
                format!(
                    "'{name}' is not a perturbation; they are {}",
                    names().join(", ")
                )
            })?;
        let level: u8 = level
            .trim()
            .parse()
            .ok()
            .filter(|l| (1..=MAX_LEVEL).contains(l))
            .ok_or_else(|| format!("'{item}': the level must be 1 to {MAX_LEVEL}"))?;
        if out.iter().any(|o| o.perturbation.name() == p.name()) {
            return Err(format!("'{name}' is given twice"));
        }
        out.push(Perturbed {
            perturbation: *p,
            level,
        });
    }
    if out.is_empty() {
        return Err("give at least one NAME:LEVEL".into());
    }
    let rank = |p: &Perturbed| {
        PERTURBATIONS
            .iter()
            .position(|q| q.name() == p.perturbation.name())
    };
    out.sort_by_key(rank);
    Ok(out)
}

/// Every perturbation's name.
pub fn names() -> Vec<&'static str> {
    PERTURBATIONS.iter().map(|p| p.name()).collect()
}

/// Mixed into the run's seed for the perturbations' streams (apart from the scene's).
const PERTURB_KEY: u64 = 0x005e_ed0f_07e2;

/// The streams of sample `index` of a run seeded `seed`: its own, and the one every clip
/// shares (static draws), both apart from the scene's draws and its pixel noise.
pub fn streams(seed: u64, index: usize) -> (ChaCha8Rng, ChaCha8Rng) {
    let mut own = ChaCha8Rng::seed_from_u64(seed ^ PERTURB_KEY);
    own.set_stream(index as u64);
    let mut fixed = ChaCha8Rng::seed_from_u64(seed ^ PERTURB_KEY);
    fixed.set_stream(u64::MAX);
    (own, fixed)
}

/// Applies `list` to `clip` (sample `index` of a run seeded `seed`).
pub fn apply_all(list: &[Perturbed], clip: &mut Clip, seed: u64, index: usize) {
    for (k, p) in list.iter().enumerate() {
        let (mut own, mut fixed) = streams(seed.wrapping_add(k as u64 * 7919), index);
        p.perturbation.apply(p.level, clip, &mut own, &mut fixed);
        for v in clip.frames.iter_mut() {
            *v = v.clamp(0.0, 1.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_in_order_and_bad_ones_are_refused() {
        let p = parse("noise:2, shake:3").unwrap();
        assert_eq!(format!("{p:?}"), "[shake:3, noise:2]");
        assert!(parse("shake:0").unwrap_err().contains("1 to 5"));
        assert!(parse("shake:6").unwrap_err().contains("1 to 5"));
        assert!(parse("wobble:1")
            .unwrap_err()
            .contains("not a perturbation"));
        assert!(parse("shake:1,shake:2").unwrap_err().contains("twice"));
        assert!(parse("shake").unwrap_err().contains("NAME:LEVEL"));
        let mut all = names();
        all.sort();
        all.dedup();
        assert_eq!(all.len(), PERTURBATIONS.len());
    }
}
