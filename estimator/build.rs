//! Links libtorch so `estimate` runs without LD_LIBRARY_PATH (an rpath to libtorch's directory),
//! and records that directory and libtorch's version for the program: libtorch_cuda (with its
//! CUDA libraries, 0.35 s and 400 MB to load) is not linked but opened at run time when a GPU
//! driver is present (`run::select_device`).

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let lib = std::env::var_os("DEP_TCH_LIBTORCH_LIB");
    if os == "linux" || os == "windows" {
        if let Some(lib) = &lib {
            println!("cargo:rustc-link-arg=-Wl,-rpath={}", lib.to_string_lossy());
        }
    }
    println!(
        "cargo:rustc-env=PHYSVID_LIBTORCH_LIB={}",
        lib.as_ref()
            .map(|l| l.to_string_lossy().into_owned())
            .unwrap_or_default()
    );
    // The PyTorch wheel keeps its version in torch/version.py; a libtorch zip in build-version.
    let version = lib
        .map(std::path::PathBuf::from)
        .and_then(|l| l.parent().map(|p| p.to_path_buf()))
        .and_then(|root| {
            std::fs::read_to_string(root.join("version.py"))
                .ok()
                .and_then(|text| {
                    text.lines()
                        .find_map(|l| l.strip_prefix("__version__ = "))
                        .map(|v| v.trim_matches(|c| c == '\'' || c == '"').to_string())
                })
                .or_else(|| {
                    std::fs::read_to_string(root.join("build-version"))
                        .ok()
                        .map(|s| s.trim().to_string())
                })
        })
        .unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=PHYSVID_LIBTORCH_VERSION={version}");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=LIBTORCH");
}
