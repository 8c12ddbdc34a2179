//! Regenerates the "Solvers" chapter's tables and figure.
fn main() -> iga_contact::Result<()> {
    let dir = iga_contact::studies::default_dir("solvers");
    iga_contact::studies::solvers::run(&dir)?;
    for f in ["solvers.md", "timings.md"] {
        println!(
            "{}",
            std::fs::read_to_string(dir.join(f)).unwrap_or_default()
        );
    }
    Ok(())
}
