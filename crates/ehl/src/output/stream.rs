//! The streaming writer of a transient run: each step's outputs go to disk as the step is
//! solved, so that a run holds no frame in memory however many it keeps.
//!
//! The CLI opens the output's [`Staging`](super::Staging) folder before it solves and hands a
//! [`TransientStream`] to [`crate::run::solve_with`] as its [`StepSink`]. Each step appends its
//! row to `timeline.csv`; each kept frame writes its `frames/frame_NNNNN.vtr` and appends its
//! pressure and film to two spill files (raw little-endian f64, in the staging folder). After
//! the run, [`TransientStream::finish`] writes `frames.npz` by copying the spill files behind
//! their `.npy` headers, `passage.pvd`, `timeline.png`, and `passage.gif` / `passage.png` from
//! the frames they show (read back from the spill files: at most [`GIF_MAX_FRAMES`] + 1, and of
//! a zoomed picture only its strip of rows), then
//! removes the spill files. Every file is byte for byte what [`super::transient::write`] writes
//! from a solution that kept every frame (tested).
//!
//! Nothing is visible before the run ends: the staging folder replaces the output folder only
//! when every file is written, and an error or Ctrl-C removes it.

use super::io_err;
use super::npz::Npz;
use super::transient::{
    crop_grid, gif_frame_indices, highest_frame, picture_record, pvd_of, timeline_header,
    timeline_is_thermal, timeline_row, validate_frame, write_passage_frame_png_of,
    write_passage_gif_of, write_snapshots, write_timeline_csv, write_timeline_png, write_vtr_frame,
    zoom_window, FRAMES_DIR, FRAMES_NPZ, GIF_MAX_FRAMES, PASSAGE_GIF, PASSAGE_PNG, PASSAGE_PVD,
    SNAPSHOTS_DIR, TIMELINE_CSV, TIMELINE_PNG,
};
use crate::case::Case;
use crate::grid::Grid;
use crate::run::StepSink;
use crate::solution::{Frame, Solution, StepRecord, TransientRecord};
use crate::{Error, Result};
use ndarray::Array1;
use ndarray_npy::{WritableElement, WriteNpyError, WriteNpyExt};
use std::fs::File;
use std::io::{BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

/// The spill files of the frames' pressure and film, in the staging folder, removed by
/// [`TransientStream::finish`].
const SPILL: [&str; 2] = [".frames-pressure.f64", ".frames-film.f64"];

/// What the stream remembers of each kept frame: where it is in the spill files and what
/// `frames.npz`, `passage.pvd` and the choice of `passage.png` need.
#[derive(Debug, Clone, Copy)]
struct FrameMeta {
    step: usize,
    time_s: f64,
    x_p_m: f64,
    /// the largest pressure of the frame, over the strip the pictures show (the zoom window)
    peak: f64,
}

/// The [`StepSink`] that writes a transient run's per-step outputs into a staging folder as
/// the run goes (see the module documentation).
pub struct TransientStream {
    /// the staging folder the files go into
    dir: PathBuf,
    /// the output folder it becomes, which messages name
    out: PathBuf,
    case: Case,
    grid: Option<Grid>,
    /// the strip of rows the pictures zoom onto (`zoom_window`): its grid and rows j0 ..= j1
    window: Option<(Grid, usize, usize)>,
    /// the rows the pictures show: the window's, or the whole grid
    rows: (usize, usize),
    thermal: bool,
    timeline: Option<BufWriter<File>>,
    spill: Vec<BufWriter<File>>,
    frames: Vec<FrameMeta>,
    line: String,
    keep: bool,
}

impl TransientStream {
    /// A stream into the folder of `staging` for `case`.
    pub fn new(staging: &super::Staging, case: &Case) -> Self {
        TransientStream {
            dir: staging.path().to_path_buf(),
            out: staging.target().to_path_buf(),
            case: case.clone(),
            grid: None,
            window: None,
            rows: (0, 0),
            thermal: false,
            timeline: None,
            spill: Vec::new(),
            frames: Vec::new(),
            line: String::new(),
            keep: false,
        }
    }

    /// The stream that also leaves every frame in the solution (for comparing its files with
    /// those of the in-memory writer).
    pub fn keeping_frames(mut self) -> Self {
        self.keep = true;
        self
    }

    /// Writes the transient outputs that remain after the run into the staging folder from
    /// `solution` (its timeline and snapshots; its frames are not read), then removes the spill
    /// files. `solution.transient` must be the run's record.
    pub fn finish(mut self, case: &Case, solution: &Solution) -> Result<()> {
        let dir = self.dir.clone();
        let spills: Vec<PathBuf> = SPILL.iter().map(|n| self.dir.join(n)).collect();
        let Some(t) = &solution.transient else {
            // not a transient solution: nothing of the stream belongs in the output
            self.spill.clear();
            for p in &spills {
                let _ = std::fs::remove_file(p);
            }
            return Ok(());
        };
        let g = solution.grid;
        // timeline.csv: streamed; its header was chosen from the case, the in-memory writer
        // chooses it from the rows: they differ only when no step has temperatures
        let path = dir.join(TIMELINE_CSV);
        if let Some(mut w) = self.timeline.take() {
            w.flush().map_err(|e| io_err(&path, e))?;
        }
        if timeline_is_thermal(t) != self.thermal || self.grid.is_none() {
            write_timeline_csv(&path, t)?;
        }
        for (w, p) in self.spill.iter_mut().zip(&spills) {
            w.flush().map_err(|e| io_err(p, e))?;
        }
        self.spill.clear();
        let result = self.write_rest(&dir, case, solution, t, &g, &spills);
        for p in &spills {
            let _ = std::fs::remove_file(p);
        }
        result
    }

    fn write_rest(
        &self,
        dir: &Path,
        case: &Case,
        solution: &Solution,
        t: &TransientRecord,
        g: &Grid,
        spills: &[PathBuf],
    ) -> Result<()> {
        let n = g.len();
        let k = self.frames.len();
        // frames.npz: the frames' times, then the two fields copied from the spill files
        let path = dir.join(FRAMES_NPZ);
        {
            let mut npz = Npz::create(&path)?;
            let per = |f: fn(&FrameMeta) -> f64| Array1::from_iter(self.frames.iter().map(f));
            npz.add("time_s", &per(|f| f.time_s))?;
            npz.add("x_p_m", &per(|f| f.x_p_m))?;
            npz.add(
                "step",
                &Array1::from_iter(self.frames.iter().map(|f| f.step as i64)),
            )?;
            npz.add_grid(g)?;
            for (name, spill) in ["pressure", "film"].iter().zip(spills) {
                let a = SpilledArray {
                    path: spill.clone(),
                    shape: vec![k, g.ny, g.nx],
                };
                npz.add_sized(name, &a, (8 * k * n) as u64)?;
            }
            npz.finish()?;
        }
        write_timeline_png(&dir.join(TIMELINE_PNG), case, t)?;
        // the pictures: the frames they show, read back (the GIF's and the still's)
        let shown = gif_frame_indices(k, GIF_MAX_FRAMES);
        let still = highest_frame(self.frames.iter().map(|f| f.peak));
        let mut wanted = shown.clone();
        wanted.extend(still);
        wanted.sort_unstable();
        wanted.dedup();
        // where the whole map would show features[0] as a speck, the pictures show a strip of
        // rows around it (`zoom_window`): only those rows are read back
        let frames = self.read_frames(spills, &wanted, n, self.rows, g.nx)?;
        let sub = picture_record(t, frames);
        let at = |i: usize| wanted.binary_search(&i).expect("read above");
        let shown_sub: Vec<usize> = shown.iter().map(|&i| at(i)).collect();
        let zcase;
        let (case_a, g_a, t_a) = match &self.window {
            Some((zg, _, _)) => {
                let mut c = case.clone();
                c.title = format!("zoom on features[0] — {}", case.title);
                zcase = c;
                (&zcase, zg, &sub)
            }
            None => (case, g, &sub),
        };
        if case.output.animation && k >= 2 {
            write_passage_gif_of(&dir.join(PASSAGE_GIF), case_a, g_a, t_a, &shown_sub)?;
        }
        if let Some(s) = still {
            write_passage_frame_png_of(
                &dir.join(PASSAGE_PNG),
                case_a,
                g_a,
                t_a,
                at(s),
                &shown_sub,
            )?;
        }
        drop(sub);
        if k > 0 {
            let path = dir.join(PASSAGE_PVD);
            std::fs::write(
                &path,
                pvd_of(self.frames.iter().map(|f| (f.step, f.time_s))),
            )
            .map_err(|e| io_err(&path, e))?;
        }
        write_snapshots(&dir.join(SNAPSHOTS_DIR), case, solution)
    }

    /// The rows `j0 ..= j1` (of `nx` cells) of the kept frames `which` (indices, increasing),
    /// read back from the spill files of frames of `n` cells.
    fn read_frames(
        &self,
        spills: &[PathBuf],
        which: &[usize],
        n: usize,
        (j0, j1): (usize, usize),
        nx: usize,
    ) -> Result<Vec<Frame>> {
        let mut files = spills
            .iter()
            .map(|p| File::open(p).map_err(|e| io_err(p, e)))
            .collect::<Result<Vec<_>>>()?;
        let mut out = Vec::with_capacity(which.len());
        let mut bytes = vec![0u8; 8 * (j1 + 1 - j0) * nx];
        for &i in which {
            let m = self.frames[i];
            let mut fields = Vec::with_capacity(2);
            for (f, p) in files.iter_mut().zip(spills) {
                f.seek(SeekFrom::Start((8 * (i * n + j0 * nx)) as u64))
                    .and_then(|_| f.read_exact(&mut bytes))
                    .map_err(|e| io_err(p, e))?;
                fields.push(
                    bytes
                        .chunks_exact(8)
                        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
                        .collect::<Vec<f64>>(),
                );
            }
            let film = fields.pop().expect("two fields");
            let pressure = fields.pop().expect("two fields");
            out.push(Frame {
                step: m.step,
                time_s: m.time_s,
                x_p_m: m.x_p_m,
                pressure,
                film,
            });
        }
        Ok(out)
    }
}

impl StepSink for TransientStream {
    fn begin(&mut self, grid: &Grid, thermal: bool) -> Result<()> {
        if super::aborting() {
            return Err(Error::Cancelled);
        }
        self.grid = Some(*grid);
        self.thermal = thermal;
        self.window = zoom_window(&self.case, grid).and_then(|(y0, y1)| crop_grid(grid, y0, y1));
        self.rows = self.window.map_or((0, grid.ny - 1), |(_, j0, j1)| (j0, j1));
        let path = self.dir.join(TIMELINE_CSV);
        let mut w = BufWriter::new(File::create(&path).map_err(|e| io_err(&path, e))?);
        w.write_all(timeline_header(thermal).as_bytes())
            .map_err(|e| io_err(&path, e))?;
        self.timeline = Some(w);
        for name in SPILL {
            let path = self.dir.join(name);
            let f = File::create(&path).map_err(|e| io_err(&path, e))?;
            self.spill.push(BufWriter::with_capacity(1 << 20, f));
        }
        // create_dir, not create_dir_all: were the staging folder removed meanwhile (Ctrl-C),
        // this fails rather than make it again
        let folder = self.dir.join(FRAMES_DIR);
        std::fs::create_dir(&folder).map_err(|e| io_err(&folder, e))
    }

    fn step(&mut self, row: &StepRecord, frame: Option<&Frame>) -> Result<bool> {
        if super::aborting() {
            // a signal is ending the process and its temporary folders are being removed
            return Err(Error::Cancelled);
        }
        let g = self.grid.expect("begin() is called before the steps");
        self.line.clear();
        timeline_row(&mut self.line, row, self.thermal);
        let path = self.dir.join(TIMELINE_CSV);
        if let Some(w) = self.timeline.as_mut() {
            w.write_all(self.line.as_bytes())
                .map_err(|e| io_err(&path, e))?;
        }
        let Some(f) = frame else {
            return Ok(self.keep);
        };
        let out = |m: String| Error::Output {
            path: self.out.clone(),
            message: m,
        };
        validate_frame(&g, f).map_err(out)?;
        for ((w, name), field) in self.spill.iter_mut().zip(SPILL).zip([&f.pressure, &f.film]) {
            let mut bytes = Vec::with_capacity(8 * field.len());
            for v in field.iter() {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
            w.write_all(&bytes)
                .map_err(|e| io_err(&self.dir.join(name), e))?;
        }
        write_vtr_frame(&self.dir.join(FRAMES_DIR), &g, f)?;
        let (j0, j1) = self.rows;
        let peak = f.pressure[j0 * g.nx..(j1 + 1) * g.nx]
            .iter()
            .cloned()
            .fold(0.0f64, f64::max);
        self.frames.push(FrameMeta {
            step: f.step,
            time_s: f.time_s,
            x_p_m: f.x_p_m,
            peak,
        });
        Ok(self.keep)
    }

    fn frames_in_memory(&self) -> bool {
        self.keep
    }
}

/// A (k, ny, nx) float64 array whose data sit in a spill file: written into `frames.npz` as
/// its `.npy` header (ndarray-npy's, so the bytes equal those of an in-memory array) followed
/// by the file's bytes, copied in blocks.
struct SpilledArray {
    path: PathBuf,
    shape: Vec<usize>,
}

impl WriteNpyExt for SpilledArray {
    fn write_npy<W: Write>(&self, mut writer: W) -> std::result::Result<(), WriteNpyError> {
        let header = ndarray_npy::npy::header::Header {
            type_descriptor: <f64 as WritableElement>::type_descriptor(),
            layout: ndarray_npy::npy::header::Layout::Standard,
            shape: self.shape.clone(),
        };
        let bytes = header
            .to_bytes()
            .map_err(|e| WriteNpyError::Io(std::io::Error::other(e.to_string())))?;
        writer.write_all(&bytes)?;
        let want = 8 * self.shape.iter().product::<usize>() as u64;
        let copied = std::io::copy(&mut File::open(&self.path)?, &mut writer)?;
        if copied != want {
            return Err(WriteNpyError::Io(std::io::Error::other(format!(
                "{}: {copied} bytes of frames, {want} expected",
                self.path.display()
            ))));
        }
        Ok(())
    }
}
