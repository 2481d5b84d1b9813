//! Output folders: this tool writes only into a folder it owns, and removes or replaces only
//! what it wrote there. A folder it creates (or finds empty) is marked by a manifest
//! (`manifest.rs`) listing what it wrote; an existing folder without that mark that holds
//! anything (`.`, a home folder, a user's project) is refused before any work unless the user
//! passes `--force`, and even then nothing of another name is touched. A file under one of the
//! tool's names that is not the tool's (put there or edited by someone, or a link) is refused
//! the same way. Files are written under random temporary names and renamed (`atomic`), links
//! are never written through, the folder is locked while it is written (on the folder itself,
//! no lock file), and a folder this run created and never filled is removed again.

mod check;
mod dir;
mod error;
mod manifest;

pub use check::{adopt, check};
pub use dir::{OutputDir, Wait};
pub use error::OutputError;
pub use manifest::{Identity, Manifest, MANIFEST};
