//! A data set held in memory (`generate_in_memory`): every clip rendered at once, with the
//! meta.json and preview `generate_to_disk` would write, refused alike; written on demand
//! (`InMemory::save`) into the same bytes as `gen` writes.

use crate::config::GenConfig;
use crate::generate::generate;
use crate::write::{dataset_meta, preview_png, refused};
use physvid_shared::{DatasetFiles, DatasetMeta, DatasetWriter};
use std::path::Path;

/// A rendered data set: its frames `[N, T, C, H, W]` row-major, its meta.json and preview.png.
#[derive(Debug, Clone)]
pub struct InMemory {
    pub frames: Vec<f32>,
    pub meta: DatasetMeta,
    pub preview: Vec<u8>,
}

/// Renders the data set `cfg` describes into memory (its `out` is not written); a data set
/// `generate_to_disk` refuses is refused with the same message.
pub fn generate_in_memory(cfg: &GenConfig) -> anyhow::Result<InMemory> {
    let g = generate(cfg);
    refused(cfg, g.still, g.overflow)?;
    let [_, t, c, h, w] = cfg.shape();
    let first = cfg.samples.min(4) * t * c * h * w;
    let preview = preview_png(cfg, &g.frames[..first]);
    let meta = dataset_meta(cfg, &g);
    Ok(InMemory {
        frames: g.frames,
        meta,
        preview,
    })
}

impl InMemory {
    /// Writes the data set into `dir` as `gen --out DIR` does (`force`: into a folder this
    /// tool did not make); nothing half-written stays after a failure.
    pub fn save(&self, dir: &Path, force: bool) -> anyhow::Result<DatasetFiles> {
        let shape: [usize; 5] = self.meta.shape;
        let mut writer = DatasetWriter::create(dir, shape, force)?;
        writer.write_frames(&self.frames)?;
        Ok(writer.finish(&self.meta, &self.preview)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{generate_to_disk, SceneRef};

    #[test]
    fn saved_it_is_the_data_set_gen_writes_to_the_byte() {
        let dir = tempfile::tempdir().unwrap();
        let mut cfg = GenConfig::new(SceneRef::by_name("pendulum").unwrap(), dir.path().join("a"));
        (cfg.samples, cfg.size, cfg.seed) = (6, 16, 3);
        let cfg = cfg.validate().unwrap();
        generate_to_disk(&cfg).unwrap();
        let data = generate_in_memory(&cfg).unwrap();
        data.save(&dir.path().join("b"), false).unwrap();
        for file in ["frames.npy", "meta.json", "preview.png"] {
            let a = std::fs::read(dir.path().join("a").join(file)).unwrap();
            let b = std::fs::read(dir.path().join("b").join(file)).unwrap();
            assert!(a == b, "{file} differs");
        }
    }

    #[test]
    fn a_data_set_refused_on_disk_is_refused_in_memory() {
        let dir = tempfile::tempdir().unwrap();
        for (scene, name, value) in [("led", "gamma", 1e-9), ("pendulum", "damping", 1e6)] {
            let out = dir.path().join("a");
            let mut cfg = GenConfig::new(SceneRef::by_name(scene).unwrap(), &out);
            cfg.samples = 4;
            cfg.params.insert(name.into(), value);
            let cfg = cfg.validate().unwrap();
            let disk = generate_to_disk(&cfg)
                .map(|_| ())
                .map_err(|e| e.to_string());
            let memory = generate_in_memory(&cfg)
                .map(|_| ())
                .map_err(|e| e.to_string());
            assert!(disk.is_err(), "{scene}: refused");
            assert_eq!(disk, memory, "{scene}");
            assert!(!out.exists(), "{scene}: nothing written");
        }
    }
}
