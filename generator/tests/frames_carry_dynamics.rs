//! The rendered frames carry the dynamics, shown without learning: a per-frame statistic that
//! is affine in z, fitted with the exact two-step recurrence, gives back γ0 and γ1 within 0.5 %.

use generator::{generate, GenConfig, SceneRef};
use physvid_shared::recurrence::fit_two_step_recurrence;

fn config(scenario: &str, size: usize, dt: f64, omega: f64, zeta: f64) -> GenConfig {
    let mut cfg = GenConfig {
        size,
        dt,
        seed: 3,
        ..GenConfig::new(SceneRef::by_name(scenario).unwrap(), "unused")
    };
    cfg.params.insert("omega".into(), omega);
    cfg.params.insert("zeta".into(), zeta);
    cfg.validate().unwrap()
}

/// Mean brightness (intensity), centroid along x (position), √(total brightness) (scale).
fn statistic(scenario: &str, frame: &[f32], size: usize) -> f64 {
    let mass: f64 = frame.iter().map(|&v| v as f64).sum();
    match scenario {
        "intensity" => mass / frame.len() as f64,
        "position" => {
            frame
                .iter()
                .enumerate()
                .map(|(i, &v)| (i % size) as f64 * v as f64)
                .sum::<f64>()
                / mass
        }
        "scale" => mass.sqrt(),
        other => unreachable!("{other} is not an oscillator scene"),
    }
}

fn check(cfg: &GenConfig) {
    let g = generate(cfg);
    let pixels = cfg.size * cfg.size;
    let series: Vec<Vec<f64>> = g
        .frames
        .chunks_exact(cfg.frames * pixels)
        .map(|clip| {
            clip.chunks_exact(pixels)
                .map(|f| statistic(cfg.scene.name(), f, cfg.size))
                .collect()
        })
        .collect();
    let fit = fit_two_step_recurrence(series.iter().map(Vec::as_slice)).unwrap();
    let (g0, g1) = fit.gammas(cfg.dt).expect("under-damped fit");
    let (omega, zeta) = (cfg.params["omega"], cfg.params["zeta"]);
    let (t0, t1) = (omega.powi(2) + zeta.powi(2), 2.0 * zeta);
    let (e0, e1) = ((g0 / t0 - 1.0).abs(), (g1 / t1 - 1.0).abs());
    eprintln!(
        "{} size {} dt {}: γ0 {g0:.5} (truth {t0:.5}, {:.3} %), γ1 {g1:.5} (truth {t1:.5}, {:.3} %)",
        cfg.scene,
        cfg.size,
        cfg.dt,
        e0 * 100.0,
        e1 * 100.0
    );
    assert!(e0 < 0.005, "{}: γ0 {g0} vs {t0}", cfg.scene);
    assert!(e1 < 0.005, "{}: γ1 {g1} vs {t1}", cfg.scene);
}

#[test]
fn default_sets_carry_the_paper_dynamics() {
    for sc in ["intensity", "position", "scale"] {
        check(&config(sc, 50, 0.2, 2.0, 0.04));
    }
}

#[test]
fn non_default_sets_carry_their_dynamics() {
    for sc in ["intensity", "position", "scale"] {
        check(&config(sc, 64, 0.1, 3.0, 0.15));
    }
}
