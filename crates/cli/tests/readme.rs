//! The README's first program does what the README says, and the
//! documentation's relative links lead to files that exist.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn automat(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run automat")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The text of the first fenced block of `lang` after `heading`.
fn block_after(text: &str, heading: &str, lang: &str) -> String {
    let from = text.find(heading).expect("heading in README");
    let fence = format!("```{lang}\n");
    let start = from + text[from..].find(&fence).expect("code block") + fence.len();
    let len = text[start..].find("```").expect("end of block");
    text[start..start + len].to_string()
}

#[test]
fn the_first_program_of_the_readme_runs_as_shown() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let heading = "## Your first program in five minutes";
    let program = block_after(&readme, heading, "iecst");
    let commands = block_after(&readme, heading, "sh");
    let dir = std::env::temp_dir().join(format!("automat-readme-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("blink.st"), &program).expect("blink.st");

    let check = automat(&dir, &["check", "blink.st"]);
    assert_eq!(check.status.code(), Some(0));
    assert_eq!(stdout(&check), "");
    assert!(commands.contains("automat check blink.st"));

    let run = automat(
        &dir,
        &[
            "run",
            "blink.st",
            "--duration",
            "5s",
            "--print",
            "Main.lamp",
            "--print",
            "Main.flashes",
        ],
    );
    assert_eq!(run.status.code(), Some(0));
    assert_eq!(stdout(&run), "Main.lamp = FALSE\nMain.flashes = 2\n");
    assert!(commands.contains("--print Main.lamp --print Main.flashes"));
    assert!(commands.contains("# Main.lamp = FALSE, Main.flashes = 2"));

    let trace = automat(
        &dir,
        &[
            "run",
            "blink.st",
            "--duration",
            "5s",
            "--trace",
            "Main.lamp,Main.t.ET",
            "--trace-file",
            "blink.csv",
        ],
    );
    assert_eq!(trace.status.code(), Some(0));
    let csv = std::fs::read_to_string(dir.join("blink.csv")).expect("blink.csv");
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("time,Main.lamp,Main.t.ET"));
    assert_eq!(lines.next(), Some("T#0s,FALSE,T#0s"));
    assert_eq!(csv.lines().count(), 501);
    assert!(commands.contains("--trace Main.lamp,Main.t.ET --trace-file blink.csv"));

    let plot = automat(&dir, &["plot", "blink.csv", "-o", "blink.svg"]);
    assert_eq!(plot.status.code(), Some(0));
    let svg = std::fs::read_to_string(dir.join("blink.svg")).expect("blink.svg");
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"));
    assert!(commands.contains("automat plot blink.csv -o blink.svg"));

    let test = automat(&dir, &["test", "blink.st"]);
    assert_eq!(test.status.code(), Some(0));
    assert!(
        stdout(&test).starts_with("ok blink.st\n"),
        "{}",
        stdout(&test)
    );
    assert!(commands.contains("automat test blink.st"));

    // The typo the README shows, and its message word for word.
    let typo = program.replace("        lamp := NOT lamp;", "        lamb := NOT lamp;");
    assert_ne!(typo, program);
    std::fs::write(dir.join("blink.st"), typo).expect("blink.st");
    let bad = automat(&dir, &["check", "blink.st"]);
    assert_eq!(bad.status.code(), Some(1));
    let first = stdout(&bad).lines().next().unwrap_or_default().to_string();
    assert_eq!(
        first,
        "blink.st:16:9: error[E020]: unknown variable `lamb` in `Main`; did you mean `lamp`?"
    );
    assert!(readme.contains(&first.replace('\n', " ")));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The Markdown files a reader follows links in.
fn documents() -> Vec<PathBuf> {
    let root = root();
    let mut docs = vec![root.join("README.md"), root.join("ARCHITECTURE.md")];
    for folder in ["docs", "examples", "tests"] {
        let mut stack = vec![root.join(folder)];
        while let Some(dir) = stack.pop() {
            let Ok(entries) = std::fs::read_dir(&dir) else {
                continue;
            };
            for e in entries.flatten() {
                let p = e.path();
                if p.is_dir() {
                    stack.push(p);
                } else if p.extension().is_some_and(|x| x == "md") {
                    docs.push(p);
                }
            }
        }
    }
    docs
}

/// The targets of `[text](target)` links, without web addresses and
/// anchors within the page.
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        let Some(end) = rest.find(')') else { break };
        let target = &rest[..end];
        rest = &rest[end..];
        let target = target.split('#').next().unwrap_or_default();
        if target.is_empty() || target.contains("://") || target.starts_with("mailto:") {
            continue;
        }
        out.push(target.to_string());
    }
    out
}

#[test]
fn relative_links_in_the_documentation_lead_to_files() {
    let mut broken = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap_or_default();
        let dir = doc.parent().unwrap_or(Path::new("."));
        for target in links(&text) {
            if !dir.join(&target).exists() {
                broken.push(format!("{}: {target}", doc.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// Files named as `docs/NAME.md` in the text (not as links) exist too: the
/// README and the examples mention pages that way.
#[test]
fn docs_pages_named_in_the_text_exist() {
    let mut missing = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap_or_default();
        let mut rest = text.as_str();
        while let Some(i) = rest.find("docs/") {
            let tail = &rest[i + 5..];
            let len = tail
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == '_' || c == '.'))
                .unwrap_or(tail.len());
            let name = tail[..len].trim_end_matches('.');
            if name.ends_with(".md") && !root().join("docs").join(name).exists() {
                missing.push(format!("{}: docs/{name}", doc.display()));
            }
            rest = &tail[len..];
        }
    }
    // The shared digest and rules of the founders live outside the repository.
    missing.retain(|m| !m.contains("processes.md") && !m.contains("architecture.md"));
    assert!(missing.is_empty(), "missing pages:\n{}", missing.join("\n"));
}
