//! Atomic file writes that keep what the user set up: the bytes go to a temporary file
//! beside the file's real location (a symlink is followed to its target, so the link stays
//! a link), the old file's permissions are given to the new one (a new file gets the umask
//! default, as any program's), and a rename puts it in place.

use std::fs::{self, Permissions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Symbolic links followed before giving up (Linux's `ELOOP` limit).
const MAX_SYMLINKS: usize = 40;

/// Writes `bytes` to `path` through a temporary file beside it and a rename. When `path`
/// is a symbolic link (or a chain of them), its final target is written and the links are
/// left as they are; the file keeps its permissions, and a new file gets the umask default
/// (`0666 & !umask`, so 0644 under the usual 022).
///
/// # Errors
/// Any I/O error, or a loop of symbolic links; the temporary file is removed and the file
/// is untouched.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let target = final_target(path)?;
    let dir = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let old_permissions = match fs::metadata(&target) {
        Ok(meta) => Some(meta.permissions()),
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return Err(e),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".ppr-").suffix(".tmp");
    #[cfg(unix)]
    builder.permissions(new_file_permissions());
    let mut tmp = builder.tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    if let Some(permissions) = old_permissions {
        tmp.as_file().set_permissions(permissions)?;
    }
    tmp.as_file().sync_all()?;
    tmp.persist(&target).map_err(|e| e.error)?;
    Ok(())
}

/// Where `path` really is: itself, or the file at the end of its chain of symbolic links
/// (which need not exist yet). Relative link targets are relative to the link's folder.
fn final_target(path: &Path) -> io::Result<PathBuf> {
    let mut current = path.to_owned();
    for _ in 0..MAX_SYMLINKS {
        match fs::symlink_metadata(&current) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = fs::read_link(&current)?;
                current = match current.parent() {
                    Some(folder) => folder.join(link),
                    None => link,
                };
            }
            _ => return Ok(current),
        }
    }
    Err(io::Error::other(format!("{}: too many levels of symbolic links", path.display())))
}

/// What a new file is created with before the umask: read and write for everyone, as
/// `open(2)` callers and shells do.
#[cfg(unix)]
fn new_file_permissions() -> Permissions {
    use std::os::unix::fs::PermissionsExt;
    Permissions::from_mode(0o666)
}

#[cfg(all(test, unix))]
mod tests {
    use std::os::unix::fs::{PermissionsExt, symlink};

    use super::*;

    fn mode(path: &Path) -> u32 {
        fs::metadata(path).expect("metadata").permissions().mode() & 0o777
    }

    #[test]
    fn the_file_keeps_its_mode() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("set.ppr.json");
        for wanted in [0o644, 0o664, 0o640, 0o444] {
            fs::write(&path, "old").expect("written");
            fs::set_permissions(&path, Permissions::from_mode(wanted)).expect("chmod");
            write_atomically(&path, b"new").expect("saved");
            assert_eq!(fs::read_to_string(&path).expect("read"), "new");
            assert_eq!(mode(&path), wanted, "mode {wanted:o} kept");
        }
    }

    #[test]
    fn a_new_file_gets_the_umask_default_not_0600() {
        let dir = tempfile::tempdir().expect("temp dir");
        // What the process's umask makes of 0666, from a file created the ordinary way.
        let probe = dir.path().join("probe");
        fs::write(&probe, "").expect("probe written");
        let path = dir.path().join("new.ppr.json");
        write_atomically(&path, b"new").expect("saved");
        assert_eq!(mode(&path), mode(&probe));
        assert_ne!(mode(&path) & 0o044, 0, "readable by others under any usual umask");
    }

    #[test]
    fn a_symlink_stays_a_link_and_its_target_is_written() {
        let dir = tempfile::tempdir().expect("temp dir");
        let real_dir = dir.path().join("shared");
        fs::create_dir(&real_dir).expect("folder");
        let target = real_dir.join("level.ppr.json");
        fs::write(&target, "old").expect("written");
        fs::set_permissions(&target, Permissions::from_mode(0o664)).expect("chmod");
        // A relative link, and a link to that link.
        let link = dir.path().join("level.ppr.json");
        symlink("shared/level.ppr.json", &link).expect("link");
        let link_to_link = dir.path().join("alias.ppr.json");
        symlink(&link, &link_to_link).expect("link to link");

        write_atomically(&link_to_link, b"new").expect("saved");
        for l in [&link, &link_to_link] {
            assert!(
                fs::symlink_metadata(l).expect("lstat").file_type().is_symlink(),
                "{} still a link",
                l.display()
            );
        }
        assert_eq!(fs::read_to_string(&target).expect("read"), "new");
        assert_eq!(mode(&target), 0o664);
        let leftovers: Vec<_> =
            fs::read_dir(&real_dir).expect("list").map(|e| e.expect("entry").file_name()).collect();
        assert_eq!(leftovers, ["level.ppr.json"], "no temporary file is left beside the target");
    }

    #[test]
    fn a_dangling_link_creates_its_target_and_a_loop_is_an_error() {
        let dir = tempfile::tempdir().expect("temp dir");
        let link = dir.path().join("set.ppr.json");
        symlink("elsewhere.ppr.json", &link).expect("link");
        write_atomically(&link, b"new").expect("saved");
        assert_eq!(fs::read_to_string(dir.path().join("elsewhere.ppr.json")).expect("read"), "new");

        let (a, b) = (dir.path().join("a"), dir.path().join("b"));
        symlink(&b, &a).expect("a -> b");
        symlink(&a, &b).expect("b -> a");
        let e = write_atomically(&a, b"new").expect_err("a loop");
        assert!(e.to_string().contains("symbolic links"), "{e}");
    }
}
