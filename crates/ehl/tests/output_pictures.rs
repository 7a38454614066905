//! The pictures of the four synthetic solutions (ball, finite roller with end peaks, infinite
//! line, lubricated ball) and the 1D lubricated profile: every expected PNG is written with the
//! documented size. Set `EHL_OUTPUT_DEMO_DIR=/some/dir` to keep the folders and look at them.

use ehl::output::{synthetic, write_all};
use std::path::{Path, PathBuf};

/// (width, height) from a PNG's IHDR chunk.
fn png_size(path: &Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(
        &b[..8],
        b"\x89PNG\r\n\x1a\n",
        "{} is not a PNG",
        path.display()
    );
    assert_eq!(&b[12..16], b"IHDR");
    let be = |k: usize| u32::from_be_bytes([b[k], b[k + 1], b[k + 2], b[k + 3]]);
    (be(16), be(20))
}

fn out_root() -> (Option<tempfile::TempDir>, PathBuf) {
    match std::env::var_os("EHL_OUTPUT_DEMO_DIR") {
        Some(d) => (None, PathBuf::from(d)),
        None => {
            let t = tempfile::tempdir().unwrap();
            let p = t.path().to_path_buf();
            (Some(t), p)
        }
    }
}

#[test]
fn every_synthetic_case_gets_its_pictures() {
    let (_keep, root) = out_root();
    let cases = [
        ("dry_ball", synthetic::dry_ball()),
        ("dry_roller", synthetic::dry_roller()),
        ("dry_line", synthetic::dry_infinite_line()),
        ("ehl_ball", synthetic::ehl_ball(false)),
        ("ehl_line", synthetic::ehl_ball(true)),
    ];
    for (name, (case, sol)) in cases {
        let dir = root.join(name);
        write_all(&dir, &case, &sol).unwrap_or_else(|e| panic!("{name}: {e}"));
        for png in ["pressure.png", "film.png", "centerline.png"] {
            let p = dir.join(png);
            // the documented size (output::plot's docs), not the code's own constants: a change
            // to those must show here
            assert_eq!(png_size(&p), (1000, 700), "{name}/{png}");
            // a real picture, not a blank frame: well above the few hundred bytes of an empty PNG
            let len = std::fs::metadata(&p).unwrap().len();
            assert!(len > 20_000, "{name}/{png} is only {len} bytes");
        }
    }
}
