//! The `bdi-check` command line: argument parsing and dispatch, nothing else.

use bdi_check::report::{self, Format};
use clap::{Parser, Subcommand, ValueEnum};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

/// Verifies Jason AgentSpeak plan libraries before they run on a robot.
#[derive(Parser, Debug)]
#[command(name = "bdi-check", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Output formats.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum FormatArg {
    /// Text for people.
    Human,
    /// The JSON report.
    Json,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Parse AgentSpeak (.asl) files and report every error.
    Parse {
        /// The files to parse.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Output format.
        #[arg(long, value_enum, default_value = "human")]
        format: FormatArg,
        /// Write the report to this file instead of stdout.
        #[arg(short = 'o', long = "output")]
        output: Option<PathBuf>,
        /// Print the verdict line only.
        #[arg(short, long)]
        quiet: bool,
    },
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // clap's usage errors are bad input: exit 2, as SPEC §2 asks (help and version: 0).
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    match cli.command {
        Command::Parse {
            files,
            format,
            output,
            quiet,
        } => {
            let run = report::outline::parse_files(&files);
            let format = match format {
                FormatArg::Human => Format::Human,
                FormatArg::Json => Format::Json,
            };
            let color = output.is_none() && std::io::stdout().is_terminal();
            let (mut out, err) = report::outline::render(&run, format, color);
            if quiet && matches!(format, Format::Human) {
                out = out
                    .lines()
                    .last()
                    .map(|l| format!("{l}\n"))
                    .unwrap_or_default();
            }
            eprint!("{err}");
            let code = run.report.verdict.exit_code();
            match emit(&out, output) {
                Ok(()) => ExitCode::from(code as u8),
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            }
        }
    }
}

/// Writes the report to `-o FILE` or stdout.
fn emit(text: &str, output: Option<PathBuf>) -> std::io::Result<()> {
    match output {
        Some(path) => std::fs::write(&path, text).map_err(|e| {
            std::io::Error::new(e.kind(), format!("cannot write `{}`: {e}", path.display()))
        }),
        None => {
            let mut stdout = std::io::stdout().lock();
            stdout.write_all(text.as_bytes())?;
            stdout.flush()
        }
    }
}
