//! Regenerates the stability atlas (`book/src/generated/stability/`).
fn main() {
    let out = iga_contact::studies::default_dir("stability");
    if let Err(e) = iga_contact::studies::stability::run(&out) {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
    println!(
        "{}",
        std::fs::read_to_string(out.join("penalty_ranges.md")).unwrap_or_default()
    );
}
