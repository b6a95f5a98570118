//! `.signorini.lock`: the output folder's owner. A run (or a restart)
//! holds an exclusive advisory lock on this file of its folder for its
//! whole life, so that a second run into the same folder, of the same case
//! or another, is refused at once instead of mixing its files with the
//! first's or removing them.
//!
//! The lock is the operating system's (`flock` on Unix, `LockFileEx` on
//! Windows, through [`std::fs::File::try_lock`]): the kernel releases it
//! when the process ends, however it ends, so a lock left by a killed run
//! is free again and the next run takes it over. The file holds the
//! holder's process id while it runs and is emptied when the run ends
//! normally, so a next run that finds a process id in it knows the
//! earlier run was killed ([`FolderLock::taken_over`]). The file itself is
//! never removed: removing it while another process opens it would let
//! two processes lock two different files of the same name.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};

use crate::{Error, Result};

/// The lock file's name in the output folder.
pub const LOCK_FILE: &str = ".signorini.lock";

/// The exclusive lock on an output folder, released when dropped.
#[derive(Debug)]
pub struct FolderLock {
    file: File,
    path: PathBuf,
    /// The process id an earlier run left in the lock file: that run was
    /// killed while it held the folder, and this one took it over.
    taken_over: Option<String>,
}

impl FolderLock {
    /// Locks `dir` (created if needed) for this process, or refuses at once
    /// with a message naming the folder and the holder's process id when
    /// another run holds it.
    pub fn acquire(dir: &Path) -> Result<Self> {
        std::fs::create_dir_all(dir).map_err(|e| Error::io("create output folder", dir, e))?;
        let path = dir.join(LOCK_FILE);
        let action = "lock output folder";
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(|e| Error::io(action, &path, e))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let holder = holder(&mut file);
                let who = holder.map_or("another run".to_string(), |pid| {
                    format!("another run (process {pid})")
                });
                return Err(Error::io(
                    action,
                    dir,
                    std::io::Error::new(
                        std::io::ErrorKind::WouldBlock,
                        format!(
                            "{who} is writing into this folder (it holds {LOCK_FILE}); wait \
                             until it ends, or give this run another folder ([output] folder, \
                             or --output)"
                        ),
                    ),
                ));
            }
            Err(TryLockError::Error(e)) => return Err(Error::io(action, &path, e)),
        }
        let taken_over = holder(&mut file);
        let mut lock = FolderLock {
            file,
            path,
            taken_over,
        };
        lock.write_holder(&std::process::id().to_string())
            .map_err(|e| Error::io(action, &lock.path, e))?;
        Ok(lock)
    }

    /// The process id of the killed run whose lock this one took over.
    pub fn taken_over(&self) -> Option<&str> {
        self.taken_over.as_deref()
    }

    /// Replaces the lock file's content by `pid` (empty: no holder).
    fn write_holder(&mut self, pid: &str) -> std::io::Result<()> {
        self.file.set_len(0)?;
        self.file.rewind()?;
        if !pid.is_empty() {
            writeln!(self.file, "{pid}")?;
        }
        self.file.flush()
    }
}

impl Drop for FolderLock {
    /// Ends normally: the file is emptied (no process id says "not
    /// killed"), then closing it releases the lock.
    fn drop(&mut self) {
        let _ = self.write_holder("");
    }
}

/// The process id the lock file names, if any (at most 32 bytes read).
fn holder(file: &mut File) -> Option<String> {
    let mut text = String::new();
    file.rewind().ok()?;
    file.take(32).read_to_string(&mut text).ok()?;
    let pid = text.trim();
    (!pid.is_empty() && pid.chars().all(|c| c.is_ascii_digit())).then(|| pid.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_held_folder_is_refused_and_a_released_one_taken() {
        let dir = tempfile::tempdir().unwrap();
        let first = FolderLock::acquire(dir.path()).unwrap();
        assert_eq!(first.taken_over(), None);
        // a second lock (another open file description, as another process
        // has) is refused while the first is held
        let e = FolderLock::acquire(dir.path()).unwrap_err().to_string();
        let pid = std::process::id().to_string();
        assert!(
            e.contains(&format!("process {pid}")) && e.contains(LOCK_FILE),
            "{e}"
        );
        drop(first);
        // released normally: no process id left, nothing taken over
        let second = FolderLock::acquire(dir.path()).unwrap();
        assert_eq!(second.taken_over(), None);
        drop(second);
        // a process id left by a killed run: taken over, and said so
        std::fs::write(dir.path().join(LOCK_FILE), "4242\n").unwrap();
        let third = FolderLock::acquire(dir.path()).unwrap();
        assert_eq!(third.taken_over(), Some("4242"));
        let text = std::fs::read_to_string(dir.path().join(LOCK_FILE)).unwrap();
        assert_eq!(text.trim(), pid);
    }
}
