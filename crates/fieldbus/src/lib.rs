//! Fieldbus I/O of automat: Modbus TCP and RTU (`docs/modbus.md`).
//!
//! - [`pdu`]: the MBAP/PDU codec of both sides (function codes 1, 2, 3,
//!   4, 5, 6, 15, 16, 23), every limit of the specification checked; no I/O.
//! - [`map`]: the server's address map over the PLC image (OpenPLC's
//!   default map plus explicit variable entries).
//! - [`server`]: the TCP server (slave) on threads of its own; the PLC
//!   session as a [`server::Device`] (reads from the published snapshot,
//!   writes as one between-scans command through the session's rules).
//! - [`client`]: the client (master) for remote I/O: a poller thread per
//!   device, exchanged with the scan by copying only ([`client::Clients`]
//!   is the session's `Exchange`).
//! - [`rtu`]: the RTU frame (unit, PDU, CRC-16) and its decoder; no I/O.
//!   [`serial`]: line settings and opening the port; [`rtu_server`] the
//!   slave over the same [`server::Device`]; [`rtu_client`] the master's
//!   shared bus, used by [`client`].
//! - [`config`]: `[modbus]` in `automat.toml` (E340–E344), one file per
//!   table kind.
//! - [`plant`]: a virtual plant as a Modbus device.
//!
//! Invariants: nothing here runs on the scan thread but the copies of
//! `Clients`; no request waits for the scan longer than one between-scans
//! command; bad input from the network gets an exception or a closed
//! connection, never a panic (`fuzz/fuzz_targets/modbus_frame.rs`).

pub mod client;
pub mod config;
pub mod map;
pub mod pdu;
pub mod plant;
pub mod rtu;
pub mod rtu_client;
pub mod rtu_server;
pub mod serial;
pub mod server;
