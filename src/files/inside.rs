//! Reading a file of a folder this run did not write (a restart folder, a
//! finished output folder handed to `asperity report`): the name must stay
//! inside the folder, no link may be followed, and the file must be a regular
//! file of bounded size.

use std::path::Path;

/// The words the messages use for a folder: its kind (`restart folder`) and
/// what its size limits are (`this case can need`).
#[derive(Clone, Copy)]
pub(crate) struct Folder<'a> {
    pub kind: &'a str,
    pub bound: &'a str,
}

/// Opens the file `rel` of the folder `dir` for reading. `rel` must be a
/// plain relative name (components separated by `/`, none empty, `.` or
/// `..`, no backslash or NUL); neither the file nor a folder on the way may
/// be a symbolic link (checked on each component, and the file opened with
/// `O_NOFOLLOW`); the file must be a regular file (not a FIFO or a device:
/// opened non-blocking, checked again on the open file) of at most `limit`
/// bytes. `what` names the file in the messages. Returns the file and its
/// size; the error is a message without the folder's path.
pub(crate) fn open_inside(
    dir: &Path,
    rel: &str,
    what: &str,
    rules: &Folder,
    limit: u64,
) -> Result<(std::fs::File, u64), String> {
    let Folder {
        kind: folder,
        bound,
    } = *rules;
    let p = walk(dir, rel, what, folder)?;
    let check = |m: &std::fs::Metadata| -> Result<u64, String> {
        if !m.is_file() {
            let kind = if m.is_dir() {
                "a folder"
            } else {
                "a device, FIFO or socket"
            };
            return Err(format!("{what} is {kind}, not a regular file"));
        }
        if m.len() > limit {
            return Err(format!(
                "{what} has {} bytes, more than the {limit} bytes {bound}",
                m.len()
            ));
        }
        Ok(m.len())
    };
    check(&std::fs::symlink_metadata(&p).map_err(|e| format!("{what}: {e}"))?)?;
    let mut opts = std::fs::OpenOptions::new();
    opts.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        opts.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK);
    }
    let f = opts.open(&p).map_err(|e| format!("{what}: {e}"))?;
    // the file opened is the one checked (not one swapped in since)
    let len = check(&f.metadata().map_err(|e| format!("{what}: {e}"))?)?;
    Ok((f, len))
}

/// `dir/rel` after checking each component of `rel`: a plain name, no
/// symbolic link, every one but the last a folder.
fn walk(dir: &Path, rel: &str, what: &str, folder: &str) -> Result<std::path::PathBuf, String> {
    let parts: Vec<&str> = rel.split('/').collect();
    let plain = |c: &str| !c.is_empty() && c != "." && c != ".." && !c.contains(['\\', '\0']);
    if !parts.iter().all(|c| plain(c)) {
        return Err(format!("{what}: not a plain name inside the {folder}"));
    }
    let mut p = dir.to_path_buf();
    for (i, c) in parts.iter().enumerate() {
        p.push(c);
        let m = std::fs::symlink_metadata(&p).map_err(|e| format!("{what}: {e}"))?;
        let t = m.file_type();
        if t.is_symlink() {
            let link = if i + 1 < parts.len() {
                format!("{what}: its folder {} is", parts[..=i].join("/"))
            } else {
                format!("{what} is")
            };
            return Err(format!(
                "{link} a symbolic link: every file of the {folder} must be a regular file inside it"
            ));
        }
        if i + 1 < parts.len() && !t.is_dir() {
            return Err(format!("{what}: {c} is not a folder"));
        }
    }
    Ok(p)
}

/// The bytes of the file `rel` of `dir`, opened as [`open_inside`] opens
/// it; a file that grew beyond `limit` while it was read is refused.
pub(crate) fn read_inside(
    dir: &Path,
    rel: &str,
    what: &str,
    rules: &Folder,
    limit: u64,
) -> Result<Vec<u8>, String> {
    let (file, len) = open_inside(dir, rel, what, rules, limit)?;
    let mut bytes = Vec::with_capacity(len as usize);
    std::io::Read::read_to_end(&mut std::io::Read::take(file, limit + 1), &mut bytes)
        .map_err(|e| format!("{what}: {e}"))?;
    if bytes.len() as u64 > limit {
        return Err(format!(
            "{what} grew beyond {limit} bytes while it was read"
        ));
    }
    Ok(bytes)
}
