"""Load for the online benchmark (crates/cli/benches/online.rs): 10 WebSocket
clients each watching 100 values at 10 Hz, plus 100 read/write requests per
second, for SECONDS. Prints the counts achieved as one JSON line.

    load.py URL TOKEN SECONDS PATH...
"""

import json
import sys
import threading
import time

import requests
from websockets.sync.client import connect


def watcher(url, token, paths, until, counts, i):
    h = {"Authorization": f"Bearer {token}"}
    with connect(url.replace("http", "ws") + "/api/v1/watch", additional_headers=h) as ws:
        ws.send(json.dumps({"subscribe": paths, "period_ms": 100}))
        while time.monotonic() < until:
            try:
                m = json.loads(ws.recv(timeout=1))
            except TimeoutError:
                continue
            if len(m.get("values", {})) == len(paths):
                counts[i] += 1


def requester(url, token, paths, until, counts):
    s = requests.Session()
    s.headers["Authorization"] = f"Bearer {token}"
    next_t = time.monotonic()
    k = 0
    while time.monotonic() < until:
        if k % 2 == 0:
            r = s.get(url + "/api/v1/read", params={"path": paths[:10]}, timeout=5)
        else:
            r = s.post(url + "/api/v1/write", json={"path": "Ctrl.startEdge.CLK", "value": "FALSE"}, timeout=5)
        if r.status_code == 200:
            counts["requests"] += 1
        k += 1
        next_t += 0.01
        time.sleep(max(0.0, next_t - time.monotonic()))


def main():
    url, token, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
    paths = sys.argv[4:]
    until = time.monotonic() + seconds
    counts = [0] * 10
    req = {"requests": 0}
    threads = [threading.Thread(target=watcher, args=(url, token, paths, until, counts, i)) for i in range(10)]
    threads.append(threading.Thread(target=requester, args=(url, token, paths, until, req)))
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    print(json.dumps({"ws_messages": sum(counts), "requests": req["requests"], "seconds": seconds}))


if __name__ == "__main__":
    main()
