//! The library type `OutputSet`: a commit replaces the whole set and lists
//! it in the manifest, an i/o failure part-way leaves the earlier set byte
//! for byte, staging of a dead owner is removed, names outside the set are
//! refused.

use crate::{commit, snapshot, staging_left, workdir};
use iga_contact::report::atomic::{read_manifest, OutputSet, MANIFEST};
use iga_contact::Error;

#[test]
fn a_commit_replaces_the_whole_set_and_lists_it_in_the_manifest() {
    let target = workdir("replace").join("out");
    commit(
        &target,
        &[("a.csv", b"1"), ("b.svg", b"2"), ("c.vtu", b"3")],
    );
    let files = commit(&target, &[("a.csv", b"new"), ("sub/d.md", b"4")]);
    assert_eq!(files, vec![target.join("a.csv"), target.join("sub/d.md")]);
    let snap = snapshot(&target);
    let names: Vec<&str> = snap.keys().map(String::as_str).collect();
    // b.svg and c.vtu belonged to the earlier set: gone, not mixed in.
    assert_eq!(names, vec![MANIFEST, "a.csv", "sub/d.md"]);
    assert_eq!(snap["a.csv"], b"new");
    assert_eq!(read_manifest(&target).unwrap(), vec!["a.csv", "sub/d.md"]);
    assert!(staging_left(&target).is_empty());
}

#[test]
fn an_io_failure_part_way_through_leaves_the_earlier_set_byte_for_byte() {
    let target = workdir("io-failure").join("out");
    commit(&target, &[("one.csv", b"old 1"), ("two.csv", b"old 2")]);
    let before = snapshot(&target);
    // A producer whose k-th file fails half-way (disk full), for every k.
    for k in 0..4 {
        let mut set = OutputSet::begin(&target).unwrap();
        let mut failure = None;
        for i in 0..4 {
            let name = format!("file{i}.csv");
            let r = set.stage_with(&name, |w| {
                w.write_all(b"the first half, ")?;
                if i == k {
                    return Err(std::io::Error::from_raw_os_error(28)); // ENOSPC
                }
                w.write_all(b"the second half")
            });
            if let Err(e) = r {
                failure = Some(e);
                break;
            }
        }
        let e = failure.expect("the k-th file fails");
        assert!(matches!(e, Error::Io { .. }), "{e}");
        assert!(e.to_string().contains(&format!("file{k}.csv")), "{e}");
        drop(set);
        assert_eq!(
            snapshot(&target),
            before,
            "k = {k}: the earlier set changed"
        );
        assert!(staging_left(&target).is_empty(), "k = {k}: staging left");
    }
}

#[test]
fn staging_of_a_dead_owner_is_removed_by_the_next_set() {
    let target = workdir("stale").join("out");
    commit(&target, &[("a.csv", b"1")]);
    let before = snapshot(&target);
    // What a SIGKILL leaves: a staging directory with a half-written file,
    // and its lock file, which no living process holds.
    let parent = target.parent().unwrap();
    let stale = parent.join(".out.staging-999999-1");
    std::fs::create_dir_all(&stale).unwrap();
    std::fs::write(stale.join("a.csv"), "half").unwrap();
    std::fs::write(parent.join(".out.staging-999999-1.lock"), "").unwrap();
    // ... and one whose lock file was never made.
    std::fs::create_dir_all(parent.join(".out.staging-999999-2")).unwrap();
    assert_eq!(snapshot(&target), before);
    // A living set's staging is not touched by another set's clean-up.
    let alive = OutputSet::begin(&target).unwrap();
    assert_eq!(
        staging_left(&target).len(),
        2,
        "{:?}",
        staging_left(&target)
    );
    let other = OutputSet::begin(&target).unwrap();
    assert!(alive.dir().is_dir());
    drop(other);
    drop(alive);
    assert!(staging_left(&target).is_empty());
    assert_eq!(snapshot(&target), before);
}

#[test]
fn names_outside_the_set_are_refused() {
    let target = workdir("names").join("out");
    let mut set = OutputSet::begin(&target).unwrap();
    for bad in ["../escape.csv", "/abs.csv", "", MANIFEST, "a/../../b"] {
        assert!(set.stage(bad, b"x").is_err(), "{bad:?} accepted");
    }
}
