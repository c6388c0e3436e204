"""A Modbus TCP device (pymodbus server) for automat's client: discrete
inputs 0..2 = TRUE, FALSE, TRUE and holding registers 0..1 = 21, 16#BEEF.
It waits until the PLC has written coil 0 = TRUE (the copy of discrete
input 0), coil 1 = FALSE, and holding registers 10..11 = 63 (3 × 21),
16#BEEF (the copy); prints `ok` and exits 0, or exits 1 after 30 s.

usage: device.py PORT
"""
import sys
import threading
import time

from pymodbus.datastore import ModbusSequentialDataBlock, ModbusServerContext, ModbusSlaveContext
from pymodbus.server import StartTcpServer

PORT = int(sys.argv[1])
store = ModbusSlaveContext(
    di=ModbusSequentialDataBlock(0, [True, False, True] + [False] * 13),
    co=ModbusSequentialDataBlock(0, [False] * 16),
    hr=ModbusSequentialDataBlock(0, [21, 0xBEEF] + [0] * 30),
    ir=ModbusSequentialDataBlock(0, [0] * 16),
    zero_mode=True,
)
context = ModbusServerContext(slaves=store, single=True)
threading.Thread(
    target=lambda: StartTcpServer(context=context, address=("127.0.0.1", PORT)), daemon=True
).start()
print("listening", flush=True)
deadline = time.time() + 30
while time.time() < deadline:
    coils = store.getValues(1, 0, 2)
    regs = store.getValues(3, 10, 2)
    if list(coils) == [True, False] and list(regs) == [63, 0xBEEF]:
        print("ok", flush=True)
        sys.exit(0)
    time.sleep(0.05)
print(f"timeout: coils {store.getValues(1, 0, 2)}, holding 10..11 {store.getValues(3, 10, 2)}", flush=True)
sys.exit(1)
