//! The `ppr-extract` binary: output file, summary, exit codes and one-line errors.

use std::path::Path;
use std::process::Command;

use crate::scenes::scenes_dir;

fn run(args: &[&std::ffi::OsStr]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_ppr-extract")).args(args).output().expect("run ppr-extract");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn os(s: &Path) -> &std::ffi::OsStr {
    s.as_os_str()
}

/// Asserts exit `code` and a single error line containing `needle`.
fn assert_error(args: &[&std::ffi::OsStr], code: i32, needle: &str) {
    let (c, _, err) = run(args);
    assert_eq!(c, code, "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
}

#[test]
fn writes_the_default_output_and_prints_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("small.glb");
    std::fs::copy(scenes_dir().join("small.glb"), &input).unwrap();
    let (code, out, err) = run(&[os(&input)]);
    assert_eq!(code, 0, "{err}");
    for needle in
        ["shapes", "total area", "mean coverage", "occluder pairs", "triangles/s", "occluders", "write"]
    {
        assert!(out.contains(needle), "summary lacks {needle}: {out}");
    }
    let written = dir.path().join("small.ppr.json");
    let set = ppr_format::ReflectorSet::load(&written).unwrap();
    assert!(!set.reflectors.is_empty());
    assert!(set.source.hash.starts_with("blake3:"));
    assert_eq!(set.extractor.name, "ppr-extract");
    // Same input, same bytes.
    let first = std::fs::read(&written).unwrap();
    let (code, _, _) = run(&[os(&input), "--quiet".as_ref()]);
    assert_eq!(code, 0);
    assert_eq!(std::fs::read(&written).unwrap(), first);
}

#[test]
fn exit_codes_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    assert_error(&[os(&d.join("nope.glb"))], 2, "nope.glb: cannot read");
    std::fs::write(d.join("photo.glb"), b"\x89PNG\r\n\x1a\n....").unwrap();
    assert_error(&[os(&d.join("photo.glb"))], 2, "not a glTF file");
    let glb = std::fs::read(scenes_dir().join("small.glb")).unwrap();
    std::fs::write(d.join("cut.glb"), &glb[..glb.len() / 2]).unwrap();
    assert_error(&[os(&d.join("cut.glb"))], 2, "truncated .glb");
    std::fs::copy(scenes_dir().join("kitchen/kitchen.gltf"), d.join("kitchen.gltf")).unwrap();
    assert_error(&[os(&d.join("kitchen.gltf"))], 2, "kitchen.bin");
    let mut json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(scenes_dir().join("kitchen/kitchen.gltf")).unwrap()).unwrap();
    json["extensionsRequired"] = serde_json::json!(["KHR_draco_mesh_compression"]);
    std::fs::write(d.join("draco.gltf"), serde_json::to_vec(&json).unwrap()).unwrap();
    assert_error(&[os(&d.join("draco.gltf"))], 2, "KHR_draco_mesh_compression");
    // Hostile sizes, URIs and coordinates: exit 2 with the file and field named, never an abort.
    let floor = || {
        let mut b = ppr_level::gltf_builder::GltfBuilder::new();
        let m = b.material("m", 0.1, 0.0, None);
        let (p, i) = ppr_level::gltf_builder::quad_xz(0.0, 0.0, 1.0, 1.0, 0.0);
        let mesh = b.mesh("floor", &p, &i, m, ppr_level::gltf_builder::PositionFormat::F32);
        b.node("n", mesh, [0.0; 3], [0.0, 0.0, 0.0, 1.0], [1.0; 3]);
        b
    };
    type Edit = fn(&mut serde_json::Value);
    let hostile: [(&str, Edit, &str); 4] = [
        (
            "count.glb",
            |j| j["accessors"][0]["count"] = serde_json::json!(1u64 << 60),
            "accessors[0] is out of range",
        ),
        (
            "offset.glb",
            |j| j["accessors"][0]["byteOffset"] = serde_json::json!(1u64 << 62),
            "accessors[0] is out of range",
        ),
        (
            "uri.glb",
            |j| j["buffers"] = serde_json::json!([{"byteLength": 64, "uri": "/dev/zero"}]),
            "buffers[0]: uri `/dev/zero` refused",
        ),
        (
            "far.glb",
            |j| j["nodes"][0]["translation"] = serde_json::json!([0.0, 0.0, 3.0e7]),
            "nodes[0] (\"n\")",
        ),
    ];
    for (name, edit, needle) in hostile {
        let mut b = floor();
        if name == "uri.glb" {
            // The URI replaces the BIN chunk: a .gltf beside nothing.
            let path = d.join("uri.gltf");
            let written = b.write_gltf(d, "uri").unwrap();
            let mut json: serde_json::Value =
                serde_json::from_slice(&std::fs::read(&written).unwrap()).unwrap();
            edit(&mut json);
            std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
            assert_error(&[os(&path)], 2, needle);
            continue;
        }
        edit(&mut b.json);
        std::fs::write(d.join(name), b.glb()).unwrap();
        assert_error(&[os(&d.join(name))], 2, needle);
    }
    // Usage errors.
    let (code, _, err) = run(&[]);
    assert_eq!(code, 1, "{err}");
    let (code, _, _) =
        run(&[os(&scenes_dir().join("small.glb")), "--angle-tolerance".as_ref(), "-3".as_ref()]);
    assert_eq!(code, 1);
    // Output that cannot be written: a directory that does not exist; nothing is left.
    let target = d.join("missing-dir").join("out.ppr.json");
    assert_error(&[os(&scenes_dir().join("small.glb")), "-o".as_ref(), os(&target)], 3, "cannot write");
    assert!(!target.exists());
    // --help documents the exit codes.
    let (code, out, _) = run(&["--help".as_ref()]);
    assert_eq!(code, 0);
    assert!(out.contains("EXIT CODES") && out.contains("--all-planar") && out.contains("EXAMPLES"), "{out}");
    for option in
        ["UNITS", "--unit", "--max-per-cube", "--near-planar-angle", "--max-occluders", "[default: 0.005]"]
    {
        assert!(out.contains(option), "--help lacks {option}: {out}");
    }
    // The density budget from the command line, and its note.
    let target = d.join("budget.ppr.json");
    let (code, out, err) = run(&[
        os(&scenes_dir().join("small.glb")),
        "-o".as_ref(),
        os(&target),
        "--max-per-cube".as_ref(),
        "1".as_ref(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("density budget (1 rectangles per 10 m cube"), "{out}");
}

/// Re-extracting over a symlinked set writes the link's target, keeps the link and the
/// file's mode (the atomic save used to leave a plain 0600 file in the link's place).
#[cfg(unix)]
#[test]
fn writing_over_a_symlinked_set_keeps_the_link_and_the_mode() {
    use std::os::unix::fs::{PermissionsExt, symlink};
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("small.glb");
    std::fs::copy(scenes_dir().join("small.glb"), &input).unwrap();
    let shared = dir.path().join("shared");
    std::fs::create_dir(&shared).unwrap();
    let target = shared.join("small.ppr.json");
    std::fs::write(&target, "old").unwrap();
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o664)).unwrap();
    let link = dir.path().join("small.ppr.json");
    symlink(&target, &link).unwrap();

    let (code, _, err) = run(&[os(&input), "--quiet".as_ref()]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "still a link");
    assert!(ppr_format::ReflectorSet::load(&target).is_ok(), "the target holds the new set");
    assert_eq!(std::fs::metadata(&target).unwrap().permissions().mode() & 0o777, 0o664);
}
