//! Buffer and image URIs: `data:` URIs decoded, relative paths resolved inside the level's
//! folder and read with a bounded length; absolute paths, `..` and other schemes refused.

use std::io::Read as _;
use std::path::{Path, PathBuf};

use base64::Engine as _;

/// Where a URI points.
#[derive(Debug, PartialEq)]
pub(crate) enum UriTarget {
    /// The bytes of a base64 `data:` URI.
    Data(Vec<u8>),
    /// A file inside the level's folder (or below it).
    File(PathBuf),
}

/// Resolves `uri` against `base_dir`; `Err` says why it is refused.
pub(crate) fn resolve(uri: &str, base_dir: &Path) -> Result<UriTarget, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest.split_once(";base64,").ok_or("data URI is not base64")?;
        return base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map(UriTarget::Data)
            .map_err(|e| format!("data URI is not valid base64: {e}"));
    }
    if let Some(scheme) = scheme(uri) {
        return Err(format!("`{scheme}:` URIs are not read, only paths relative to the level's folder"));
    }
    let decoded = percent_decode(uri);
    if decoded.is_empty() {
        return Err("empty path".into());
    }
    if decoded.contains('\0') {
        return Err("the path contains a NUL byte".into());
    }
    if decoded.starts_with('/') || decoded.starts_with('\\') {
        return Err("absolute paths are not read, only paths relative to the level's folder".into());
    }
    if decoded.split(['/', '\\']).any(|part| part == "..") {
        return Err("paths with `..` are not read: buffers must lie in the level's folder or below".into());
    }
    Ok(UriTarget::File(base_dir.join(decoded)))
}

/// The scheme of an absolute URI (`http`, `file`, a Windows drive letter...), if any.
fn scheme(uri: &str) -> Option<&str> {
    let (head, _) = uri.split_once(':')?;
    let mut chars = head.chars();
    let first = chars.next()?;
    (first.is_ascii_alphabetic() && chars.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c)))
        .then_some(head)
}

/// Why a file could not be read: an I/O error, or not a regular file, or too short.
pub(crate) enum FileReadError {
    Io(std::io::Error),
    NotAFile,
    TooShort { len: u64 },
}

/// Reads the first `length` bytes of the regular file `file`; allocates only once the
/// file is known to hold them.
pub(crate) fn read_prefix(file: &Path, length: u64) -> Result<Vec<u8>, FileReadError> {
    let meta = std::fs::metadata(file).map_err(FileReadError::Io)?;
    if !meta.is_file() {
        return Err(FileReadError::NotAFile);
    }
    if meta.len() < length {
        return Err(FileReadError::TooShort { len: meta.len() });
    }
    let size = usize::try_from(length).map_err(|_| FileReadError::TooShort { len: meta.len() })?;
    let mut out = Vec::with_capacity(size);
    std::fs::File::open(file)
        .and_then(|f| f.take(length).read_to_end(&mut out))
        .map_err(FileReadError::Io)?;
    if out.len() < size {
        return Err(FileReadError::TooShort { len: out.len() as u64 });
    }
    Ok(out)
}

/// Decodes `%XX` escapes of a relative URI (glTF URIs are RFC 3986).
fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%'
            && i + 2 < bytes.len()
            && let (Some(h), Some(l)) = (hex(bytes[i + 1]), hex(bytes[i + 2]))
        {
            out.push((h * 16 + l) as u8);
            i += 3;
            continue;
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decodes_percent_escapes() {
        assert_eq!(percent_decode("my%20level.bin"), "my level.bin");
        assert_eq!(percent_decode("plain.bin"), "plain.bin");
        assert_eq!(percent_decode("bad%2"), "bad%2");
        assert_eq!(percent_decode("end%41"), "endA");
    }

    fn check(uri: &str, expected: Result<&str, &str>) {
        let got = resolve(uri, Path::new("levels"));
        match (got, expected) {
            (Ok(UriTarget::File(p)), Ok(e)) => assert_eq!(p, Path::new("levels").join(e), "{uri}"),
            (Err(g), Err(e)) => assert!(g.contains(e), "{uri}: {g}"),
            (g, e) => panic!("{uri}: got {g:?}, expected {e:?}"),
        }
    }

    #[test]
    fn only_relative_paths_inside_the_folder_resolve() {
        check("level.bin", Ok("level.bin"));
        check("sub/level%20one.bin", Ok("sub/level one.bin"));
        check("a..b.bin", Ok("a..b.bin"));
        check("/dev/zero", Err("absolute"));
        check("%2Fdev%2Fzero", Err("absolute"));
        check("\\\\server\\share", Err("absolute"));
        check("../secret.bin", Err("`..`"));
        check("sub/../../x.bin", Err("`..`"));
        check("sub\\..\\..\\x.bin", Err("`..`"));
        check("%2E%2E/x.bin", Err("`..`"));
        check("file:///etc/passwd", Err("`file:`"));
        check("C:/Windows/x.bin", Err("`C:`"));
        check("https://example.org/x.bin", Err("`https:`"));
        check("", Err("empty"));
        check("a%00b", Err("NUL"));
        assert_eq!(
            resolve("data:application/octet-stream;base64,AQID", Path::new(".")),
            Ok(UriTarget::Data(vec![1, 2, 3]))
        );
        assert!(resolve("data:application/octet-stream,AQID", Path::new(".")).is_err());
    }

    #[test]
    fn reads_only_regular_files_and_only_what_is_declared() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("b.bin");
        std::fs::write(&file, [1u8, 2, 3, 4, 5]).unwrap();
        assert_eq!(read_prefix(&file, 3).ok(), Some(vec![1, 2, 3]));
        assert!(matches!(read_prefix(&file, 6), Err(FileReadError::TooShort { len: 5 })));
        assert!(matches!(read_prefix(dir.path(), 0), Err(FileReadError::NotAFile)));
        if Path::new("/dev/zero").exists() {
            assert!(matches!(read_prefix(Path::new("/dev/zero"), 1 << 40), Err(FileReadError::NotAFile)));
        }
        assert!(matches!(read_prefix(&dir.path().join("none"), 1), Err(FileReadError::Io(_))));
    }
}
