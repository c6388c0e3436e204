//! "Did you mean …?": the visible name nearest to a misspelt one.
//!
//! IEC names are case-insensitive, so distances are taken on ASCII
//! lower case. The edit distance counts insertions, deletions,
//! substitutions and swaps of two neighbours (optimal string alignment:
//! `Motro` → `Motor` is one edit). A name is offered when it is within
//! about a third of the typed length (at least one edit, at most three),
//! so `x` does not suggest `y` while `MotorRuning` suggests
//! `MotorRunning`; among equally near names the one listed first wins, so
//! callers list the nearest scope first. A namespace's item written
//! without its namespace (`Clamp` for `Motion.Clamp`) is the nearest.

/// The nearest of `candidates` to `typed`, if near enough.
pub fn nearest<'a>(typed: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let t = typed.to_ascii_lowercase();
    let limit = (t.chars().count() / 3).clamp(1, 3);
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        if c.eq_ignore_ascii_case(typed) || c.starts_with("__") {
            continue;
        }
        // An item of a namespace (`Motion.Clamp`, from
        // `desugar_namespaces`) named without its namespace: the nearest.
        let unqualified = c
            .rsplit_once('.')
            .is_some_and(|(_, last)| last.eq_ignore_ascii_case(typed));
        let d = if unqualified {
            Some(0)
        } else {
            distance(&t, &c.to_ascii_lowercase(), limit)
        };
        let Some(d) = d else {
            continue;
        };
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c)
}

/// The optimal-string-alignment distance of `a` and `b`, or `None` when
/// it is above `limit` (cut short: names are short, candidates many).
fn distance(a: &str, b: &str, limit: usize) -> Option<usize> {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    if a.len().abs_diff(b.len()) > limit {
        return None;
    }
    let w = b.len() + 1;
    let mut d = vec![0usize; (a.len() + 1) * w];
    for (j, cell) in d.iter_mut().take(w).enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        d[i * w] = i;
        let mut row_min = usize::MAX;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[(i - 1) * w + j] + 1)
                .min(d[i * w + j - 1] + 1)
                .min(d[(i - 1) * w + j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[(i - 2) * w + j - 2] + 1);
            }
            d[i * w + j] = v;
            row_min = row_min.min(v);
        }
        if row_min > limit {
            return None;
        }
    }
    let v = d[a.len() * w + b.len()];
    (v <= limit).then_some(v)
}

/// `; did you mean `X`?` or nothing: appended to an "unknown name" message.
pub fn did_you_mean<'a>(typed: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    nearest(typed, candidates).map_or_else(String::new, |c| format!("; did you mean `{c}`?"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_names_are_offered_and_far_ones_not() {
        let names = ["MotorRunning", "MotorSpeed", "Start", "x"];
        assert_eq!(nearest("MotorRuning", names), Some("MotorRunning"));
        assert_eq!(nearest("motorrunnign", names), Some("MotorRunning"));
        assert_eq!(nearest("Strat", names), Some("Start"));
        assert_eq!(nearest("y", names), Some("x"));
        assert_eq!(nearest("Stop", names), None);
        assert_eq!(nearest("Speed", names), None);
        // The name itself (another spelling of it) is not a suggestion.
        assert_eq!(nearest("START", ["Start"]), None);
        // The first of equally near names wins.
        assert_eq!(nearest("ab", ["ac", "ad"]), Some("ac"));
        assert_eq!(
            did_you_mean("lamb", ["lamp", "flashes"]),
            "; did you mean `lamp`?"
        );
        assert_eq!(did_you_mean("zzz", ["lamp"]), "");
        // Generated names never.
        assert_eq!(nearest("__sfc1", ["__sfc"]), None);
        // A namespace's item named without its namespace.
        assert_eq!(
            nearest("clamp", ["Clump", "Motion.Clamp"]),
            Some("Motion.Clamp")
        );
    }
}
