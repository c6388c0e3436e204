//! SLC-500 indexed and indirect addresses by name in a session (the
//! online API's reads, writes and forces): found in the image of each
//! read; a write or force goes to the place named at that time; outside
//! its data file, that one request fails and the PLC runs on.

mod support;

use automat_session::Error;
use support::{config, get, series, source_file, step};

/// S:24 = 2; N7:0 counts 1, 2, 3, 4, 0, ... (the scan number mod 5);
/// N7:2 = 9 points at N7:9, which counts up from 90 by 1 a scan.
const LADDER: &str = "\
DATA N7 10 = 0 0 9 0 0 50 60 70 80 90
DATA B3 2 = 0 4
MOV 2 S:24
ADD N7:0 1 N7:0
GRT N7:0 4 CLR N7:0
ADD N7:[N7:2] 1 N7:[N7:2]
";

#[test]
fn reads_follow_the_index_words_scan_by_scan() {
    let s = source_file("main.slc", LADDER, config());
    // Before any scan S:24 is 0: #N7:5 is N7:5.
    assert_eq!(get(&s, "#N7:5"), "50");
    // N7:0 = 1, 2, 3: N7:1 = 0, N7:2 = 9, N7:3 = 0.
    assert_eq!(series(&s, "N7:[N7:0]", 3), ["0", "9", "0"]);
    assert_eq!(get(&s, "N7:[N7:2]"), "93");
    assert_eq!(get(&s, "#N7:5"), "70");
    s.write("N7:1", "18").unwrap();
    // Bit 18 of B3: B3:1/2 (B3:1 = 4).
    assert_eq!(get(&s, "B3/[N7:1]"), "1");
    assert_eq!(
        s.read(&["N7:[N7:1]".to_string()]),
        Err(Error::Path(
            "indirect address `N7:[N7:1]`: the element 18 is not one of data file N7 (0 to 9)"
                .into()
        ))
    );
    assert_eq!(
        s.read(&["B3:[N7:0]/2".to_string()]),
        Err(Error::Path(
            "indirect address `B3:[N7:0]/2`: the element 3 is not one of data file B3 (0 to 1)"
                .into()
        ))
    );
    // The PLC ran on.
    assert_eq!(series(&s, "N7:0", 1), ["4"]);
}

#[test]
fn writes_and_forces_go_to_the_place_named_then() {
    let s = source_file("main.slc", LADDER, config());
    step(&s, 1);
    // N7:0 = 1, N7:9 = 91, S:24 = 2.
    s.write("N7:[N7:0]", "33").unwrap();
    assert_eq!(get(&s, "N7:1"), "33");
    s.write("#N7:6", "-5").unwrap();
    assert_eq!(get(&s, "N7:8"), "-5");
    s.write("N7:1", "3").unwrap();
    s.force("N7:[N7:1]", "500").unwrap();
    // Listed under the place it forced; N7:1 changing later moves nothing.
    assert_eq!(s.forces(), [("N7:3".to_string(), "500".to_string())]);
    s.write("N7:1", "8").unwrap();
    step(&s, 2);
    assert_eq!(get(&s, "N7:3"), "500");
    assert_eq!(get(&s, "N7:9"), "93");
    // N7:[N7:1] is N7:8 now, which is not forced.
    assert_eq!(
        s.unforce("N7:[N7:1]"),
        Err(Error::Refused("this location is not forced".into()))
    );
    s.unforce("N7:3").unwrap();
    assert!(s.forces().is_empty());
    // N7:0 = 3: bit 3 of B3:0.
    s.write("B3:0/[N7:0]", "1").unwrap();
    assert_eq!(get(&s, "B3:0"), "8");
    assert_eq!(
        s.write("#N7:9", "1"),
        Err(Error::Path(
            "indexed address `#N7:9` + S:24 (2) lies outside data file N7 (words 0 to 9)".into()
        ))
    );
}
