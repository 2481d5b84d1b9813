//! The verdict's constructed failures, shared by `estimate`'s end-to-end tests and
//! `reproduce verdict`: a data set's frames shuffled within each clip, or each clip's first
//! frame held still with sensor noise or under a flickering light, each from its own seeded
//! ChaCha8 source, so both draw the same frames.

use physvid_shared::npy::{read_npy, write_npy};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use std::path::Path;

/// A constructed failure of a data set's clips.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Failure {
    /// Every clip's frames in a random order.
    Shuffled,
    /// Every clip's first frame repeated, with Gaussian sensor noise of σ 0.05.
    StillWithNoise,
    /// Every clip's first frame repeated under a gain drawn from 0.8–1.2 per frame.
    StillUnderFlicker,
}

impl Failure {
    /// Applies the failure to clips `x` of `t` frames of `px` values each.
    pub fn apply(self, t: usize, px: usize, x: &mut [f32]) {
        match self {
            Failure::Shuffled => {
                let mut rng = ChaCha8Rng::seed_from_u64(1);
                for clip in x.chunks_mut(t * px) {
                    let mut order: Vec<usize> = (0..t).collect();
                    order.shuffle(&mut rng);
                    let before = clip.to_vec();
                    for (k, &from) in order.iter().enumerate() {
                        clip[k * px..(k + 1) * px]
                            .copy_from_slice(&before[from * px..(from + 1) * px]);
                    }
                }
            }
            Failure::StillWithNoise => {
                let (mut rng, sensor) = (
                    ChaCha8Rng::seed_from_u64(2),
                    Normal::new(0.0f32, 0.05).expect("a valid σ"),
                );
                held(t, px, x, |first| first + sensor.sample(&mut rng));
            }
            Failure::StillUnderFlicker => {
                let mut rng = ChaCha8Rng::seed_from_u64(3);
                for clip in x.chunks_mut(t * px) {
                    for k in 1..t {
                        let gain: f32 = rng.random_range(0.8..1.2);
                        for p in 0..px {
                            clip[k * px + p] = clip[p] * gain;
                        }
                    }
                }
            }
        }
    }

    /// The frames of the data set in `data` (its frames.npy) with this failure, written as a
    /// bare `.npy` at `to`.
    pub fn write(self, data: &Path, to: &Path) -> std::io::Result<()> {
        let mut a = read_npy(&data.join("frames.npy")).map_err(std::io::Error::other)?;
        let pixels: usize = a.shape[2..].iter().product();
        self.apply(a.shape[1], pixels, &mut a.data);
        write_npy(std::fs::File::create(to)?, &a.shape, &a.data)
    }
}

/// Every clip's frames after the first replaced by `value` of the first frame's pixel.
fn held(t: usize, px: usize, x: &mut [f32], mut value: impl FnMut(f32) -> f32) {
    for clip in x.chunks_mut(t * px) {
        for k in 1..t {
            for p in 0..px {
                clip[k * px + p] = value(clip[p]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shuffling_keeps_each_clips_frames_and_moves_some() {
        let (t, px) = (6, 2);
        let x0: Vec<f32> = (0..3 * t * px).map(|v| v as f32).collect();
        let mut x = x0.clone();
        Failure::Shuffled.apply(t, px, &mut x);
        assert_ne!(x, x0);
        for (a, b) in x.chunks(t * px).zip(x0.chunks(t * px)) {
            let (mut a, mut b) = (a.to_vec(), b.to_vec());
            a.sort_by(f32::total_cmp);
            b.sort_by(f32::total_cmp);
            assert_eq!(a, b);
        }
    }

    #[test]
    fn held_scenes_repeat_the_first_frame_up_to_noise_or_gain() {
        let (t, px) = (5, 3);
        let x0: Vec<f32> = (0..2 * t * px).map(|v| 1.0 + v as f32).collect();
        for failure in [Failure::StillWithNoise, Failure::StillUnderFlicker] {
            let mut x = x0.clone();
            failure.apply(t, px, &mut x);
            for clip in x.chunks(t * px) {
                for k in 1..t {
                    for p in 0..px {
                        let r = clip[k * px + p] / clip[p];
                        assert!((0.7..1.3).contains(&r), "{failure:?}: {r}");
                    }
                }
            }
        }
    }
}
