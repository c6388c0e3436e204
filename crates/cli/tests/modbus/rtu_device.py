"""Two Modbus RTU slaves on one serial line (pymodbus's serial server on a
socat pseudo-terminal) for automat's RTU master. Unit 1: discrete inputs
0..2 = TRUE, FALSE, TRUE, holding registers 0..1 = 21, 16#BEEF; unit 2:
holding register 0 = 100. It waits until the PLC has written unit 1's
coils 0..1 = TRUE, FALSE, its holding registers 10..11 = 63 (3 x 21),
16#BEEF, and unit 2's holding register 5 = 101; prints `ok` and exits 0,
or exits 1 after 30 s.

usage: rtu_device.py PORT
"""
import sys
import threading
import time

from pymodbus.datastore import ModbusSequentialDataBlock, ModbusServerContext, ModbusSlaveContext
from pymodbus.server import StartSerialServer

PORT = sys.argv[1]
one = ModbusSlaveContext(
    di=ModbusSequentialDataBlock(0, [True, False, True] + [False] * 13),
    co=ModbusSequentialDataBlock(0, [False] * 16),
    hr=ModbusSequentialDataBlock(0, [21, 0xBEEF] + [0] * 30),
    ir=ModbusSequentialDataBlock(0, [0] * 16),
    zero_mode=True,
)
two = ModbusSlaveContext(
    di=ModbusSequentialDataBlock(0, [False] * 16),
    co=ModbusSequentialDataBlock(0, [False] * 16),
    hr=ModbusSequentialDataBlock(0, [100] + [0] * 15),
    ir=ModbusSequentialDataBlock(0, [0] * 16),
    zero_mode=True,
)
context = ModbusServerContext(slaves={1: one, 2: two}, single=False)
threading.Thread(
    target=lambda: StartSerialServer(
        context=context, port=PORT, baudrate=38400, parity="N", stopbits=2, bytesize=8
    ),
    daemon=True,
).start()
time.sleep(0.5)
print("listening", flush=True)
deadline = time.time() + 30
while time.time() < deadline:
    coils = list(one.getValues(1, 0, 2))
    regs = list(one.getValues(3, 10, 2))
    r2 = list(two.getValues(3, 5, 1))
    if coils == [True, False] and regs == [63, 0xBEEF] and r2 == [101]:
        print("ok", flush=True)
        sys.exit(0)
    time.sleep(0.05)
print(f"timeout: unit 1 coils {coils}, holding 10..11 {regs}; unit 2 holding 5 {r2}", flush=True)
sys.exit(1)
