"""A real Modbus RTU master (pymodbus's serial client, pyserial) against
`automat run` as RTU slave 3 on a socat pseudo-terminal (the program of
crates/cli/tests/modbus_rtu.rs): the default map, an explicit REAL,
function codes 1, 3, 5, 6, 15, 16, 23, exceptions, another unit's
requests left alone, a broadcast write, and raw abuse (a bad CRC, a
flood of garbage, an unknown function). Prints one line per check and
`N passed, M failed`; exits 1 on a failure.

usage: rtu_check.py PORT
"""
import sys
import time

import serial
from pymodbus.client import ModbusSerialClient

PORT = sys.argv[1]
UNIT = 3
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


def crc(data):
    c = 0xFFFF
    for b in data:
        c ^= b
        for _ in range(8):
            c = (c >> 1) ^ 0xA001 if c & 1 else c >> 1
    return bytes([c & 0xFF, c >> 8])


def adu(unit, pdu):
    return bytes([unit]) + pdu + crc(bytes([unit]) + pdu)


c = ModbusSerialClient(port=PORT, baudrate=19200, parity="N", stopbits=1, timeout=1, retries=0)
check("open", c.connect(), True)
check("FC3 %QW0..1 (level = sensor + 7, cmd)", c.read_holding_registers(0, 2, slave=UNIT).registers, [7, 0])
c.write_register(1, 20, slave=UNIT)
settle()
check("FC6 cmd = 20 -> FC1 lamp %QX4.0 (coil 32)", c.read_coils(32, 1, slave=UNIT).bits[0], True)
c.write_registers(2048, [0x5678, 0x1234], slave=UNIT)
check("FC16 %MD0 low word first = %MW0..1", c.read_holding_registers(1024, 2, slave=UNIT).registers, [0x5678, 0x1234])
check("explicit REAL speed = 1.5 at 9000", c.read_holding_registers(9000, 2, slave=UNIT).registers, [0x3FC0, 0])
r = c.readwrite_registers(read_address=1024, read_count=2, write_address=1024, values=[9], slave=UNIT)
check("FC23 write then read", r.registers, [9, 0x1234])
c.write_coil(33, True, slave=UNIT)
c.write_coils(34, [True, False, True], slave=UNIT)
check("FC5 + FC15 coils 33..36", c.read_coils(33, 4, slave=UNIT).bits[:4], [True, True, False, True])
e = c.read_holding_registers(5, 1, slave=UNIT)
check("holding 5 (past %QW) -> exception 02", (e.isError(), getattr(e, "exception_code", None)), (True, 2))
e = c.read_holding_registers(0, 1, slave=4)
check("unit 4 is someone else's: no answer", e.isError(), True)
c.close()

s = serial.Serial(PORT, baudrate=19200, parity="N", stopbits=1, timeout=0.5)


def ask(frame, want_len):
    s.reset_input_buffer()
    s.write(frame)
    return s.read(want_len)


read0 = adu(UNIT, bytes([3, 0, 0, 0, 1]))
want0 = adu(UNIT, bytes([3, 2, 0, 7]))
check("raw FC3 of %QW0: exact bytes", ask(read0, 7), want0)
bad = bytearray(read0)
bad[-1] ^= 0xFF
check("a bad CRC is not answered", ask(bytes(bad), 7), b"")
time.sleep(0.05)
check("the next frame is answered", ask(read0, 7), want0)
check("300 bytes of garbage are not answered", ask(bytes(range(256)) + bytes(44), 7), b"")
time.sleep(0.05)
check("after the silence frames are answered again", ask(read0, 7), want0)
check("unknown function 0x2B -> exception 01", ask(adu(UNIT, bytes([0x2B, 0x0E, 1, 0])), 5), adu(UNIT, bytes([0xAB, 1])))
check("broadcast FC6 cmd = 5 is not answered", ask(adu(0, bytes([6, 0, 1, 0, 5])), 8), b"")
settle()
check("... and was done: lamp FALSE", ask(adu(UNIT, bytes([1, 0, 32, 0, 1])), 6), adu(UNIT, bytes([1, 1, 0])))
half = adu(UNIT, bytes([3, 0, 0, 0, 1]))
s.write(half[:3])
time.sleep(0.1)
check("a fragment is dropped at the silence", ask(read0, 7), want0)
s.close()

print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
