//! `automat corpus`: measure how much of a body of real code checks and
//! runs (see `corpus/mod.rs` and docs/realcode.md).

use crate::corpus::{self, report, Options};
use crate::Outcome;
use automat_scenario::conformance::Backend;
use clap::Args;
use std::path::PathBuf;

/// Measure a corpus of code written elsewhere: per source folder, the files
/// and POUs that check clean, the diagnostics by code, and the examples
/// (files opening with a conformance header: `expect:` …) run for their
/// documented values.
///
/// In each SOURCE folder a file is a project of its own and a sub-folder
/// one project of all its files (`--whole`: the folder is one project). A
/// POU is clean when no error falls in it. Prints one block per source and
/// the totals (`--json`: the same figures as JSON). Exits with 0 when no
/// example failed (unclean code is a measurement, not a failure), 1 when
/// one did, 2 when a path cannot be read or the command line is wrong.
#[derive(Args)]
pub struct CorpusArgs {
    /// Source folders (or files), each measured and reported on its own.
    #[arg(required = true, value_name = "SOURCE")]
    sources: Vec<PathBuf>,
    /// Use a dialect for every source (repeatable), as `automat check --lib`.
    #[arg(long = "lib", value_name = "NAME")]
    libs: Vec<String>,
    /// Check each SOURCE as one project (a library whose files use each
    /// other, however they are arranged in folders).
    #[arg(long)]
    whole: bool,
    /// Print the figures as JSON.
    #[arg(long)]
    json: bool,
    /// How many of the most frequent diagnostic codes to list per source.
    #[arg(long, value_name = "N", default_value_t = 10)]
    top: usize,
    /// The backend that runs the examples.
    #[arg(long, value_enum, default_value_t = crate::engines::EngineKind::Jit)]
    engine: crate::engines::EngineKind,
}

pub fn run(args: &CorpusArgs) -> Outcome {
    if let Err(e) = automat_dialect::parse_names(&args.libs) {
        eprintln!("error: --lib: {e}");
        return Outcome::BadInput;
    }
    let opts = Options {
        libraries: args.libs.clone(),
        whole: args.whole,
        backend: match args.engine {
            crate::engines::EngineKind::Interp => Backend::Interp,
            crate::engines::EngineKind::Jit => Backend::Jit,
        },
    };
    let sources = match corpus::measure(&args.sources, &opts) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return Outcome::BadInput;
        }
    };
    if args.json {
        println!("{}", report::json(&sources));
    } else {
        print!("{}", report::text(&sources, args.top));
    }
    if report::total(&sources).failed > 0 {
        Outcome::ProgramErrors
    } else {
        Outcome::Ok
    }
}
