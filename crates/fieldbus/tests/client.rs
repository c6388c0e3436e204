//! The client (master) against a server of this crate over loopback:
//! inputs copied into the image, outputs written to the device, and a
//! dead device seen in the status, its inputs zeroed (or held), without
//! the exchange ever waiting.

use automat_fieldbus::client::{Block, Clients, DeviceSpec, Link, OnLoss, StatusPlaces, Target};
use automat_fieldbus::map::WordOrder;
use automat_fieldbus::pdu::{Exception, Table};
use automat_fieldbus::server::{self, Device, Options};
use automat_session::Exchange;
use std::net::{SocketAddr, TcpListener};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// 8 discrete inputs, 8 coils and 8 holding registers in memory.
#[derive(Default)]
struct Mem {
    discrete: Mutex<[bool; 8]>,
    coils: Mutex<[bool; 8]>,
    regs: Mutex<[u16; 8]>,
}

fn range(addr: u16, n: usize, len: usize) -> Result<std::ops::Range<usize>, Exception> {
    let a = usize::from(addr);
    if a + n > len {
        return Err(Exception::IllegalDataAddress);
    }
    Ok(a..a + n)
}

impl Device for Mem {
    fn read_bits(&self, table: Table, addr: u16, count: u16) -> Result<Vec<bool>, Exception> {
        let r = range(addr, usize::from(count), 8)?;
        Ok(match table {
            Table::Coils => self.coils.lock().unwrap()[r].to_vec(),
            _ => self.discrete.lock().unwrap()[r].to_vec(),
        })
    }
    fn read_registers(&self, _t: Table, addr: u16, count: u16) -> Result<Vec<u16>, Exception> {
        let r = range(addr, usize::from(count), 8)?;
        Ok(self.regs.lock().unwrap()[r].to_vec())
    }
    fn write_coils(&self, addr: u16, values: &[bool]) -> Result<(), Exception> {
        let r = range(addr, values.len(), 8)?;
        self.coils.lock().unwrap()[r].copy_from_slice(values);
        Ok(())
    }
    fn write_registers(&self, addr: u16, values: &[u16]) -> Result<(), Exception> {
        let r = range(addr, values.len(), 8)?;
        self.regs.lock().unwrap()[r].copy_from_slice(values);
        Ok(())
    }
}

fn spec(addr: SocketAddr, on_loss: OnLoss) -> DeviceSpec {
    DeviceSpec {
        name: "rio".into(),
        link: Link::Tcp(addr),
        unit: 1,
        period: Duration::from_millis(10),
        timeout: Duration::from_millis(200),
        retries: 0,
        on_loss,
        reads: vec![
            // discrete inputs 0..3 → bits 1..3 of image byte 0
            Block {
                table: Table::DiscreteInputs,
                addr: 0,
                count: 3,
                target: Target::Bits { byte: 0, bit: 1 },
            },
            // holding 4..5 → a DINT at bytes 4..7, high word first
            Block {
                table: Table::HoldingRegisters,
                addr: 4,
                count: 2,
                target: Target::Values {
                    items: vec![(4, 2, 4, false)],
                    order: WordOrder::HighFirst,
                },
            },
        ],
        writes: vec![
            Block {
                table: Table::Coils,
                addr: 2,
                count: 2,
                target: Target::Bits { byte: 1, bit: 6 },
            },
            Block {
                table: Table::HoldingRegisters,
                addr: 0,
                count: 2,
                target: Target::Words { base: 8 },
            },
        ],
        status: StatusPlaces {
            connected: Some((12, None)),
            errors: Some((13, 2)),
            last_error: Some((15, 2)),
        },
    }
}

/// Waits (bounded) until `f` holds.
fn until(what: &str, mut f: impl FnMut() -> bool) {
    let t = Instant::now();
    while !f() {
        assert!(t.elapsed() < Duration::from_secs(10), "timed out: {what}");
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn inputs_come_in_outputs_go_out_and_a_lost_device_reads_zero() {
    let mem = Arc::new(Mem::default());
    *mem.discrete.lock().unwrap() = [true, false, true, false, false, false, false, false];
    mem.regs.lock().unwrap()[4] = 0x1234;
    mem.regs.lock().unwrap()[5] = 0x5678;
    let dev: Arc<dyn Device> = Arc::clone(&mem) as Arc<dyn Device>;
    let srv = server::start(dev, Options::new(SocketAddr::from(([127, 0, 0, 1], 0)))).unwrap();
    let mut clients = Clients::start(vec![spec(srv.addr, OnLoss::Zero)]).unwrap();
    let mut image = vec![0u8; 20];
    // Outputs: bits 6, 7 of byte 1 = TRUE, FALSE; words at 8..11.
    image[1] = 0b0100_0000;
    image[8..12].copy_from_slice(&[0x34, 0x12, 0xCD, 0xAB]);
    clients.outputs(&image);
    until("the outputs reach the device", || {
        *mem.regs.lock().unwrap() == [0x1234, 0xABCD, 0, 0, 0x1234, 0x5678, 0, 0]
            && mem.coils.lock().unwrap()[2..4] == [true, false]
    });
    until("the inputs come in", || {
        clients.inputs(&mut image);
        image[4..8] == [0x78, 0x56, 0x34, 0x12]
    });
    assert_eq!(image[0], 0b0000_1010);
    assert_eq!(image[12], 1);
    assert_eq!(&image[13..17], &[0, 0, 0, 0]);
    let st = &clients.status()[0].1;
    assert!(st.connected);
    assert_eq!((st.errors, st.last_error), (0, 0));

    // The device goes away: status, zeroed inputs, and the exchange never blocks.
    drop(srv);
    until("the loss is seen", || {
        let t = Instant::now();
        clients.inputs(&mut image);
        assert!(t.elapsed() < Duration::from_millis(50), "inputs() waited");
        image[12] == 0
    });
    let st = &clients.status()[0].1;
    assert!(!st.connected);
    assert!(st.errors >= 1);
    assert_eq!(st.last_error, -2, "{}", st.last_error_text);
    assert_eq!(image[0], 0);
    assert_eq!(&image[4..8], &[0, 0, 0, 0]);
    assert!(u16::from_le_bytes([image[13], image[14]]) >= 1);
    assert_eq!(i16::from_le_bytes([image[15], image[16]]), -2);
}

#[test]
fn hold_keeps_the_last_inputs_and_a_device_never_reached_counts_errors() {
    // A port with nothing listening.
    let free = TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap();
    let mut clients = Clients::start(vec![spec(free, OnLoss::Hold)]).unwrap();
    let mut image = vec![0u8; 20];
    image[4] = 0x99;
    until("connection errors counted", || {
        clients.status()[0].1.errors >= 2
    });
    clients.inputs(&mut image);
    assert_eq!(image[4], 0x99, "hold keeps what the inputs were");
    assert_eq!(image[12], 0);
    assert_eq!(i16::from_le_bytes([image[15], image[16]]), -2);
    let t = Instant::now();
    drop(clients);
    assert!(t.elapsed() < Duration::from_secs(2));
}

#[test]
fn exceptions_of_the_device_are_its_last_error() {
    let mem = Arc::new(Mem::default());
    let dev: Arc<dyn Device> = Arc::clone(&mem) as Arc<dyn Device>;
    let srv = server::start(dev, Options::new(SocketAddr::from(([127, 0, 0, 1], 0)))).unwrap();
    let mut s = spec(srv.addr, OnLoss::Zero);
    // Holding 7..8 is past the device's 8 registers: exception 02.
    s.reads[1].addr = 7;
    let clients = Clients::start(vec![s]).unwrap();
    until("the exception is seen", || {
        clients.status()[0].1.last_error == 2
    });
    let st = &clients.status()[0].1;
    assert!(st.connected, "an exception keeps the connection");
    assert_eq!(st.last_error_text, "exception 02 (illegal data address)");
}
