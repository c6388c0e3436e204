//! A Modbus server reachable from other hosts must not take writes from
//! anyone: Modbus has no passwords, so it needs an allow list or a
//! read-only map (loopback is always fine).

use automat_fieldbus::server::{parse_addr, Allow, Options};

#[test]
fn a_server_open_to_other_hosts_needs_an_allow_list_or_read_only() {
    let loopback = Options::new(parse_addr("127.0.0.1:5020").unwrap());
    assert_eq!(loopback.open_to_writes(false), None);
    let open = Options::new(parse_addr("0.0.0.0:5020").unwrap());
    assert_eq!(
        open.open_to_writes(false).as_deref(),
        Some("a Modbus server on 0.0.0.0:5020 would take writes from any host (Modbus has no passwords)")
    );
    assert_eq!(open.open_to_writes(true), None);
    let mut listed = Options::new(parse_addr("0.0.0.0:5020").unwrap());
    listed.allow.push(Allow::parse("10.1.0.0/16").unwrap());
    assert_eq!(listed.open_to_writes(false), None);
}
