//! `automat passwd NAME`: an argon2id hash of a password, as the
//! `[users.NAME]` table of `automat.toml` takes it.

use crate::Outcome;
use clap::Args;
use std::io::BufRead;

/// Make a user entry for automat.toml (the network API of `automat run
/// --listen`): reads the password from the first line of standard input
/// and prints a `[users.NAME]` table with its argon2id hash. The password
/// itself is never stored or printed.
#[derive(Args)]
pub struct PasswdArgs {
    /// The user's name.
    #[arg(value_name = "NAME")]
    name: String,
    /// viewer (read, browse, watch), operator (+ write, force) or
    /// engineer (+ run control).
    #[arg(long, default_value = "viewer")]
    role: String,
}

pub fn run(args: &PasswdArgs) -> Outcome {
    if !automat_project::file::ROLES.contains(&args.role.as_str()) {
        eprintln!(
            "error: --role {}: not viewer, operator or engineer",
            args.role
        );
        return Outcome::BadInput;
    }
    let valid_name = !args.name.is_empty()
        && args
            .name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if !valid_name {
        eprintln!("error: a user name is letters, digits, `_` and `-`");
        return Outcome::BadInput;
    }
    let mut line = String::new();
    if let Err(e) = std::io::stdin().lock().read_line(&mut line) {
        eprintln!("error: reading the password: {e}");
        return Outcome::BadInput;
    }
    let password = line.trim_end_matches(['\n', '\r']);
    if password.len() < 8 {
        eprintln!("error: the password must be at least 8 characters long");
        return Outcome::BadInput;
    }
    match automat_online::hash_password(password) {
        Ok(hash) => {
            println!(
                "[users.{}]\nrole = \"{}\"\npassword = \"{hash}\"",
                args.name, args.role
            );
            Outcome::Ok
        }
        Err(e) => {
            eprintln!("error: {e}");
            Outcome::BadInput
        }
    }
}
