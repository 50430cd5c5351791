//! Buffer bytes: the `.glb` BIN chunk, external files, `data:` URIs, and buffer views
//! (including those decoded from `EXT_meshopt_compression`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use gltf::Document;

use crate::LoadError;
use crate::meshopt_views::decode_meshopt_view;
use crate::uri::{self, FileReadError, UriTarget};

/// The bytes of every buffer, and of every meshopt-compressed buffer view once decoded.
pub(crate) struct BufferData {
    path: PathBuf,
    /// `None` for a buffer without data (a meshopt fallback buffer).
    buffers: Vec<Option<Vec<u8>>>,
    decoded_views: BTreeMap<usize, Vec<u8>>,
}

/// The bytes a buffer view covers and its stride.
pub(crate) struct ViewBytes<'a> {
    pub bytes: &'a [u8],
    pub stride: Option<usize>,
}

impl BufferData {
    /// Reads every buffer of `doc` (resolving URIs against `base_dir`) and decodes the
    /// compressed buffer views.
    pub(crate) fn load(
        path: &Path,
        doc: &Document,
        bin: Option<&[u8]>,
        base_dir: &Path,
    ) -> Result<Self, LoadError> {
        let mut buffers = Vec::new();
        for buffer in doc.buffers() {
            let index = buffer.index();
            let declared = buffer.length();
            let bad = |reason: String| LoadError::BadBuffer { path: path.to_owned(), index, reason };
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => match bin {
                    Some(b) => Some(b.to_vec()),
                    None if is_meshopt_fallback(&buffer) => None,
                    None => return Err(bad("has no `uri` and the file has no .glb BIN chunk".into())),
                },
                gltf::buffer::Source::Uri(uri) => Some(read_uri(path, index, uri, declared, base_dir)?),
            };
            if let Some(data) = &data
                && data.len() < declared
            {
                return Err(bad(format!(
                    "byteLength is {declared} but only {} bytes are there (truncated?)",
                    data.len()
                )));
            }
            buffers.push(data);
        }
        let mut out = Self { path: path.to_owned(), buffers, decoded_views: BTreeMap::new() };
        for view in doc.views() {
            if let Some(ext) = view.extension_value("EXT_meshopt_compression") {
                let decoded = decode_meshopt_view(path, view.index(), ext, |b| out.buffer(b))?;
                out.decoded_views.insert(view.index(), decoded);
            }
        }
        Ok(out)
    }

    fn buffer(&self, index: usize) -> Result<&[u8], LoadError> {
        let bad =
            |reason: &str| LoadError::BadBuffer { path: self.path.clone(), index, reason: reason.into() };
        match self.buffers.get(index) {
            Some(Some(b)) => Ok(b),
            Some(None) => Err(bad("has no data (EXT_meshopt_compression fallback) but is read directly")),
            None => Err(bad("does not exist")),
        }
    }

    /// The bytes of `view` (decoded when compressed), bounds-checked.
    pub(crate) fn view(&self, view: &gltf::buffer::View) -> Result<ViewBytes<'_>, LoadError> {
        let index = view.index();
        if let Some(bytes) = self.decoded_views.get(&index) {
            return Ok(ViewBytes { bytes, stride: view.stride() });
        }
        let buffer = self.buffer(view.buffer().index())?;
        let (offset, length) = (view.offset(), view.length());
        let bytes = offset.checked_add(length).and_then(|end| buffer.get(offset..end)).ok_or_else(|| {
            LoadError::OutOfRange {
                path: self.path.clone(),
                field: format!("bufferViews[{index}]"),
                reason: format!(
                    "byteOffset {offset} + byteLength {length} exceeds buffers[{}] ({} bytes)",
                    view.buffer().index(),
                    buffer.len()
                ),
            }
        })?;
        Ok(ViewBytes { bytes, stride: view.stride() })
    }

    /// The bytes of every buffer together: what the file holds, the bound on what an
    /// accessor without a buffer view may describe.
    pub(crate) fn total_buffer_bytes(&self) -> usize {
        self.buffers.iter().flatten().map(Vec::len).sum()
    }
}

fn is_meshopt_fallback(buffer: &gltf::Buffer) -> bool {
    buffer.extension_value("EXT_meshopt_compression").is_some()
}

fn read_uri(
    path: &Path,
    index: usize,
    uri: &str,
    declared: usize,
    base_dir: &Path,
) -> Result<Vec<u8>, LoadError> {
    let unsafe_uri =
        |reason: String| LoadError::UnsafeUri { path: path.to_owned(), index, uri: uri.to_owned(), reason };
    let file = match uri::resolve(uri, base_dir).map_err(unsafe_uri)? {
        UriTarget::Data(bytes) => return Ok(bytes),
        UriTarget::File(file) => file,
    };
    uri::read_prefix(&file, declared as u64).map_err(|e| match e {
        FileReadError::Io(source) => {
            LoadError::MissingBuffer { path: path.to_owned(), index, uri: file.display().to_string(), source }
        }
        FileReadError::NotAFile => unsafe_uri("it names something other than a regular file".into()),
        FileReadError::TooShort { len } => LoadError::BadBuffer {
            path: path.to_owned(),
            index,
            reason: format!("byteLength is {declared} but only {len} bytes are there (truncated?)"),
        },
    })
}
