//! `automat explain`: what a diagnostic code means.

use crate::Outcome;
use automat_base::codes::{self, Code};
use clap::Args;

/// Explain a diagnostic code (`automat explain E030`), or list them all.
#[derive(Args)]
pub struct ExplainArgs {
    /// The code, e.g. E030.
    #[arg(value_name = "CODE", required_unless_present = "list")]
    code: Option<String>,
    /// List every code with its title (as Markdown, the source of docs/diagnostics.md).
    #[arg(long)]
    list: bool,
}

pub fn run(args: &ExplainArgs) -> Outcome {
    if args.list {
        print!("{}", codes::markdown());
        return Outcome::Ok;
    }
    let Some(text) = &args.code else {
        return Outcome::BadInput;
    };
    match Code::parse(text) {
        Some(code) => {
            println!("{}: {}\n\n{}", code.as_str(), code.title(), code.explain());
            Outcome::Ok
        }
        None => {
            eprintln!("error: unknown diagnostic code `{text}` (see `automat explain --list`)");
            Outcome::BadInput
        }
    }
}
