//! Regenerates the "IGA against FEM" chapter's tables and figure.
fn main() -> iga_contact::Result<()> {
    let dir = iga_contact::studies::default_dir("iga_vs_fem");
    iga_contact::studies::iga_vs_fem::run(&dir)?;
    for f in ["comparison.md", "timings.md"] {
        println!(
            "{}",
            std::fs::read_to_string(dir.join(f)).unwrap_or_default()
        );
    }
    Ok(())
}
