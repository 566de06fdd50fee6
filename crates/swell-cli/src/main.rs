//! `swell`: render, export and bake water scenes from the command line.
//!
//! Raw arguments ([`args`]) are parsed apart from the resolved configuration each command builds;
//! the commands themselves live in [`cmd`], one file each.

mod args;
mod bench;
mod cmd;
mod interrupt;
mod thread_pool;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = args::Cli::parse();
    match cmd::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // User text in the message (keys, values, paths) is escaped and cut (issue 37).
            eprintln!("error: {}", swell::error::printable(&e.to_string()));
            ExitCode::FAILURE
        }
    }
}
