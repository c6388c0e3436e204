use super::*;
use crate::plot::csv::parse;

const TRACE: &str = "time,b,x,s\n\
T#0s,FALSE,0,A#Up\n\
T#10ms,TRUE,1,A#Up\n\
T#20ms,TRUE,2,A#Right\n\
T#30ms,FALSE,1,A#Right\n";

fn lines_with<'a>(svg: &'a str, start: &str) -> Vec<&'a str> {
    svg.lines().filter(|l| l.starts_with(start)).collect()
}

#[test]
fn a_small_trace_exactly() {
    let svg = render(&parse(TRACE).unwrap());
    assert!(svg.starts_with(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="900" height="198" viewBox="0 0 900 198""#
    ));
    assert!(svg.ends_with("</svg>\n"));
    let paths = lines_with(&svg, "<path");
    assert_eq!(paths.len(), 2);
    // 40 ms over 740 px: 18.5 px per ms; high at y 15, low at y 35
    assert!(
        paths[0].contains(r#"d="M140 35 H325 V15 H695 V35 H880""#),
        "{}",
        paths[0]
    );
    // analog row from y 46: 0 at y 111, 2 at y 51
    assert!(
        paths[1].contains(r#"d="M140 111 L325 81 L510 51 L695 81""#),
        "{}",
        paths[1]
    );
    let rects = lines_with(&svg, "<rect");
    assert_eq!(rects.len(), 3);
    assert!(
        rects[1].contains(r#"x="140" y="125" width="370" height="24""#),
        "{}",
        rects[1]
    );
    assert!(
        rects[2].contains(r#"x="510" y="125" width="370" height="24""#),
        "{}",
        rects[2]
    );
    let texts = lines_with(&svg, "<text");
    assert_eq!(texts.len(), 3 + 2 + 2 + 9);
    let names: Vec<&str> = lines_with(&svg, r#"<text class="name""#);
    assert_eq!(names.len(), 3);
    assert!(names[0].contains(r#"x="132" y="29""#) && names[0].ends_with(">b</text>"));
    let ranges = lines_with(&svg, r#"<text class="range""#);
    assert!(ranges[0].contains(r#"y="59""#) && ranges[0].ends_with(">2</text>"));
    assert!(ranges[1].contains(r#"y="111""#) && ranges[1].ends_with(">0</text>"));
    let steps = lines_with(&svg, r#"<text class="step""#);
    assert!(steps[0].contains(r#"x="143" y="141""#) && steps[0].ends_with(">Up</text>"));
    assert!(steps[1].ends_with(">Right</text>"));
    // axis at y 162, ticks every 5 ms from 0 to 40 ms
    let lines = lines_with(&svg, "<line");
    assert_eq!(lines.len(), 10);
    assert!(lines[0].contains(r#"x1="140" y1="162" x2="880" y2="162""#));
    assert!(
        lines[2].contains(r#"x1="232.5" y1="162" x2="232.5" y2="167""#),
        "{}",
        lines[2]
    );
    let times: Vec<&str> = lines_with(&svg, r#"<text class="time""#);
    assert!(times[0].ends_with(">0s</text>"));
    assert!(times[8].contains(r#"x="880""#) && times[8].ends_with(">40ms</text>"));
}

#[test]
fn tick_steps_are_round() {
    assert_eq!(tick_step(40_000_000), 5_000_000);
    assert_eq!(tick_step(60_000_000_000), 10_000_000_000);
    assert_eq!(tick_step(1), 1);
    assert_eq!(tick_step(0), 1);
}
