use super::*;
use crate::testutil::{inst, task};

const MS: i64 = 1_000_000;

/// Runs the schedule over every tick before `until`, logging (time, task index).
fn drive(s: &mut Schedule, image: &[u8], until: i64) -> Vec<(i64, usize)> {
    let mut log = Vec::new();
    let mut due = Vec::new();
    loop {
        let t = s.next_tick();
        if t >= until {
            return log;
        }
        s.due(t, image, &mut due);
        log.extend(due.iter().map(|&i| (t / MS, i)));
    }
}

#[test]
fn implicit_task_runs_every_cycle_time() {
    let mut s = Schedule::new(&[task("MAIN", None, 0, vec![])], 10 * MS).unwrap();
    assert_eq!(s.base_ns(), 10 * MS);
    assert_eq!(s.fastest(), Some(0));
    assert_eq!(
        drive(&mut s, &[], 40 * MS),
        [(0, 0), (10, 0), (20, 0), (30, 0)]
    );
    assert_eq!(s.runs(0), 4);
}

#[test]
fn intervals_use_the_gcd_base_tick_and_run_at_multiples() {
    let tasks = [
        task("SLOW", Some(15), 1, vec![]),
        task("FAST", Some(10), 2, vec![]),
    ];
    let mut s = Schedule::new(&tasks, 7 * MS).unwrap();
    assert_eq!(s.base_ns(), 5 * MS);
    assert_eq!(s.fastest(), Some(1));
    assert_eq!(
        drive(&mut s, &[], 46 * MS),
        [
            (0, 0),
            (0, 1),
            (10, 1),
            (15, 0),
            (20, 1),
            (30, 0),
            (30, 1),
            (40, 1),
            (45, 0)
        ]
    );
    assert_eq!((s.runs(0), s.runs(1)), (4, 5));
}

#[test]
fn priority_first_then_declaration_order() {
    let tasks = [
        task("A", Some(10), 5, vec![]),
        task("B", Some(10), 1, vec![]),
        task("C", Some(20), 1, vec![]),
        task("D", Some(10), 5, vec![]),
    ];
    let mut s = Schedule::new(&tasks, 10 * MS).unwrap();
    let log = drive(&mut s, &[], 30 * MS);
    assert_eq!(
        log,
        [
            (0, 1),
            (0, 2),
            (0, 0),
            (0, 3),
            (10, 1),
            (10, 0),
            (10, 3),
            (20, 1),
            (20, 2),
            (20, 0),
            (20, 3)
        ]
    );
}

#[test]
fn event_task_runs_on_rising_edges_only() {
    let mut ev = task("EV", None, 0, vec![inst("P", 0, 0)]);
    ev.single = Some((3, Some(2)));
    let tasks = [task("CYC", Some(10), 1, vec![]), ev];
    let mut s = Schedule::new(&tasks, 100 * MS).unwrap();
    // The event is sampled on the base tick (10 ms, the only interval).
    assert_eq!(s.base_ns(), 10 * MS);
    let mut due = Vec::new();
    let mut image = [0u8; 4];
    let mut seen = Vec::new();
    for (k, bit) in [0, 1, 1, 0, 1, 0, 0, 1].into_iter().enumerate() {
        image[3] = bit << 2 | 0b1000_0000;
        let t = s.next_tick();
        assert_eq!(t, k as i64 * 10 * MS);
        s.due(t, &image, &mut due);
        seen.push(due.clone());
    }
    assert_eq!(
        seen,
        [
            vec![0],
            vec![1, 0],
            vec![0],
            vec![0],
            vec![1, 0],
            vec![0],
            vec![0],
            vec![1, 0]
        ]
    );
    assert_eq!(s.runs(1), 3);
}

#[test]
fn event_true_at_the_first_tick_is_an_edge_and_byte_bools_work() {
    let mut ev = task("EV", None, 0, vec![]);
    ev.single = Some((0, None));
    let mut s = Schedule::new(&[ev], 5 * MS).unwrap();
    assert_eq!(s.fastest(), None);
    let mut due = Vec::new();
    s.due(s.next_tick(), &[1], &mut due);
    assert_eq!(due, [0]);
    s.due(s.next_tick(), &[1], &mut due);
    assert!(due.is_empty());
    // Outside the image the BOOL reads FALSE.
    let mut ev = task("EV", None, 0, vec![]);
    ev.single = Some((99, Some(1)));
    let mut s = Schedule::new(&[ev], 5 * MS).unwrap();
    s.due(0, &[0xFF], &mut due);
    assert!(due.is_empty());
}

#[test]
fn virtual_time_is_exact_over_many_cycles() {
    // 3 ms does not divide 1 s evenly in binary floating point; integer
    // ticks keep cycle k at exactly (k - 1) * 3 ms.
    let mut s = Schedule::new(&[task("T", Some(3), 0, vec![])], 10 * MS).unwrap();
    let mut due = Vec::new();
    for k in 1..=100_000i64 {
        let t = s.next_tick();
        assert_eq!(t, (k - 1) * 3 * MS);
        s.due(t, &[], &mut due);
    }
    assert_eq!(s.runs(0), 100_000);
}

#[test]
fn skip_to_drops_missed_instants_without_catch_up() {
    let tasks = [
        task("A", Some(10), 0, vec![]),
        task("B", Some(25), 0, vec![]),
    ];
    let mut s = Schedule::new(&tasks, 10 * MS).unwrap();
    let mut due = Vec::new();
    s.due(0, &[], &mut due);
    assert_eq!(due, [0, 1]);
    // The scan at 0 ended at 37 ms: 10, 20, 30 (A) and 25 (B) are missed.
    s.skip_to(37 * MS);
    assert_eq!(s.next_tick(), 40 * MS);
    s.due(40 * MS, &[], &mut due);
    assert_eq!(due, [0]);
    assert_eq!(s.next_tick(), 50 * MS);
    s.due(50 * MS, &[], &mut due);
    assert_eq!(due, [0, 1]);
    // Exactly on an instant: it is still due.
    s.skip_to(60 * MS);
    assert_eq!(s.next_tick(), 60 * MS);
}

#[test]
fn bad_cycle_time_and_empty_configuration() {
    assert_eq!(
        Schedule::new(&[], 0).unwrap_err(),
        "the cycle time must be longer than 0"
    );
    let mut s = Schedule::new(&[], 10 * MS).unwrap();
    let mut due = Vec::new();
    assert_eq!(s.next_tick(), 0);
    s.due(0, &[], &mut due);
    assert_eq!(s.next_tick(), 10 * MS);
    assert!(due.is_empty());
}

#[test]
fn time_overflow_means_never() {
    let mut s = Schedule::new(&[task("T", None, 0, vec![])], i64::MAX / 2 + 1).unwrap();
    let mut due = Vec::new();
    s.due(0, &[], &mut due);
    assert_eq!(s.next_tick(), i64::MAX / 2 + 1);
    s.due(s.next_tick(), &[], &mut due);
    assert_eq!(s.next_tick(), i64::MAX);
}
