//! The `ii-prove` command line: parses arguments and hands over to the library.

use std::process::ExitCode;
use std::time::Duration;

use clap::{Parser, Subcommand};
use ii_prove::ladder::TimerModel;
use ii_prove::report::{self, Options};
use ii_prove::{repl, script};

const EXIT_CODES: &str = "\
Exit status:
  0  every property was proved
  1  some property was refuted or is unknown
  2  bad input or usage (nothing was proved from that input)";

/// Proves safety properties of ladder programs in the II algebra of binary signals.
///
/// `ii-prove PROGRAM.ld PROPS.ii` proves the properties of PROPS.ii about the
/// compiled program; `ii-prove FILE.ii…` proves properties about the free
/// signals the files declare with `input`.
///
/// A property of a program holds when, on every run, it holds at every scan up to
/// which the `assume` statements have held (hypotheses hold "up to now"). Each rung
/// is compiled to what the PLC does on every scan; timers count scans as the
/// runtime does (see --timers). Programs with control flow (GOTO, GOSUB,
/// SUBPROG/ENDSUB, RETURN, LOCK, SLEEP) are refused with a located error.
#[derive(Parser)]
#[command(name = "ii-prove", version, after_help = EXIT_CODES, args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// A ladder program (.ld) and property files (.ii), or property files alone.
    files: Vec<String>,
    /// Print each kernel-checked proof as a calculation.
    #[arg(long, global = true)]
    trace: bool,
    /// Write the report as JSON.
    #[arg(long, global = true)]
    json: bool,
    /// Use ASCII notation (`.`, `!`, `=>`) and ASCII diagrams.
    #[arg(long, global = true)]
    ascii: bool,
    /// Time limit per property, in seconds.
    #[arg(long, global = true, default_value_t = 10.0, value_name = "SECONDS")]
    timeout: f64,
    /// How a program's TON/TOF timers are compiled: `plc`, exactly the scans the
    /// runtime counts (P = floor(delay / cycle) + adjust, so an LDmicro0.1 timer is one
    /// scan early); `ideal`, the paper's idealisation, the delay as written.
    #[arg(long, global = true, value_enum, default_value_t = Timers::Plc)]
    timers: Timers,
    /// Write the counterexamples as a Value Change Dump (GTKWave).
    #[arg(long, value_name = "FILE")]
    vcd: Option<String>,
    /// Write the counterexamples as WaveDrom JSON.
    #[arg(long, value_name = "FILE")]
    wavedrom: Option<String>,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum Timers {
    Plc,
    Ideal,
}

#[derive(Subcommand)]
enum Command {
    /// List every law the prover may use, with its name and file.
    Axioms,
    /// Check proof scripts: every theorem and lemma, step by step, by the kernel.
    Check {
        /// Proof scripts (.ii files with `theorem`/`lemma` statements).
        #[arg(required = true)]
        files: Vec<String>,
    },
    /// The interactive prover: state goals and prove them step by step (`help` inside).
    Repl {
        /// A .ii file to load first.
        file: Option<String>,
    },
    /// Print a ladder program's compiled equations and bounds as `.ii` text.
    Show {
        /// The ladder program (.ld).
        program: String,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if !(cli.timeout.is_finite() && cli.timeout > 0.0) {
        eprintln!("error: --timeout must be a positive number of seconds");
        return ExitCode::from(2);
    }
    let opts = Options {
        trace: cli.trace,
        json: cli.json,
        ascii: cli.ascii,
        timeout: Duration::from_secs_f64(cli.timeout.min(1e6)),
        timers: match cli.timers {
            Timers::Plc => TimerModel::Plc,
            Timers::Ideal => TimerModel::Ideal,
        },
    };
    let result = match cli.command {
        Some(Command::Axioms) => report::list_axioms(&opts).map(|text| (text, 0)),
        Some(Command::Repl { file }) => {
            let result = if std::io::IsTerminal::is_terminal(&std::io::stdin()) {
                repl::run_interactive(file.as_deref())
            } else {
                repl::repl_with(std::io::stdin().lock(), std::io::stdout(), false, file.as_deref())
            };
            return match result {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            };
        }
        Some(Command::Check { files }) => {
            let run = script::check_files(&files, &opts);
            for error in &run.errors {
                eprint!("{error}");
            }
            Ok((script::render_text(&run), run.exit_code()))
        }
        Some(Command::Show { program }) => report::show_program(&program, &opts).map(|t| (t, 0)),
        None if cli.files.is_empty() => {
            eprintln!(
                "error: no input files\n\nUsage: ii-prove [OPTIONS] [FILES]...\nFor more information, try '--help'."
            );
            return ExitCode::from(2);
        }
        None => match cli.files.split_first() {
            Some((program, props)) if program.ends_with(".ld") => {
                report::run_program(program, props, &opts)
            }
            _ => report::run_free(&cli.files, &opts),
        }
        .and_then(|r| {
            report::export::write_files(&r, cli.vcd.as_deref(), cli.wavedrom.as_deref())?;
            let text =
                if opts.json { report::render_json(&r) } else { report::render_text(&r, &opts) };
            Ok((text, r.exit_code()))
        }),
    };
    match result {
        Ok((text, code)) => {
            print!("{text}");
            if !text.ends_with('\n') {
                println!();
            }
            ExitCode::from(code as u8)
        }
        Err(e) => {
            eprint!("{}", e.rendered);
            ExitCode::from(2)
        }
    }
}
