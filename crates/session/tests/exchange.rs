//! The fieldbus hook (`Parts::exchange`): inputs copied in between scans
//! (a forced input still beats them, the snapshot shows them), outputs
//! copied out after each scan, with the safe state on a STOP and at the
//! end of the session.

mod support;

use automat_engine::Engine;
use automat_project::build;
use automat_session::{Control, Exchange, Parts, Session};
use std::sync::{Arc, Mutex};
use support::{config, get, step, temp_dir};

const PROGRAM: &str = "PROGRAM Main
VAR
    inp AT %IW0 : INT;
    out AT %QW0 : INT;
END_VAR
    out := inp + 1;
END_PROGRAM
";

#[derive(Default)]
struct Io {
    /// What the device reads now (goes to %IW0).
    input: i16,
    /// Every %QW0 the device was given.
    outputs: Vec<i16>,
}

struct Dev {
    io: Arc<Mutex<Io>>,
    inp: usize,
    out: usize,
}

impl Exchange for Dev {
    fn inputs(&mut self, image: &mut [u8]) {
        let v = self.io.lock().unwrap().input;
        image[self.inp..self.inp + 2].copy_from_slice(&v.to_le_bytes());
    }
    fn outputs(&mut self, image: &[u8]) {
        let v = i16::from_le_bytes([image[self.out], image[self.out + 1]]);
        self.io.lock().unwrap().outputs.push(v);
    }
}

fn session(io: &Arc<Mutex<Io>>) -> Session {
    let dir = temp_dir("exchange");
    let file = dir.join("main.st");
    std::fs::write(&file, PROGRAM).unwrap();
    let (program, _) = build::compile(&[file], None, &[]).unwrap_or_else(|e| panic!("{}", e.text));
    let at = |p: &str| program.symbols.get(p).unwrap().offset as usize;
    let dev = Dev {
        io: Arc::clone(io),
        inp: at("Main.inp"),
        out: at("Main.out"),
    };
    let program = Arc::new(program);
    let p = (*program).clone();
    Session::start(
        program,
        config(),
        Box::new(move || {
            Ok(Parts {
                exec: Box::new(Engine::new(p)),
                sim: None,
                observer: None,
                exchange: Some(Box::new(dev)),
            })
        }),
    )
    .unwrap()
}

fn last_output(io: &Arc<Mutex<Io>>) -> Option<i16> {
    io.lock().unwrap().outputs.last().copied()
}

#[test]
fn inputs_come_in_between_scans_and_outputs_go_out_after_them() {
    let io = Arc::new(Mutex::new(Io::default()));
    let s = session(&io);
    io.lock().unwrap().input = 5;
    step(&s, 1);
    assert_eq!(get(&s, "Main.out"), "6");
    // The snapshot after the scan already shows the next scan's input.
    assert_eq!(get(&s, "Main.inp"), "5");
    assert!(io.lock().unwrap().outputs.contains(&6));
    // A forced input beats the device's value.
    s.force("Main.inp", "100").unwrap();
    step(&s, 1);
    assert_eq!(get(&s, "Main.out"), "101");
    assert_eq!(get(&s, "Main.inp"), "100");
    s.unforce("Main.inp").unwrap();
    io.lock().unwrap().input = 41;
    step(&s, 1);
    assert_eq!(get(&s, "Main.out"), "42");
    assert_eq!(last_output(&io), Some(42));
    // STOP: the outputs go to the safe state and the device is told.
    s.control(Control::Stop).unwrap();
    assert_eq!(get(&s, "Main.out"), "0");
    assert_eq!(last_output(&io), Some(0));
    s.control(Control::Start).unwrap();
    std::thread::sleep(std::time::Duration::from_millis(50));
    let end = s.shutdown().unwrap();
    // The end of the session: the final (safe) image once more.
    assert!(end.fault.is_none() && end.error.is_none());
    assert_eq!(last_output(&io), Some(0));
}
