//! The `twoball` command: parses arguments and hands over to [`twoball::cli`].

fn main() {
    std::process::exit(twoball::cli::main());
}
