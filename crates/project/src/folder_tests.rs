use super::*;
use std::os::unix::fs::symlink;

/// A fresh folder under the system's temporary folder.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-folder-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn st(walk: &mut Walk, root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut keep = |e: Entry| match e {
        Entry::Dir(_) => true,
        Entry::File(p) => p.extension().is_some_and(|x| x == "st"),
    };
    walk.dir(root, &mut keep, &mut out).unwrap();
    out
}

#[test]
fn a_link_to_the_parent_folder_is_not_followed() {
    let d = scratch("up");
    std::fs::write(d.join("a.st"), "").unwrap();
    std::fs::create_dir(d.join("sub")).unwrap();
    std::fs::write(d.join("sub/b.st"), "").unwrap();
    symlink("..", d.join("sub/up")).unwrap();
    let mut w = Walk::new();
    assert_eq!(st(&mut w, &d), vec![d.join("a.st"), d.join("sub/b.st")]);
    assert_eq!(
        w.skipped(),
        &[Skipped {
            path: d.join("sub/up"),
            first: d.clone(),
            is_loop: true
        }]
    );
    assert_eq!(
        w.warning().unwrap(),
        format!(
            "warning: {}: a symbolic link back to {} (a loop): not followed",
            d.join("sub/up").display(),
            d.display()
        )
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn two_links_into_each_other_end_and_read_each_file_once() {
    let d = scratch("pair");
    std::fs::create_dir(d.join("a")).unwrap();
    std::fs::create_dir(d.join("b")).unwrap();
    std::fs::write(d.join("a/x.st"), "").unwrap();
    std::fs::write(d.join("b/y.st"), "").unwrap();
    symlink("../b", d.join("a/to_b")).unwrap();
    symlink("../a", d.join("b/to_a")).unwrap();
    let mut w = Walk::new();
    // a, then b through a/to_b (b/to_a leads back into a: a loop), then b
    // itself is already searched.
    assert_eq!(
        st(&mut w, &d),
        vec![d.join("a/to_b/y.st"), d.join("a/x.st")]
    );
    assert_eq!(
        w.skipped(),
        &[
            Skipped {
                path: d.join("a/to_b/to_a"),
                first: d.join("a"),
                is_loop: true
            },
            Skipped {
                path: d.join("b"),
                first: d.join("a/to_b"),
                is_loop: false
            },
        ]
    );
    assert_eq!(
        w.warning().unwrap(),
        format!(
            "warning: {}: a symbolic link back to {} (a loop): not followed (and 1 more)",
            d.join("a/to_b/to_a").display(),
            d.join("a").display()
        )
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_second_name_for_a_file_or_a_root_is_not_read_again() {
    let d = scratch("again");
    std::fs::write(d.join("a.st"), "").unwrap();
    symlink("a.st", d.join("b.st")).unwrap();
    let mut w = Walk::new();
    assert_eq!(st(&mut w, &d), vec![d.join("a.st")]);
    // The same root given twice yields nothing the second time.
    assert_eq!(st(&mut w, &d), Vec::<PathBuf>::new());
    assert_eq!(w.skipped().len(), 2);
    assert_eq!(
        w.warning().unwrap(),
        format!(
            "warning: {}: already read as {}: not read again (and 1 more)",
            d.join("b.st").display(),
            d.join("a.st").display()
        )
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn nothing_skipped_means_no_warning() {
    let d = scratch("plain");
    std::fs::write(d.join("a.st"), "").unwrap();
    std::fs::write(d.join("notes.txt"), "").unwrap();
    let mut w = Walk::new();
    assert_eq!(st(&mut w, &d), vec![d.join("a.st")]);
    assert_eq!(w.warning(), None);
    std::fs::remove_dir_all(&d).unwrap();
}
