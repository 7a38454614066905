//! Messages to stdout and stderr that never panic. `println!` and `eprintln!` panic when the
//! stream fails (a closed pipe: `ehl check case.toml | head -1`; a full disk: `> /dev/full`).
//! Here a closed stdout ends the program quietly with [`EXIT_BROKEN_PIPE`], any other stdout
//! failure is an error (exit 1, said on stderr), and a failing stderr is ignored (there is
//! nowhere left to say it).

use std::io::Write;

/// Exit status when stdout was closed by its reader (128 + SIGPIPE, as a shell reports a
/// program ended by SIGPIPE).
pub const EXIT_BROKEN_PIPE: u8 = 141;

/// The error for "stdout is closed": the program stops quietly with [`EXIT_BROKEN_PIPE`].
#[derive(Debug)]
pub struct Closed;

impl std::fmt::Display for Closed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("standard output is closed")
    }
}

impl std::error::Error for Closed {}

/// Maps a failed write to stdout: [`Closed`] for a broken pipe, else an error saying what failed.
pub fn stdout_error(e: std::io::Error) -> anyhow::Error {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        anyhow::Error::new(Closed)
    } else {
        anyhow::anyhow!("writing to standard output: {e}")
    }
}

/// Writes `text` and a newline to stdout and flushes, so that a failure is seen here.
pub fn out(text: &str) -> anyhow::Result<()> {
    let mut o = std::io::stdout().lock();
    o.write_all(text.as_bytes())
        .and_then(|()| o.write_all(b"\n"))
        .and_then(|()| o.flush())
        .map_err(stdout_error)
}

/// Writes `text` and a newline to stderr; failures are ignored.
pub fn err(text: &str) {
    let mut e = std::io::stderr().lock();
    let _ = e
        .write_all(text.as_bytes())
        .and_then(|()| e.write_all(b"\n"))
        .and_then(|()| e.flush());
}
