//! The allocator's settings for `estimate`: freed memory is kept for reuse rather than handed
//! back to the system.
//!
//! libtorch takes its tensors from glibc's malloc, which serves every block above 32 MiB by a
//! fresh mmap and unmaps it when freed: a training step's large activations (the spring's
//! keypoint encoder makes blocks of about 200 MB) were then page-faulted in anew at every step.
//! Measured on the 2-core machine: a quarter of the spring's time in the kernel clearing pages;
//! with the heap kept, its epochs 35 % faster and the shared pendulum recording 30 % (39.7 →
//! 27.9 s) for 20 % more peak memory (1.64 → 1.98 GB), every answer identical.

/// Serves large blocks from the heap and never trims it (glibc only; elsewhere nothing).
pub fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets allocator parameters; called first thing in main, before any
    // other thread exists.
    unsafe {
        libc::mallopt(libc::M_MMAP_MAX, 0);
        libc::mallopt(libc::M_TRIM_THRESHOLD, i32::MAX);
    }
}
