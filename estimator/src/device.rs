//! Where to train: `--device` and the CPU threads (`cpu_threads`), with libtorch's CUDA half
//! opened on demand. `estimate` is not linked against libtorch_cuda (loading it and its CUDA
//! libraries costs 0.35 s and 400 MB on every run); when an NVIDIA driver is present it is
//! opened here, before anything asks libtorch about CUDA (ATen disables CUDA for good if asked
//! before the library is loaded).

use crate::error::EstimateError;
use serde::Serialize;
use std::path::Path;
use std::sync::OnceLock;
use tch::Device;

/// Where to train.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum, Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum DeviceChoice {
    /// CUDA when libtorch sees a GPU, else CPU.
    #[default]
    Auto,
    Cpu,
    Cuda,
}

/// The CPU threads a run uses: libtorch's, and the pool that the track's readings and the
/// shooting fits run on (the first run of a process sizes it; later ones find it made).
pub fn cpu_threads(threads: usize) {
    tch::set_num_threads(threads as i32);
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global();
}

/// libtorch's library directory, recorded at build time.
const LIBTORCH_LIB: &str = env!("PHYSVID_LIBTORCH_LIB");

/// Whether an NVIDIA driver is loaded on this machine.
fn nvidia_driver() -> bool {
    Path::new("/proc/driver/nvidia/version").exists() || Path::new("/dev/nvidiactl").exists()
}

/// Opens libtorch_cuda (once per process); the error says what failed.
fn open_cuda_backend() -> &'static Result<(), String> {
    static OPENED: OnceLock<Result<(), String>> = OnceLock::new();
    OPENED.get_or_init(|| {
        #[cfg(unix)]
        {
            use libloading::os::unix::{Library, RTLD_GLOBAL, RTLD_NOW};
            let mut last = String::from("no libtorch directory known");
            for path in [
                Path::new(LIBTORCH_LIB).join("libtorch_cuda.so"),
                "libtorch_cuda.so".into(),
            ] {
                // SAFETY: loading a library of the libtorch installation the program was built
                // against; its initialisers register the CUDA backend and nothing else.
                match unsafe { Library::open(Some(&path), RTLD_NOW | RTLD_GLOBAL) } {
                    Ok(lib) => {
                        // Kept for the life of the process: its kernels are registered.
                        std::mem::forget(lib);
                        return Ok(());
                    }
                    Err(e) => last = e.to_string(),
                }
            }
            Err(last)
        }
        #[cfg(not(unix))]
        {
            Err("opening libtorch_cuda at run time is implemented for Unix only".into())
        }
    })
}

/// Resolves `--device`, and a warning when a GPU seems present but cannot be used.
pub fn select_device(choice: DeviceChoice) -> Result<(Device, Option<String>), EstimateError> {
    if choice == DeviceChoice::Cpu {
        return Ok((Device::Cpu, None));
    }
    let driver = nvidia_driver();
    let opened = if driver {
        open_cuda_backend().clone()
    } else {
        Err("no NVIDIA driver on this machine".into())
    };
    let available = opened.is_ok() && tch::Cuda::is_available();
    match (choice, available) {
        (_, true) => Ok((Device::Cuda(0), None)),
        (DeviceChoice::Cuda, false) => Err(EstimateError::NoCuda),
        _ if driver => Ok((
            Device::Cpu,
            Some(format!(
                "an NVIDIA driver is present but libtorch's CUDA backend is unavailable ({}); \
                 training on the CPU",
                opened
                    .err()
                    .unwrap_or_else(|| "libtorch sees no GPU".into())
            )),
        )),
        _ => Ok((Device::Cpu, None)),
    }
}
