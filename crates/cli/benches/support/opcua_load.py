"""OPC UA load for `cargo bench -p automat --bench modbus`: one asyncua
client (PyPI) on the anonymous None endpoint, subscribed to N nodes
(`ns=1;s=ua_0` ... at a 10 ms publishing interval and sampling), for S
seconds. Prints `opcua: N nodes, K notifications` last; exits 1 when the
subscription could not be made.

    opcua_load.py opc.tcp://127.0.0.1:PORT N SECONDS
"""

import asyncio
import sys

from asyncua import Client


class Count:
    def __init__(self):
        self.n = 0

    def datachange_notification(self, node, val, data):
        self.n += 1


async def main(url, n, seconds):
    async with Client(url, timeout=20) as c:
        count = Count()
        sub = await c.create_subscription(10, count)
        nodes = [c.get_node(f"ns=1;s=ua_{i}") for i in range(n)]
        handles = await sub.subscribe_data_change(nodes, sampling_interval=10)
        bad = [h for h in handles if not isinstance(h, int)]
        if bad:
            print(f"opcua: {len(bad)} of {n} monitored items refused: {bad[0]}")
            sys.exit(1)
        await asyncio.sleep(seconds)
        await sub.delete()
        print(f"opcua: {n} nodes, {count.n} notifications")


if __name__ == "__main__":
    asyncio.run(main(sys.argv[1], int(sys.argv[2]), float(sys.argv[3])))
