//! The generator's output in memory: the `.glb` bytes (packed by `gltf::binary::Glb`) and
//! the ground-truth JSON text.

use std::path::Path;

use anyhow::{Context, Result};

use crate::demo_room::build_demo_room;
use crate::ground_truth::expected_level;
use crate::json_layout::inline_number_arrays;

/// File name of the level inside `assets/`.
pub const LEVEL_FILE: &str = "demo_room.glb";
/// File name of the ground truth inside `assets/`.
pub const EXPECTED_FILE: &str = "demo_room.expected.json";

/// Both generated files, byte for byte.
pub struct GeneratedLevel {
    pub glb: Vec<u8>,
    pub expected_json: String,
}

impl GeneratedLevel {
    /// Builds the demo room; the same bytes on every run and every platform.
    pub fn generate() -> Result<Self> {
        let room = build_demo_room();
        let (document, bin) = room.builder.to_document("demo_room");
        let json = serde_json::to_vec(&document).context("serialising the glTF document")?;
        let expected = expected_level(&room.builder, LEVEL_FILE, &room.reflectors, &room.non_reflectors)?;
        let pretty = serde_json::to_string_pretty(&expected).context("serialising the ground truth")?;
        let glb = gltf::binary::Glb {
            header: gltf::binary::Header { magic: *b"glTF", version: 2, length: 0 },
            json: json.into(),
            bin: Some(bin.into()),
        };
        let glb = glb.to_vec().context("packing the GLB container")?;
        Ok(Self { glb, expected_json: inline_number_arrays(&pretty) })
    }

    /// Writes `demo_room.glb` and `demo_room.expected.json` into `directory`.
    pub fn write_to(&self, directory: &Path) -> Result<()> {
        std::fs::create_dir_all(directory).with_context(|| format!("creating {}", directory.display()))?;
        let level = directory.join(LEVEL_FILE);
        std::fs::write(&level, &self.glb).with_context(|| format!("writing {}", level.display()))?;
        let expected = directory.join(EXPECTED_FILE);
        std::fs::write(&expected, &self.expected_json)
            .with_context(|| format!("writing {}", expected.display()))?;
        Ok(())
    }
}
