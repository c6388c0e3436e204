"""A real Modbus TCP client (pymodbus) against `automat run` serving the
program of crates/cli/tests/modbus.rs: the default map, an explicit REAL,
function codes 1-6, 15, 16, 23, exceptions, and raw-socket abuse (partial
frames, huge counts, unknown functions, a flood, impossible headers, the
connection limit). Prints one line per check and `N passed, M failed`;
exits 1 on a failure.

usage: client_check.py HOST PORT
"""
import socket
import struct
import sys
import time

from pymodbus.client import ModbusTcpClient

HOST, PORT = sys.argv[1], int(sys.argv[2])
passed = failed = 0


def check(name, got, want):
    global passed, failed
    if got == want:
        passed += 1
        print(f"ok   {name}")
    else:
        failed += 1
        print(f"FAIL {name}: got {got!r}, want {want!r}")


def settle():
    # A write is answered once the PLC applied it; the program's outputs
    # follow at its next scan (10 ms).
    time.sleep(0.15)


c = ModbusTcpClient(HOST, port=PORT, timeout=5)
check("connect", c.connect(), True)
check("FC3 %QW0..1 (level = sensor + 7, cmd)", c.read_holding_registers(0, 2, slave=1).registers, [7, 0])
check("FC4 %IW0", c.read_input_registers(0, 1, slave=1).registers, [0])
c.write_register(1, 20, slave=1)
settle()
check("FC6 cmd = 20 -> FC1 lamp %QX4.0 (coil 32)", c.read_coils(32, 1, slave=1).bits[0], True)
c.write_register(1, 5, slave=1)
settle()
check("FC6 cmd = 5 -> lamp FALSE", c.read_coils(32, 1, slave=1).bits[0], False)
c.write_registers(2048, [0x5678, 0x1234], slave=1)
check("FC16 %MD0 low word first = %MW0..1", c.read_holding_registers(1024, 2, slave=1).registers, [0x5678, 0x1234])
check("explicit REAL speed = 1.5 at 9000", c.read_holding_registers(9000, 2, slave=1).registers, [0x3FC0, 0])
c.write_registers(9000, [0x4020, 0], slave=1)
check("FC16 speed := 2.5", c.read_holding_registers(9000, 2, slave=1).registers, [0x4020, 0])
r = c.readwrite_registers(read_address=1024, read_count=2, write_address=1024, values=[9], slave=1)
check("FC23 write then read", r.registers, [9, 0x1234])
c.write_coil(33, True, slave=1)
c.write_coils(34, [True, False, True], slave=1)
check("FC5 + FC15 coils 33..36", c.read_coils(33, 4, slave=1).bits[:4], [True, True, False, True])
check("FC2 %IX discrete inputs", c.read_discrete_inputs(0, 8, slave=1).bits[:8], [False] * 8)
e = c.read_holding_registers(5, 1, slave=1)
check("holding 5 (past %QW) -> exception 02", (e.isError(), getattr(e, "exception_code", None)), (True, 2))
e = c.write_register(9, 1, slave=1)
check("write past the area -> exception 02", (e.isError(), getattr(e, "exception_code", None)), (True, 2))
c.close()


def raw():
    s = socket.create_connection((HOST, PORT), timeout=5)
    s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return s


def recv_exact(s, n):
    buf = b""
    while len(buf) < n:
        chunk = s.recv(n - len(buf))
        if not chunk:
            return buf
        buf += chunk
    return buf


def ask(s, tid, pdu):
    s.sendall(struct.pack(">HHHB", tid, 0, len(pdu) + 1, 1) + pdu)
    head = recv_exact(s, 7)
    if len(head) < 7:
        return None
    _, _, length, _ = struct.unpack(">HHHB", head)
    return recv_exact(s, length - 1)


def closed(s):
    try:
        return s.recv(1) == b""
    except (ConnectionResetError, socket.timeout):
        return True


s = raw()
check("FC3 count 126 -> exception 03", ask(s, 1, bytes([3, 0, 0, 0, 126])), bytes([0x83, 3]))
check("FC1 count 2001 -> exception 03", ask(s, 2, bytes([1, 0, 0, 0x07, 0xD1])), bytes([0x81, 3]))
check("FC16 byte count mismatch -> exception 03", ask(s, 3, bytes([16, 0, 0, 0, 2, 3, 0, 1, 0])), bytes([0x90, 3]))
check("unknown function 0x2B -> exception 01", ask(s, 4, bytes([0x2B, 0x0E, 1, 0])), bytes([0xAB, 1]))
check("FC5 value 0x1234 -> exception 03", ask(s, 5, bytes([5, 0, 32, 0x12, 0x34])), bytes([0x85, 3]))
frame = struct.pack(">HHHB", 6, 0, 6, 1) + bytes([3, 0, 0, 0, 1])
s.sendall(frame[:4])
time.sleep(0.2)
s.sendall(frame[4:9])
time.sleep(0.2)
s.sendall(frame[9:])
check("a frame in three pieces", recv_exact(s, 11), struct.pack(">HHHB", 6, 0, 5, 1) + bytes([3, 2, 0, 7]))
n = 1000
flood = b"".join(struct.pack(">HHHB", 1000 + i, 0, 6, 1) + bytes([4, 0, 0, 0, 1]) for i in range(n))
s.sendall(flood)
tids = []
for _ in range(n):
    head = recv_exact(s, 7)
    body = recv_exact(s, struct.unpack(">H", head[4:6])[0] - 1)
    tids.append(struct.unpack(">H", head[:2])[0])
check(f"a flood of {n} pipelined requests, every one answered in order", tids, list(range(1000, 1000 + n)))
s.close()

s = raw()
s.sendall(struct.pack(">HHHB", 1, 7, 6, 1) + bytes([3, 0, 0, 0, 1]))
check("protocol id 7 -> connection closed", closed(s), True)
s = raw()
s.sendall(struct.pack(">HHHB", 1, 0, 0xFFFF, 1) + b"\0" * 64)
check("MBAP length 65535 -> connection closed", closed(s), True)

held = [raw() for _ in range(4)]
for h in held:
    ask(h, 1, bytes([3, 0, 0, 0, 1]))
extra = raw()
check("a 5th connection over max_connections = 4 is closed", closed(extra), True)
for h in held:
    h.close()
time.sleep(0.3)

c = ModbusTcpClient(HOST, port=PORT, timeout=5)
c.connect()
check("the server still answers after all that", c.read_holding_registers(1024, 1, slave=1).registers, [9])
c.close()

print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
