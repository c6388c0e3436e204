//! `automat`: the command-line front end.
//!
//! Exit codes are a contract that scripts rely on: 0 ok, 1 the program has
//! errors, 2 bad command line or unreadable input (3 is reserved for runtime
//! faults of `automat run`). A closed stdout or stderr (`| head -1`)
//! changes neither: the output is dropped and the command ends as it
//! would have (see `out.rs`).

// Every print of the binary goes through `out.rs`, which never panics on a
// closed pipe. Defined before the modules, these shadow the standard
// macros in all of them.
macro_rules! print {
    ($($arg:tt)*) => { $crate::out::stdout(format_args!($($arg)*)) };
}
macro_rules! println {
    () => { $crate::out::stdout(format_args!("\n")) };
    ($($arg:tt)*) => { $crate::out::stdout(format_args!("{}\n", format_args!($($arg)*))) };
}
macro_rules! eprint {
    ($($arg:tt)*) => { $crate::out::stderr(format_args!($($arg)*)) };
}
macro_rules! eprintln {
    () => { $crate::out::stderr(format_args!("\n")) };
    ($($arg:tt)*) => { $crate::out::stderr(format_args!("{}\n", format_args!($($arg)*))) };
}

mod cmd_check;
mod cmd_corpus;
mod cmd_explain;
mod cmd_export;
mod cmd_online;
mod cmd_passwd;
mod cmd_plant;
mod cmd_run;
mod cmd_test;
mod corpus;
mod draw;
mod engines;
mod files;
mod junit;
mod live;
mod out;
mod plot;
mod project_run;
mod realtime_run;
mod retain_run;
mod test_pool;
mod test_queue;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// automat — an IEC 61131-3 soft-PLC toolchain.
///
/// Compiles Structured Text programs and reports every error with its
/// location, a code (`automat explain E030`) and a source excerpt.
#[derive(Parser)]
#[command(name = "automat", version, about, long_about = None, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    Check(cmd_check::CheckArgs),
    Corpus(cmd_corpus::CorpusArgs),
    Explain(cmd_explain::ExplainArgs),
    Export(cmd_export::ExportArgs),
    // Boxed: by far the largest set of flags.
    Run(Box<cmd_run::RunArgs>),
    Test(cmd_test::TestArgs),
    Plot(plot::PlotArgs),
    Draw(draw::DrawArgs),
    Passwd(cmd_passwd::PasswdArgs),
    Plant(cmd_plant::PlantArgs),
}

/// Exit status of a command.
pub enum Outcome {
    Ok,
    ProgramErrors,
    BadInput,
    /// A runtime fault stopped the PLC (`automat run`).
    Fault,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // clap prints help/version to stdout (exit 0) and usage errors to stderr (exit 2).
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    let outcome = match cli.command {
        Command::Check(args) => cmd_check::run(&args),
        Command::Corpus(args) => cmd_corpus::run(&args),
        Command::Explain(args) => cmd_explain::run(&args),
        Command::Export(args) => cmd_export::run(&args),
        Command::Run(args) => cmd_run::run_cmd(&args),
        Command::Test(args) => cmd_test::run(&args),
        Command::Plot(args) => plot::run(&args),
        Command::Draw(args) => draw::run(&args),
        Command::Passwd(args) => cmd_passwd::run(&args),
        Command::Plant(args) => cmd_plant::run(&args),
    };
    ExitCode::from(match outcome {
        Outcome::Ok => 0,
        Outcome::ProgramErrors => 1,
        Outcome::BadInput => 2,
        Outcome::Fault => 3,
    })
}
