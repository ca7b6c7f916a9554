//! The `ii-prove` command line: parses arguments and hands over to the library.

use std::io::IsTerminal;
use std::process::ExitCode;
use std::time::Duration;

use clap::{Args, CommandFactory, Parser, Subcommand, ValueEnum};
use ii_prove::ladder::TimerModel;
use ii_prove::report::console::{self, Console, ConsoleOptions};
use ii_prove::report::formats::Format;
use ii_prove::report::text::Paint;
use ii_prove::report::{self, Options};
use ii_prove::{repl, script};

/// Proving allocates many small terms and frees them soon; mimalloc does this faster
/// than the system allocator.
#[cfg(feature = "mimalloc")]
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

const EXIT_CODES: &str = "\
Exit status:
  0    every property was proved
  1    some property was refuted or is unknown (or, with --deny vacuous, holds vacuously)
  2    bad input or usage, or no property to check (nothing was proved from that input)
  130  interrupted (Ctrl-C): the results so far and a partial summary are printed
  141  the output pipe was closed";

/// Proves safety properties of PLC programs in the II algebra of binary signals.
///
/// `ii-prove PROGRAM.ld PROPS.ii` proves the properties of PROPS.ii about the
/// compiled program: an LDmicro file, a PLCopen XML project (LD, FBD, ST or IL bodies),
/// or IEC 61131-3 Structured Text (.st) or Instruction List (.il), recognised by its
/// content or extension; `ii-prove FILE.ii…` proves properties about the free signals the
/// files declare with `input`. `ii-prove PROGRAM.st` alone checks the program's own
/// `#ASSERT` comments.
///
/// A property of a program holds when, on every run, it holds at every scan up to
/// which the `assume` statements have held (hypotheses hold "up to now"). Each rung or
/// statement is compiled to what the PLC does on every scan; timers count scans as the
/// runtime does (see --timers). What is not modelled yet (LDmicro's GOTO, GOSUB,
/// SUBPROG/ENDSUB, RETURN, LOCK, SLEEP; ST WHILE and REPEAT loops; IL backward jumps) is refused
/// with a located error.
#[derive(Parser)]
#[command(name = "ii-prove", version, after_help = EXIT_CODES, args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// A program (LDmicro .ld, PLCopen .xml, Structured Text .st, Instruction List .il)
    /// and property files (.ii), or property files alone.
    files: Vec<String>,
    #[command(flatten)]
    common: Common,
}

/// The options of a reported run: report, notation, compilation, limits and outputs.
#[derive(Args)]
struct Common {
    #[command(flatten)]
    head: ReportHead,
    #[command(flatten)]
    notation: Notation,
    #[command(flatten)]
    compilation: Compilation,
    #[command(flatten)]
    tail: ReportTail,
}

/// How a run reports (the options before the notation and compilation).
#[derive(Args)]
struct ReportHead {
    /// Print each kernel-checked proof as a calculation (an induction's timer chains,
    /// step lemmas and invariant folded to a few lines).
    #[arg(long)]
    trace: bool,
    /// As `--trace`, with every lemma the kernel checked printed in full.
    #[arg(long)]
    trace_all: bool,
    /// The report format on standard output.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// The same as `--format json`.
    #[arg(long, conflicts_with = "format")]
    json: bool,
}

/// How a run reports (the options after the notation and compilation).
#[derive(Args)]
struct ReportTail {
    /// Time limit per property: `10`, `10s`, `500ms`, `2m` (a bare number is seconds).
    #[arg(long, default_value = "10s", value_parser = parse_timeout, value_name = "DURATION")]
    timeout: Duration,
    /// Check only the properties whose name contains NAME or matches the glob NAME (`P1*`);
    /// repeatable.
    #[arg(long, value_name = "NAME")]
    only: Vec<String>,
    /// Make a kind of result fail the run: `vacuous` (a proof from hypotheses that force it).
    #[arg(long, value_enum, value_name = "KIND")]
    deny: Vec<Deny>,
    /// Properties checked at once (default: the number of cores); results are still
    /// printed in file order, as each is known.
    #[arg(long, short = 'j', value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    jobs: Option<u16>,
    /// No warnings on standard error.
    #[arg(short, long)]
    quiet: bool,
    /// Colour in the text report.
    #[arg(long, value_enum, default_value_t = Color::Auto, value_name = "WHEN")]
    color: Color,
    /// Write the counterexamples as a Value Change Dump (GTKWave); `-` for standard output.
    #[arg(long, value_name = "FILE")]
    vcd: Option<String>,
    /// Write the counterexamples as WaveDrom JSON; `-` for standard output.
    #[arg(long, value_name = "FILE")]
    wavedrom: Option<String>,
    /// Write the HTML report (as `--format html`) beside any other format; `-` for standard output.
    #[arg(long, value_name = "FILE")]
    html: Option<String>,
}

/// How a ladder program is compiled.
#[derive(Args)]
struct Compilation {
    /// How a program's TON/TOF timers are compiled: `plc`, exactly the scans the
    /// runtime counts (P = floor(delay / cycle) + adjust, so an LDmicro0.1 timer is one
    /// scan early); `ideal`, the paper's idealisation, the delay as written.
    #[arg(long, value_enum, default_value_t = Timers::Plc)]
    timers: Timers,
    /// For a PLCopen XML, ST or IL program: the POU to check (default: the program the
    /// configuration's task runs, or the only program).
    #[arg(long, value_name = "NAME")]
    pou: Option<String>,
    /// For a PLCopen XML, ST or IL program: the scan cycle, `20ms`, `T#20ms`, `500us` (default: the
    /// task's interval, else 20 ms with a warning).
    #[arg(long, value_parser = parse_cycle, value_name = "DURATION")]
    cycle: Option<u64>,
    /// For a PLCopen XML program: retained (`retain`/`persistent`) variables start at
    /// their declared initial values, as after a cold restart (default: with any value,
    /// as after a warm restart).
    #[arg(long)]
    cold_start: bool,
    /// For a PLCopen XML program whose LD/FBD positions and document order give
    /// different statement orders: `layout` (by position: Beremiz before 2022, the
    /// OpenPLC editor) or `document` (Beremiz since 2022). Without it such a file is
    /// refused.
    #[arg(long, value_enum, value_name = "ORDER")]
    order: Option<Order>,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Order {
    /// By position: rows top to bottom, each left to right.
    Layout,
    /// As the objects appear in the file.
    Document,
}

impl Order {
    fn choice(self) -> ii_prove::ladder::plcopen::StatementOrder {
        match self {
            Order::Layout => ii_prove::ladder::plcopen::StatementOrder::Layout,
            Order::Document => ii_prove::ladder::plcopen::StatementOrder::Document,
        }
    }
}

/// A scan cycle in µs: an IEC literal (`T#20ms`) or a plain duration (`20ms`).
fn parse_cycle(text: &str) -> Result<u64, String> {
    let us = ii_prove::ladder::plcopen::parse_duration(text).or_else(|| {
        humantime::parse_duration(text).ok().and_then(|d| u64::try_from(d.as_micros()).ok())
    });
    match us {
        Some(us) if us > 0 => Ok(us),
        _ => Err(format!("`{text}` is not a positive duration such as `20ms` or `T#20ms`")),
    }
}

impl Compilation {
    fn selection(&self) -> ii_prove::ladder::plcopen::Selection {
        ii_prove::ladder::plcopen::Selection {
            pou: self.pou.clone(),
            cycle_us: self.cycle,
            cold_start: self.cold_start,
            order: self.order.map(Order::choice),
            elapsed: Default::default(),
        }
    }

    fn model(&self) -> TimerModel {
        self.timers.model()
    }
}

impl Timers {
    fn model(self) -> TimerModel {
        match self {
            Timers::Plc => TimerModel::Plc,
            Timers::Ideal => TimerModel::Ideal,
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Timers {
    /// The scans the runtime counts (the default).
    Plc,
    /// The delay as written (the paper's idealisation).
    Ideal,
}

#[derive(Args)]
struct Notation {
    /// Use ASCII notation (`.`, `!`, `=>`) and ASCII diagrams.
    #[arg(long)]
    ascii: bool,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Deny {
    /// A vacuous proof fails the run.
    Vacuous,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Color {
    /// When standard output is a terminal and `NO_COLOR` is not set.
    Auto,
    Always,
    Never,
}

#[derive(Subcommand)]
enum Command {
    /// List every law the prover may use, with its name and file.
    Axioms {
        #[command(flatten)]
        notation: Notation,
    },
    /// Check proof scripts: every theorem and lemma, step by step, by the kernel.
    Check {
        /// Proof scripts (.ii files with `theorem`/`lemma` statements).
        #[arg(required = true)]
        files: Vec<String>,
        #[command(flatten)]
        notation: Notation,
        #[command(flatten)]
        compilation: Compilation,
    },
    /// The interactive prover: state goals and prove them step by step (`help` inside).
    Repl {
        /// A .ii file to load first.
        file: Option<String>,
    },
    /// Print a ladder program's compiled equations and recurrences as `.ii` text.
    Show {
        /// The ladder program (.ld).
        program: String,
        #[command(flatten)]
        notation: Notation,
        #[command(flatten)]
        compilation: Compilation,
    },
    /// Export a program and its properties as an AIGER model for hardware model checkers
    /// (ABC `pdr`, `int`): one step a scan, one bad-state output per property (named in
    /// the symbol table). `--aiger FILE.aig` writes binary AIGER, any other name ASCII.
    Export {
        /// The program (.ld, .xml, .st, .il).
        program: String,
        /// Property files (.ii); the program's own properties come first.
        properties: Vec<String>,
        /// The AIGER file to write (`-`: standard output, ASCII).
        #[arg(long, value_name = "FILE")]
        aiger: String,
        /// Export only the properties whose name contains NAME or matches the glob NAME;
        /// repeatable.
        #[arg(long, value_name = "NAME")]
        only: Vec<String>,
        #[command(flatten)]
        compilation: Compilation,
    },
    /// Compare two programs: is each output of A equal to the same output of B at every
    /// scan, from power-up, for every input sequence?
    ///
    /// A and B are any programs ii-prove reads (LDmicro, PLCopen XML, .st, .il), or the
    /// same file twice with --timers-b. Inputs and outputs are matched by name (exactly,
    /// else without an LDmicro kind prefix and ignoring case: `XL_flow` is `L_flow`);
    /// --map renames. An input only one program reads is free for both; an unmatched
    /// output is not compared; both are reported. The outputs are LDmicro's `Y` pins,
    /// or, for a language without them, every bit the code writes. B's signals are
    /// primed in proofs and diagrams (`YL1_pump'`). One verdict per output:
    /// `proved` (equivalent: a kernel-checked proof of `X = X'` from both programs'
    /// equations, by the algebra or by induction over scans), `refuted` (differs: an
    /// input sequence replayed on both programs' simulators, the scan where they part
    /// marked) or `unknown`. Both programs must scan at the same cycle; they start from
    /// power-up, or with `--any-state` from matched arbitrary states.
    #[command(after_help = EXIT_CODES)]
    Equiv {
        /// The first program.
        a: String,
        /// The second program.
        b: String,
        /// Renames: a file of lines `NAME_IN_A = NAME_IN_B` (`#` comments), inputs or outputs.
        #[arg(long, value_name = "FILE")]
        map: Option<String>,
        /// Compare only these outputs (either program's names, comma-separated or repeated).
        #[arg(long, value_name = "NAMES", value_delimiter = ',')]
        outputs: Vec<String>,
        /// How B's timers are compiled (default: as --timers).
        #[arg(long, value_enum, value_name = "MODEL")]
        timers_b: Option<Timers>,
        /// B's scan cycle, for a PLCopen, ST or IL program (default: as --cycle).
        #[arg(long, value_parser = parse_cycle, value_name = "DURATION")]
        cycle_b: Option<u64>,
        /// B's statement order, for a PLCopen program whose LD/FBD positions and document
        /// order differ (default: as --order); `equiv P.xml P.xml --order layout
        /// --order-b document` asks whether the two editors' orders do the same.
        #[arg(long, value_enum, value_name = "ORDER")]
        order_b: Option<Order>,
        /// Start both programs from any state instead of power-up: the bits and integers
        /// both write under one name (or a --map pair) start equal, the rest (one-shot
        /// memories too) arbitrary; a timer is refused (its count is not modelled).
        #[arg(long)]
        any_state: bool,
        #[command(flatten)]
        common: Common,
    },
    /// Print a shell completion script, or install it with `--install` (e.g. `ii-prove completions bash --install`).
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
        /// Write it where the shell looks for a user's completions (bash:
        /// `$XDG_DATA_HOME/bash-completion/completions`, zsh: `~/.zfunc`, fish:
        /// `$XDG_CONFIG_HOME/fish/completions`), creating the folders.
        #[arg(long)]
        install: bool,
    },
    /// Print the manual page (roff; `ii-prove man | man -l -`).
    Man,
}

/// Writes a completion script where `shell` looks for a user's own, creating the
/// folders; says where, and what else the shell needs.
fn install_completions(
    shell: clap_complete::Shell,
    script: &str,
) -> Result<String, report::InputError> {
    use clap_complete::Shell;
    let error = |text: String| report::InputError { rendered: format!("error: {text}\n") };
    let env_dir = |var: &str, fallback: &str| -> Result<std::path::PathBuf, report::InputError> {
        match std::env::var_os(var).filter(|v| !v.is_empty()) {
            Some(dir) => Ok(dir.into()),
            None => std::env::var_os("HOME")
                .filter(|h| !h.is_empty())
                .map(|h| std::path::Path::new(&h).join(fallback))
                .ok_or_else(|| error(format!("neither {var} nor HOME is set"))),
        }
    };
    let (path, note) = match shell {
        Shell::Bash => (
            env_dir("XDG_DATA_HOME", ".local/share")?.join("bash-completion/completions/ii-prove"),
            "",
        ),
        Shell::Fish => {
            (env_dir("XDG_CONFIG_HOME", ".config")?.join("fish/completions/ii-prove.fish"), "")
        }
        Shell::Zsh => (
            env_dir("ZDOTDIR", "")?.join(".zfunc/_ii-prove"),
            "\nadd `fpath=(~/.zfunc $fpath); autoload -Uz compinit; compinit` to ~/.zshrc if it is not there",
        ),
        other => {
            return Err(error(format!(
                "{other} has no standard folder for completions: `ii-prove completions {other} > FILE` and load FILE from your profile"
            )));
        }
    };
    let folder = path.parent().unwrap_or(std::path::Path::new("."));
    let temp = folder.join(".ii-prove-completions.tmp");
    std::fs::create_dir_all(folder)
        .and_then(|()| std::fs::write(&temp, script))
        .and_then(|()| std::fs::rename(&temp, &path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&temp);
            error(format!("cannot write {}: {e}", path.display()))
        })?;
    Ok(format!("installed the {shell} completions in {}{note}", path.display()))
}

/// `--timeout`: a positive duration, in seconds when it has no unit.
fn parse_timeout(text: &str) -> Result<Duration, String> {
    let duration = match text.trim().parse::<f64>() {
        Ok(seconds) if seconds.is_finite() && seconds > 0.0 => {
            Duration::from_secs_f64(seconds.min(1e6))
        }
        Ok(_) => return Err("must be a positive duration".into()),
        Err(_) => humantime::parse_duration(text.trim()).map_err(|e| e.to_string())?,
    };
    if duration.is_zero() {
        return Err("must be a positive duration".into());
    }
    Ok(duration)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let opts = |ascii: bool| Options { ascii, ..Options::default() };
    let result = match cli.command {
        Some(Command::Axioms { notation }) => {
            report::list_axioms(&opts(notation.ascii)).map(|text| (text, 0))
        }
        Some(Command::Repl { file }) => {
            // Commands piped in end with status 2 when one of them failed.
            let result = if std::io::stdin().is_terminal() {
                repl::run_interactive(file.as_deref()).map(|()| false)
            } else {
                repl::repl_with(std::io::stdin().lock(), std::io::stdout(), false, file.as_deref())
            };
            return match result {
                Ok(false) => ExitCode::SUCCESS,
                Ok(true) => ExitCode::from(2),
                Err(e) if console::is_broken_pipe(&e) => ExitCode::from(console::BROKEN_PIPE),
                Err(e) => {
                    console::err(&format!("error: {e}\n"));
                    ExitCode::from(2)
                }
            };
        }
        Some(Command::Check { files, notation, compilation }) => {
            let opts = Options {
                timers: compilation.model(),
                plcopen: compilation.selection(),
                ..opts(notation.ascii)
            };
            let run = script::check_files(&files, &opts);
            for error in &run.errors {
                console::err(error);
            }
            Ok((script::render_text(&run), run.exit_code()))
        }
        Some(Command::Show { program, notation, compilation }) => {
            let opts = Options {
                timers: compilation.model(),
                plcopen: compilation.selection(),
                ..opts(notation.ascii)
            };
            report::show_program(&program, &opts).map(|t| (t, 0))
        }
        Some(Command::Export { program, properties, aiger, only, compilation }) => {
            let opts = Options {
                timers: compilation.model(),
                plcopen: compilation.selection(),
                only,
                ..Options::default()
            };
            let binary = aiger.ends_with(".aig");
            report::aiger::export_aiger(&program, &properties, &opts, binary, false).and_then(
                |model| {
                    report::export::write_whole(&aiger, &model.bytes)?;
                    let what = if aiger == "-" { "the AIGER model" } else { aiger.as_str() };
                    console::err(&format!("wrote {what}: {}\n", model.summary));
                    Ok((String::new(), 0))
                },
            )
        }
        Some(Command::Completions { shell, install }) => {
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "ii-prove", &mut script);
            let script = String::from_utf8_lossy(&script).into_owned();
            if install {
                install_completions(shell, &script).map(|t| (t, 0))
            } else {
                Ok((script, 0))
            }
        }
        Some(Command::Man) => {
            let mut page = Vec::new();
            match clap_mangen::Man::new(Cli::command()).render(&mut page) {
                Ok(()) => Ok((String::from_utf8_lossy(&page).into_owned(), 0)),
                Err(e) => Err(report::InputError { rendered: format!("error: {e}\n") }),
            }
        }
        Some(Command::Equiv {
            a,
            b,
            map,
            outputs,
            timers_b,
            cycle_b,
            order_b,
            any_state,
            common,
        }) => {
            let b_plcopen = ii_prove::ladder::plcopen::Selection {
                cycle_us: cycle_b.or(common.compilation.cycle),
                order: order_b.map(Order::choice).or(common.compilation.selection().order),
                ..common.compilation.selection()
            };
            let equiv = report::equiv::EquivOptions {
                map,
                outputs,
                b_timers: timers_b.map(Timers::model),
                b_plcopen: Some(b_plcopen),
                any_state,
            };
            let run = Run { files: vec![a.clone(), b.clone()], equiv: Some((a, b, equiv)) };
            return prove(run, common);
        }
        None => {
            let run = Run { files: cli.files, equiv: None };
            return prove(run, cli.common);
        }
    };
    match result {
        Ok((text, code)) => {
            console::out(&text);
            if !text.is_empty() && !text.ends_with('\n') {
                console::out("\n");
            }
            ExitCode::from(code as u8)
        }
        Err(e) => {
            console::err(&e.rendered);
            ExitCode::from(2)
        }
    }
}

/// What a reported run checks: a program's (or free signals') properties, or two
/// programs' equivalence.
struct Run {
    /// The files on the command line.
    files: Vec<String>,
    /// `equiv A B`: the two programs and what to compare.
    equiv: Option<(String, String, report::equiv::EquivOptions)>,
}

/// `ii-prove [OPTIONS] FILES…` and `ii-prove equiv A B`: proves every property, printing
/// each result as it is known.
fn prove(run: Run, common: Common) -> ExitCode {
    let Common { head, notation, compilation, tail } = common;
    let fail = |e: report::InputError| {
        console::err(&e.rendered);
        ExitCode::from(2)
    };
    if run.files.is_empty() {
        console::err(
            "error: no input files\n\nUsage: ii-prove [OPTIONS] [FILES]...\nFor more information, try '--help'.\n",
        );
        return ExitCode::from(2);
    }
    let opts = Options {
        trace: head.trace || head.trace_all,
        trace_all: head.trace_all,
        ascii: notation.ascii,
        timeout: tail.timeout,
        only: tail.only.clone(),
        deny_vacuous: tail.deny.contains(&Deny::Vacuous),
        timers: compilation.model(),
        plcopen: compilation.selection(),
        jobs: tail.jobs.map_or_else(
            || std::thread::available_parallelism().map_or(1, usize::from),
            usize::from,
        ),
        proof_text: head.trace
            || head.trace_all
            || head.json
            || matches!(head.format, Format::Json | Format::Html)
            || tail.html.is_some(),
        run_signals: head.json || matches!(head.format, Format::Json),
        equations: matches!(head.format, Format::Html) || tail.html.is_some(),
    };
    let format = if head.json { Format::Json } else { head.format };
    let outputs = report::export::Outputs {
        vcd: tail.vcd.as_deref(),
        wavedrom: tail.wavedrom.as_deref(),
        html: tail.html.as_deref(),
    };
    if let Err(e) = report::export::check_outputs(&outputs) {
        return fail(e);
    }
    let inputs = match &run.equiv {
        Some((a, b, _)) => report::Inputs { program: Some(a.clone()), properties: vec![b.clone()] },
        None => match report::classify(&run.files) {
            Ok(inputs) => inputs,
            Err(e) => return fail(e),
        },
    };
    let color = match tail.color {
        Color::Always => true,
        Color::Never => false,
        Color::Auto => std::io::stdout().is_terminal() && std::env::var_os("NO_COLOR").is_none(),
    };
    let mut console = Console::new(
        inputs.program.clone(),
        inputs.properties.clone(),
        &opts,
        ConsoleOptions {
            format,
            paint: Paint { enabled: color && format == Format::Text },
            quiet: tail.quiet,
            progress: true,
            results_to_stderr: outputs.to_stdout(),
            files_after: outputs.any(),
        },
    );
    console.exit_on_interrupt();
    let run = match (&run.equiv, &inputs.program) {
        (Some((a, b, equiv)), _) => report::equiv::run_equiv_with(a, b, &opts, equiv, &mut console),
        (None, Some(program)) => {
            report::run_program_with(program, &inputs.properties, &opts, &mut console)
        }
        (None, None) => report::run_free_with(&inputs.properties, &opts, &mut console),
    };
    let run = match run {
        Ok(run) => run,
        Err(e) => return fail(e),
    };
    console.finish(&run);
    if let Err(e) = report::export::write_files(&run, &outputs) {
        return fail(e);
    }
    ExitCode::from(u8::from(run.summary.fails(opts.deny_vacuous)))
}
