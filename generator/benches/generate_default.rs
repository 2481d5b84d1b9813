//! Benchmark: render and write the default 500×20×1×50×50 set; prints wall times and the
//! speed-up of all threads over one thread, measured in the same process.
//! Run with `cargo bench -p physvid-generator --bench generate_default`.

use generator::{generate, generate_to_disk, GenConfig, SceneRef};
use std::time::Instant;

fn config(scenario: &str, out: std::path::PathBuf) -> GenConfig {
    GenConfig {
        force: true,
        ..GenConfig::new(SceneRef::by_name(scenario).unwrap(), out)
    }
    .validate()
    .expect("defaults are valid")
}

/// Best of `reps` wall times of `f`, in seconds.
fn best_of(reps: usize, mut f: impl FnMut()) -> f64 {
    (0..reps)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let tmp = tempfile::tempdir().expect("temporary directory");
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let all = rayon::ThreadPoolBuilder::new()
        .num_threads(cores)
        .build()
        .unwrap();
    println!("gen benchmark: default 500×20×1×50×50 set (100 MB), best of 5, {cores} cores");
    println!(
        "{:<10} {:>12} {:>12} {:>12} {:>12}",
        "scenario", "render 1T", "render all", "render+write", "speed-up"
    );
    for sc in ["intensity", "position", "scale"] {
        let cfg = config(sc, tmp.path().join(sc));
        let r1 = best_of(5, || {
            one.install(|| std::hint::black_box(generate(&cfg)));
        });
        let rn = best_of(5, || {
            all.install(|| std::hint::black_box(generate(&cfg)));
        });
        let full1 = best_of(3, || {
            one.install(|| generate_to_disk(&cfg).unwrap());
        });
        let fulln = best_of(5, || {
            all.install(|| generate_to_disk(&cfg).unwrap());
        });
        println!(
            "{:<10} {:>10.3} s {:>10.3} s {:>10.3} s {:>11.2}x   (render+write on 1 thread: {:.3} s)",
            sc, r1, rn, fulln, full1 / fulln, full1
        );
    }
}
