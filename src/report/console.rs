//! The command line's output: each result on standard output as soon as it is known (in
//! file order), warnings on standard error, a progress line on a terminal, a partial
//! summary on Ctrl-C, and a closed pipe ending the run quietly.
//!
//! Every write of the command line goes through [`out`] or [`err`]: when the reader has
//! gone (`ii-prove … | head`), the process ends at once, silently, with status
//! [`BROKEN_PIPE`] (128 + SIGPIPE, what a shell reports for a program killed by it).

use std::io::{self, IsTerminal, Write};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use super::formats::{self, Format};
use super::stream::JsonStream;
use super::text::{self, Paint};
use super::{
    Location, Observer, Options, PropertyReport, RunReport, Summary, Unchecked, WarningReport,
};

/// The exit status after a closed output pipe.
pub const BROKEN_PIPE: u8 = 141;
/// The exit status after Ctrl-C (128 + SIGINT).
pub const INTERRUPTED: i32 = 130;
/// A run shows a progress line only once it has taken this long.
const PROGRESS_AFTER: Duration = Duration::from_secs(1);

fn write_to(mut stream: impl Write, text: &str) {
    if let Err(e) = stream.write_all(text.as_bytes()).and_then(|()| stream.flush()) {
        if e.kind() == io::ErrorKind::BrokenPipe {
            std::process::exit(i32::from(BROKEN_PIPE));
        }
        // Nothing sensible is left to do with an output that fails otherwise.
        std::process::exit(2);
    }
}

/// Writes to standard output; a closed pipe ends the process quietly.
pub fn out(text: &str) {
    write_to(io::stdout().lock(), text);
}

/// Writes to standard error; a closed pipe ends the process quietly.
pub fn err(text: &str) {
    write_to(io::stderr().lock(), text);
}

/// Is this error a closed pipe (the reader has gone)?
pub fn is_broken_pipe(e: &io::Error) -> bool {
    e.kind() == io::ErrorKind::BrokenPipe
}

/// How the console reports.
#[derive(Clone, Copy, Debug)]
pub struct ConsoleOptions {
    /// The report format.
    pub format: Format,
    /// Colours for the text report.
    pub paint: Paint,
    /// No warnings on standard error (`-q`).
    pub quiet: bool,
    /// Draw a progress line on standard error (when it is a terminal).
    pub progress: bool,
    /// The results go to standard error (standard output carries `--vcd -`).
    pub results_to_stderr: bool,
    /// Files are written from the whole report after the run (`--vcd`, `--html`…): the
    /// run keeps every result in full.
    pub files_after: bool,
}

struct State {
    /// What is known so far: the counts, and for a structured format every report (its
    /// partial document); a streaming format has printed its results already.
    partial: RunReport,
    plan: Vec<(String, Location)>,
    width: usize,
    current: Option<usize>,
    began: Instant,
    /// The progress line on screen, if one is.
    progress_shown: Option<String>,
    done: bool,
    /// The JSON document as far as it is written (`--format json`).
    json: Option<JsonStream>,
}

/// Prints a run as it goes ([`Observer`]), and the whole report at the end.
pub struct Console {
    state: Arc<Mutex<State>>,
    console: ConsoleOptions,
    opts: Options,
}

fn lock(state: &Mutex<State>) -> MutexGuard<'_, State> {
    state.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

impl Console {
    /// A console for a run of `program` and `files`.
    pub fn new(
        program: Option<String>,
        files: Vec<String>,
        opts: &Options,
        console: ConsoleOptions,
    ) -> Console {
        let timers = program.as_ref().map(|_| opts.timers.as_str());
        let partial = RunReport {
            program,
            files,
            timers,
            warnings: Vec::new(),
            properties: Vec::new(),
            correspondences: Vec::new(),
            summary: Summary::default(),
            interrupted: false,
            unchecked: Vec::new(),
            equations: Vec::new(),
        };
        let state = State {
            partial,
            plan: Vec::new(),
            width: 0,
            current: None,
            began: Instant::now(),
            progress_shown: None,
            done: false,
            json: (console.format == Format::Json).then(JsonStream::default),
        };
        Console { state: Arc::new(Mutex::new(state)), console, opts: opts.clone() }
    }

    /// On Ctrl-C: print what is known (the results so far and a partial summary, or the
    /// partial document of a structured format) and exit with status 130.
    pub fn exit_on_interrupt(&self) {
        let state = Arc::clone(&self.state);
        let (console, opts) = (self.console, self.opts.clone());
        let _ = ctrlc::set_handler(move || {
            let mut s = lock(&state);
            if s.done {
                // The whole report is out already.
                std::process::exit(INTERRUPTED);
            }
            clear_progress(&mut s);
            s.partial.interrupted = true;
            // Results come in the plan's order: those not finished are the plan's rest.
            let (done, total) = (s.partial.summary.total(), s.plan.len());
            let unchecked: Vec<Unchecked> = s.plan[done.min(total)..]
                .iter()
                .map(|(name, at)| Unchecked { name: name.clone(), location: at.clone() })
                .collect();
            s.partial.unchecked = unchecked;
            let s = &mut *s;
            let text = if let Some(json) = &mut s.json {
                json.tail(&s.partial)
            } else if console.format.streams() {
                format!(
                    "interrupted after {done} of {total} properties: {}",
                    text::summary_line(&s.partial.summary, s.partial.timers)
                )
            } else {
                formats::render(console.format, &s.partial, &opts)
            };
            emit(console, &text);
            std::process::exit(INTERRUPTED);
        });
    }

    /// The run has ended: the rest of the report (the summary, or the whole document).
    pub fn finish(&self, report: &RunReport) {
        let mut s = lock(&self.state);
        s.done = true;
        clear_progress(&mut s);
        let s = &mut *s;
        let text = if let Some(json) = &mut s.json {
            json.tail(report)
        } else if self.console.format.streams() {
            text::summary_line(&report.summary, report.timers)
        } else {
            formats::render(self.console.format, report, &self.opts)
        };
        emit(self.console, &text);
    }

    fn spawn_progress(&self) {
        let state = Arc::clone(&self.state);
        std::thread::spawn(move || {
            loop {
                std::thread::sleep(Duration::from_millis(200));
                let mut s = lock(&state);
                if s.done {
                    break;
                }
                if s.began.elapsed() < PROGRESS_AFTER {
                    continue;
                }
                let Some(i) = s.current else { continue };
                let line = format!(
                    "[{}/{}] checking {} ({:.0} s)",
                    s.partial.summary.total(),
                    s.plan.len(),
                    s.plan[i].0,
                    s.began.elapsed().as_secs_f64().floor()
                );
                if s.progress_shown.as_deref() != Some(line.as_str()) {
                    let _ = write!(io::stderr().lock(), "\r\x1b[K{line}");
                    s.progress_shown = Some(line);
                }
            }
        });
    }
}

/// Writes results where they go (standard output, or standard error under `--vcd -`).
fn emit(console: ConsoleOptions, text: &str) {
    if console.results_to_stderr { err(text) } else { out(text) }
}

fn clear_progress(s: &mut State) {
    if s.progress_shown.take().is_some() {
        let _ = io::stderr().lock().write_all(b"\r\x1b[K");
    }
}

impl Observer for Console {
    fn begin(&mut self, plan: &[(String, Location)], files: &[String]) {
        {
            let mut guard = lock(&self.state);
            let s = &mut *guard;
            s.plan = plan.to_vec();
            s.partial.files = files.to_vec();
            s.width = text::name_width(plan.iter().map(|(n, _)| n.as_str()));
            if let Some(json) = &mut s.json {
                emit(self.console, &json.head(&s.partial));
            }
        }
        if self.console.progress && io::stderr().is_terminal() {
            self.spawn_progress();
        }
    }

    fn warning(&mut self, warning: &WarningReport) {
        let mut s = lock(&self.state);
        s.partial.warnings.push(warning.clone());
        if self.console.quiet {
            return;
        }
        clear_progress(&mut s);
        match self.console.format {
            Format::Github => emit(self.console, &formats::github_warning(warning)),
            _ => err(&text::render_warning(warning, self.console.paint)),
        }
    }

    fn started(&mut self, index: usize) {
        lock(&self.state).current = Some(index);
    }

    fn wants_results(&self) -> bool {
        self.console.files_after
            || !(self.console.format.streams() || self.console.format == Format::Json)
    }

    fn correspondence(&mut self, report: &PropertyReport) {
        let mut guard = lock(&self.state);
        let s = &mut *guard;
        let text = if let Some(json) = &mut s.json {
            json.correspondence(&s.partial, report)
        } else {
            let first = s.partial.correspondences.is_empty();
            s.partial.correspondences.push(report.clone());
            if self.console.quiet || !self.console.format.streams() {
                return;
            }
            text::render_correspondence(report, first, &self.opts)
        };
        clear_progress(s);
        emit(self.console, &text);
    }

    fn finished(&mut self, report: &PropertyReport) {
        let mut guard = lock(&self.state);
        let s = &mut *guard;
        s.partial.summary.count(report);
        s.current = None;
        let text = if let Some(json) = &mut s.json {
            json.property(&s.partial, report)
        } else {
            if !self.console.format.streams() {
                s.partial.properties.push(report.clone());
            }
            let width = s.width;
            match self.console.format {
                Format::Text => {
                    text::render_property(report, width, &self.opts, self.console.paint)
                }
                Format::Github => formats::github_property(report, width, &self.opts),
                _ => return,
            }
        };
        clear_progress(s);
        emit(self.console, &text);
    }
}
