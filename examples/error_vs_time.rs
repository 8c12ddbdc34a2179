//! Regenerates the "Accuracy per second" chapter's tables and figures.
fn main() -> iga_contact::Result<()> {
    let dir = iga_contact::studies::default_dir("error_vs_time");
    iga_contact::studies::error_vs_time::run(&dir)?;
    for f in ["reference.md", "runs.md", "accuracy_per_second.md"] {
        println!(
            "{}",
            std::fs::read_to_string(dir.join(f)).unwrap_or_default()
        );
    }
    Ok(())
}
