//! Reading the ParaView collections (`.pvd`) that runs write, in tests.

/// The `file="..."` entries of a `.pvd` collection's text, in order.
pub fn files(pvd: &str) -> Vec<String> {
    pvd.lines()
        .filter_map(|l| l.split("file=\"").nth(1))
        .filter_map(|l| l.split('"').next())
        .map(str::to_string)
        .collect()
}
