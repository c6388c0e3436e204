"""The web HMI in a real browser: headless Chromium driven by Selenium.

Run by crates/cli/tests/hmi.rs against two PLCs it starts:

    hmi_browser.py CRANE_URL CRANE_TOKEN LOAD_URL LOAD_TOKEN SHOTS_DIR LD_URL LD_TOKEN

CRANE is `automat run examples/crane --virtual-clock` with the users ada
(viewer, viewer-pass) and otto (operator, operator-pass): every value is
exact, scans run on `step`. LOAD runs a program of 200 counters in real
time, for the update-rate figure. Screenshots of every view go to
SHOTS_DIR. LD runs `examples/crane-ld --virtual-clock` (the crane in IEC
Ladder Diagram) for the live LD drawing. Prints one line per check and
`N passed, M failed` last.
"""

import json
import os
import sys
import tempfile
import time

import requests
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait

passed = 0
failed = 0


def check(name, cond, detail=""):
    global passed, failed
    if cond:
        passed += 1
        print(f"ok   {name}", flush=True)
    else:
        failed += 1
        print(f"FAIL {name}: {detail}", flush=True)


def browser():
    o = webdriver.ChromeOptions()
    o.binary_location = os.environ.get("CHROMIUM", "/usr/bin/chromium")
    for flag in ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--disable-dev-shm-usage", "--window-size=1366,768",
                 "--user-data-dir=" + tempfile.mkdtemp(prefix="automat-hmi-chromium-")]:
        o.add_argument(flag)
    o.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    # The driver is named, so Selenium never looks for one on the network.
    service = Service(executable_path=os.environ.get("CHROMEDRIVER", "/usr/bin/chromedriver"))
    d = webdriver.Chrome(options=o, service=service)
    d.set_window_size(1366, 768)
    return d


def wait(d, what, fn, timeout=15):
    try:
        return WebDriverWait(d, timeout, poll_frequency=0.05).until(lambda _: fn())
    except Exception as e:  # the check reports it
        return None


class Api:
    def __init__(self, base, token):
        self.base, self.h = base, {"Authorization": f"Bearer {token}"}

    def step(self, n):
        r = requests.post(self.base + "/api/v1/control", headers=self.h, json={"command": "step", "scans": n},
                          timeout=60)
        assert r.status_code == 200, r.text

    def forces(self):
        return requests.get(self.base + "/api/v1/forces", headers=self.h, timeout=30).json()["forces"]

    def read(self, *paths):
        return requests.get(self.base + "/api/v1/read", headers=self.h, params={"path": list(paths)},
                            timeout=30).json()["values"]


def tab(d, name):
    d.find_element(By.ID, "tab-" + name).click()
    wait(d, name, lambda: d.find_element(By.ID, name).is_displayed())


def row_value(d, path):
    return d.execute_script(
        "const r = document.querySelector(`#wl-rows tr[data-path='${arguments[0]}']`);"
        "return r ? [r.querySelector('td.value').textContent, r.classList.contains('forced')] : null;", path)


def shot(d, path):
    """A screenshot without the passing status message."""
    d.execute_script("document.getElementById('message').hidden = true")
    d.save_screenshot(path)


def console_errors(d):
    try:
        return [e["message"] for e in d.get_log("browser") if e["level"] == "SEVERE"]
    except Exception:
        return []


def crane(d, base, token, shots):
    api = Api(base, token)

    # Static files are public, the data is not.
    r = requests.get(base + "/", timeout=10)
    check("the page is served at / without a token", r.status_code == 200 and "automat HMI" in r.text
          and "script-src 'self'" in r.headers.get("Content-Security-Policy", ""), r.status_code)
    check("the API still needs one", requests.get(base + "/api/v1/status", timeout=10).status_code == 401)

    # Login with user and password.
    d.get(base + "/")
    form = wait(d, "login form", lambda: d.find_element(By.ID, "login-user").is_displayed())
    check("without a token the login form shows", form)
    d.find_element(By.ID, "login-user").send_keys("otto")
    d.find_element(By.ID, "login-password").send_keys("wrong")
    d.find_element(By.ID, "login-submit").click()
    err = wait(d, "error", lambda: d.find_element(By.ID, "login-error").text)
    check("a wrong password is refused", err == "wrong user or password", err)
    d.find_element(By.ID, "login-password").clear()
    d.find_element(By.ID, "login-password").send_keys("operator-pass")
    d.find_element(By.ID, "login-submit").click()
    who = wait(d, "who", lambda: d.find_element(By.ID, "who").text)
    check("otto logs in as operator", who == "otto (operator)", who)
    state = wait(d, "state", lambda: d.find_element(By.ID, "state").text)
    check("the overview shows the state", state and state.lower() == "stopped", state)
    check("an operator gets no run control",
          d.find_element(By.ID, "ctl-start").get_attribute("disabled") is not None
          and "engineer" in d.find_element(By.ID, "control-note").text)
    d.find_element(By.ID, "logout").click()
    wait(d, "login", lambda: d.find_element(By.ID, "login").is_displayed())

    # The token file's token in the address, gone from it at once.
    d.get(base + "/?token=" + token)
    who = wait(d, "who", lambda: d.find_element(By.ID, "who").text)
    check("/?token= logs in as engineer", who == "token (engineer)", who)
    check("and leaves the address bar", "token=" not in d.current_url, d.current_url)
    project = wait(d, "project", lambda: d.find_element(By.ID, "ov-project").text)
    check("the overview names the project and its task",
          project == "crane" and "Ctrl" in d.find_element(By.ID, "ov-tasks").text, project)

    # A value changes: watch GS1.T, step 10 scans with the Step button.
    tab(d, "watch")
    wait(d, "tree", lambda: d.find_elements(By.CSS_SELECTOR, "#sym-tree button.twist"))
    d.find_element(By.CSS_SELECTOR, "#sym-tree button[aria-label='Open Ctrl']").click()
    d.find_element(By.CSS_SELECTOR, "#sym-tree button[aria-label='Open Ctrl.GS1']").click()
    d.find_element(By.CSS_SELECTOR, "#sym-tree button[aria-label='Watch Ctrl.GS1.t']").click()
    for p in ["Ctrl.l4", "Ctrl.M2S", "Ctrl.Pornire", "Ctrl.GS2.X"]:
        d.find_element(By.ID, "wl-add-path").send_keys(p)
        d.find_element(By.ID, "wl-add").click()
    v = wait(d, "value", lambda: (row_value(d, "Ctrl.GS1.t") or [None])[0] == "T#0s")
    check("the symbol tree adds Ctrl.GS1.t, shown T#0s", v, row_value(d, "Ctrl.GS1.t"))
    tab(d, "overview")
    d.find_element(By.ID, "ctl-scans").clear()
    d.find_element(By.ID, "ctl-scans").send_keys("10")
    d.find_element(By.ID, "ctl-step").click()
    time.sleep(0.3)
    tab(d, "watch")
    v = wait(d, "changed", lambda: (row_value(d, "Ctrl.GS1.t") or [None])[0] == "T#90ms")
    check("after Step 10 scans it shows T#90ms", v, row_value(d, "Ctrl.GS1.t"))

    # Force from the table: shown forced, then released.
    row = d.find_element(By.CSS_SELECTOR, "#wl-rows tr[data-path='Ctrl.l4']")
    row.find_element(By.CSS_SELECTOR, "input.newval").send_keys("TRUE")
    row.find_element(By.CSS_SELECTOR, "button[aria-label='Force Ctrl.l4']").click()
    v = wait(d, "forced", lambda: row_value(d, "Ctrl.l4") == ["TRUE", True])
    check("forcing Ctrl.l4 TRUE shows it forced", v, row_value(d, "Ctrl.l4"))
    api.step(1)
    check("the program sees it", api.read("Ctrl.l4") == {"Ctrl.l4": "TRUE"})
    color = d.execute_script("return getComputedStyle(document.querySelector(\"#wl-rows tr[data-path='Ctrl.l4'] td.value\")).color")
    check("forced values are styled apart", color == "rgb(179, 38, 30)", color)
    shot(d, os.path.join(shots, "watch.png"))
    # The page reads the values again after the click. That read is made
    # to race a step on purpose: answered by the server before the step,
    # delivered to the page only after the step's WebSocket update. The
    # page must keep the update (the newer snapshot), not the read.
    d.execute_script("""
      const real = window.fetch;
      window.automatHmiTest = { readServed: false };
      window.fetch = async (url, opts) => {
        const r = await real(url, opts);
        if (String(url).includes('/api/v1/read')) {
          window.fetch = real;
          window.automatHmiTest.readServed = true;
          await new Promise((ok) => setTimeout(ok, 1000));
        }
        return r;
      };""")
    d.find_element(By.CSS_SELECTOR, "button[aria-label='Unforce Ctrl.l4']").click()
    # The click's request is asynchronous: step only once the server has
    # released the force (a step before it would keep TRUE one more scan)
    # and has answered the page's read.
    wait(d, "released", lambda: "Ctrl.l4" not in api.forces())
    wait(d, "read answered", lambda: d.execute_script("return window.automatHmiTest.readServed"))
    api.step(1)
    time.sleep(1.5)
    v = wait(d, "unforced", lambda: row_value(d, "Ctrl.l4") == ["FALSE", False])
    check("unforce releases it (the plant gives FALSE again), "
          "also when the page's read is answered after the next update", v, row_value(d, "Ctrl.l4"))
    lists = d.execute_script("return localStorage.getItem('automat.hmi.watch.crane')")
    check("the watch list is kept per project in the browser",
          json.loads(lists)["lists"]["Watch 1"][:2] == ["Ctrl.GS1.t", "Ctrl.l4"], lists)

    # A second named list, then back to the first.
    d.find_element(By.ID, "wl-new").click()
    alert = wait(d, "prompt", lambda: d.switch_to.alert)
    alert.send_keys("Motors")
    alert.accept()
    d.find_element(By.ID, "wl-add-path").send_keys("Ctrl.M1D")
    d.find_element(By.ID, "wl-add").click()
    rows = d.execute_script("return [...document.querySelectorAll('#wl-rows tr')].map(r => r.dataset.path)")
    stored = json.loads(d.execute_script("return localStorage.getItem('automat.hmi.watch.crane')"))
    check("several named watch lists", rows == ["Ctrl.M1D"] and sorted(stored["lists"]) == ["Motors", "Watch 1"]
          and stored["current"] == "Motors", (rows, stored))
    Select(d.find_element(By.ID, "wl-select")).select_by_visible_text("Watch 1")
    rows = d.execute_script("return document.querySelectorAll('#wl-rows tr').length")
    check("switching lists shows the other list", rows == 5, rows)

    # The chart before the press.
    tab(d, "charts")
    wait(d, "chart", lambda: d.find_elements(By.CSS_SELECTOR, "#chart-area g.step"))
    active = lambda: d.execute_script(
        "return [...document.querySelectorAll('#chart-area g.step.active')].map(g => g.dataset.step)")
    v = wait(d, "GS1", lambda: active() == ["GS1"])
    check("the crane chart: GS1 active", v, active())
    steps = d.execute_script("return document.querySelectorAll('#chart-area g.step').length")
    check("every step drawn", steps == 8, steps)
    # Conditions the chart evaluates to mark a transition that can fire.
    got = d.execute_script("""
        const names = new Set(['ctrl.startedge.q', 'ctrl.l1', 'ctrl.l3', 'ctrl.gs2.t']);
        const resolve = (n) => names.has(('ctrl.' + n).toLowerCase()) ? 'Ctrl.' + n : null;
        const v = new Map([['Ctrl.startEdge.Q', 'TRUE'], ['Ctrl.l1', 'TRUE'], ['Ctrl.l3', 'FALSE'], ['Ctrl.GS2.t', 'T#3s']]);
        return ['startEdge.Q AND l1 AND l3', 'startEdge.Q AND (l1 OR l3)', 'NOT l3 & l1', 'GS2.t >= T#2s',
                'GS2.t >= T#5s', '%X1.T >= T#2s', 'unknown AND l1', 'l1 + 1'].map((c) => {
            const e = SfcChart.compile(c, resolve);
            return e === null ? null : e.value(v);
        });""")
    check("conditions evaluated from watched values (or left alone)",
          got == [False, True, True, True, False, None, None, None], got)
    shot(d, os.path.join(shots, "charts-before.png"))

    # Press Pornire in the plant view (the momentary button, held), step.
    tab(d, "plant")
    press = wait(d, "press", lambda: d.find_element(By.CSS_SELECTOR, "button[aria-label='Press Pornire']"))
    check("the plant view has the Pornire button", press is not None)
    mimic = wait(d, "mimic", lambda: d.find_elements(By.CSS_SELECTOR, "#mimic svg[aria-label='Crane mimic']"))
    check("and the crane mimic", mimic)
    webdriver.ActionChains(d).click_and_hold(press).perform()
    time.sleep(0.3)
    api.step(1)
    v = wait(d, "pressed", lambda: api.read("Ctrl.Pornire") == {"Ctrl.Pornire": "TRUE"})
    check("held down, the PLC reads Pornire TRUE", v, api.read("Ctrl.Pornire"))
    webdriver.ActionChains(d).release(press).perform()
    time.sleep(0.3)
    api.step(150)
    check("released, FALSE again", api.read("Ctrl.Pornire") == {"Ctrl.Pornire": "FALSE"})
    time.sleep(0.5)
    shot(d, os.path.join(shots, "plant.png"))
    hook = d.execute_script("return document.querySelector('#mimic text.big').textContent")
    check("the mimic shows the hook rising", hook == "x 0.00 m  y 1.49 m", hook)

    tab(d, "charts")
    v = wait(d, "GS2", lambda: active() == ["GS2"])
    check("the crane chart's active step moved to GS2", v, active())
    t = wait(d, "time", lambda: d.execute_script(
        "return document.querySelector(\"#chart-area g.step[data-step='GS2'] text.time\").textContent"))
    check("with its step time", t == "T#1s500ms", t)
    firable = d.execute_script("return document.querySelectorAll('#chart-area g.tr.enabled, #chart-area g.tr.firable').length")
    check("its transition marked enabled", firable == 1, firable)
    shot(d, os.path.join(shots, "charts.png"))

    # Trends: GS2.X as a band, M2S as steps, GS2.T as a line; CSV.
    for p in ["Ctrl.GS2.X", "Ctrl.M2S"]:
        tab(d, "watch")
        d.find_element(By.CSS_SELECTOR, f"button[aria-label='Plot {p}']").click()
    check("Plot opens the trends", d.find_element(By.ID, "trends").is_displayed())
    for p in ["Ctrl.l2", "Ctrl.GS2.t"]:
        d.find_element(By.ID, "tr-path").send_keys(p)
        d.find_element(By.ID, "tr-add").click()
    time.sleep(0.3)
    # One scan at a time: a client that reads slower than the scans run
    # misses updates (by design), the virtual clock runs a step at once.
    for _ in range(100):
        api.step(1)
        time.sleep(0.005)
    time.sleep(0.5)
    csv = d.execute_script("const t = automatHmi.views.trends; t.csv(); return t.lastCsv;")
    lines = csv.splitlines()
    check("CSV in the --trace format: header", lines[0] == "time,Ctrl.GS2.X,Ctrl.M2S,Ctrl.l2,Ctrl.GS2.t", lines[:2])
    times = [ln.split(",")[0] for ln in lines[1:]]
    check("one row per scan", len(lines) == 102 and times[0] == "T#1s620ms" and times[-1] == "T#2s620ms"
          and times[50] == "T#2s120ms", (len(lines), times[:3], times[-3:]))
    check("values as --print shows them", lines[1] == "T#1s620ms,TRUE,TRUE,FALSE,T#1s500ms"
          and lines[-1] == "T#2s620ms,TRUE,TRUE,FALSE,T#2s500ms", (lines[1], lines[-1]))
    # On through GS3 for the picture (a client may miss updates when
    # scans run faster than it reads: the plot has gaps, never lies).
    for _ in range(30):
        api.step(20)
        time.sleep(0.02)
    d.execute_script("automatHmi.views.trends.span = 8e9")
    time.sleep(0.5)
    shot(d, os.path.join(shots, "trends.png"))
    # Zoom with the wheel over the canvas, pan by keyboard.
    span = d.execute_script("return automatHmi.views.trends.span")
    d.execute_script("document.getElementById('tr-canvas').dispatchEvent(new WheelEvent('wheel', {deltaY: -100, clientX: 700, clientY: 300, bubbles: true, cancelable: true}))")
    span2 = d.execute_script("return automatHmi.views.trends.span")
    check("the wheel zooms", span2 < span, (span, span2))

    tab(d, "overview")
    time.sleep(0.3)
    shot(d, os.path.join(shots, "overview.png"))

    # A tablet (820x1180, portrait): one column, nothing wider than the screen.
    d.set_window_size(820, 1180)
    wide = {}
    for view in ["overview", "watch", "charts", "trends", "plant"]:
        tab(d, view)
        time.sleep(0.2)
        wide[view] = d.execute_script("return document.documentElement.scrollWidth - window.innerWidth")
    check("on a tablet no view is wider than the screen", all(v <= 0 for v in wide.values()), wide)
    d.set_window_size(1366, 768)
    tab(d, "overview")

    # Keyboard: the tabs are real buttons in the tab order.
    d.find_element(By.ID, "tab-overview").send_keys("\ue014")  # ArrowRight
    check("arrow keys move between views", d.find_element(By.ID, "watch").is_displayed())
    # The wrong password's 401 is the one failed request the test makes.
    errors = [e for e in console_errors(d) if "/api/v1/login" not in e]
    check("no script errors in the console", not errors, errors)


def load(d, base, token, shots):
    api = Api(base, token)
    tree = requests.get(base + "/api/v1/symbols", headers=api.h, timeout=30).json()["symbols"]
    leaves = []

    def walk(n):
        if "children" in n:
            for c in n["children"]:
                walk(c)
        elif n["type"] == "DINT":
            leaves.append(n["path"])
    for n in tree:
        walk(n)
    paths = leaves[:200]
    check("200 values to watch", len(paths) == 200, len(paths))
    d.get(base + "/")
    d.execute_script("sessionStorage.clear(); localStorage.setItem('automat.hmi.watch.sources', arguments[0]);",
                     json.dumps({"current": "load", "lists": {"load": paths}}))
    d.get(base + "/?token=" + token + "#watch")
    wait(d, "rows", lambda: d.execute_script("return document.querySelectorAll('#wl-rows tr').length") == 200)
    wait(d, "values", lambda: (row_value(d, paths[-1]) or ["", False])[0] not in ("", None), 20)
    time.sleep(1.0)
    stats = lambda: d.execute_script("return Object.assign({}, automatHmi.stats)")
    a, t0 = stats(), time.monotonic()
    time.sleep(5.0)
    b, t1 = stats(), time.monotonic()
    secs = t1 - t0
    renders = (b["renders"] - a["renders"]) / secs
    messages = (b["messages"] - a["messages"]) / secs
    plc = (b["renderedPlcNs"] - a["renderedPlcNs"]) / 1e9 / secs
    lag = d.execute_async_script(
        "const done = arguments[0];"
        "fetch('/api/v1/status', {headers: {Authorization: 'Bearer ' + automatHmi.token}})"
        ".then(r => r.json()).then(s => done((s.plc_time_ns - automatHmi.stats.renderedPlcNs) / 1e6));")
    shown = row_value(d, paths[-1])[0]
    print(f"HMI with 200 watched values: {renders:.1f} updates/s rendered, {messages:.1f} WebSocket messages/s, "
          f"PLC time shown advancing {plc:.2f} s per s, {lag:.0f} ms behind the PLC", flush=True)
    check("updates at >= 10 Hz with 200 watched values", renders >= 10, renders)
    check("without falling behind (shown PLC time keeps pace, < 500 ms behind)", plc >= 0.9 and lag < 500,
          (plc, lag))
    check("the last value is shown", shown.lstrip("-").isdigit(), shown)

    # A runtime fault: the overview shows it with its site.
    r = requests.post(base + "/api/v1/write", headers=api.h, json={"path": "Load.trip", "value": True}, timeout=30)
    check("trip written", r.status_code == 200, r.text)
    tab(d, "overview")
    shown = wait(d, "fault", lambda: d.find_element(By.ID, "ov-fault").is_displayed())
    msg = d.find_element(By.ID, "ov-fault-message").text
    site = d.find_element(By.ID, "ov-fault-site").text
    check("the overview shows the fault and its site", shown and msg.startswith("division by zero")
          and site.endswith("/load.st:13:10 in Load (task Load, program instance Load, PLC time " + site.split("PLC time ")[-1])
          and "load.st:13:10 in Load (task Load, program instance Load, PLC time T#" in site, (msg, site))
    check("and the state", d.find_element(By.ID, "state").text.lower() == "fault")
    shot(d, os.path.join(shots, "fault.png"))


def ladder(d, base, token, shots):
    """The LD drawing live: `GET /api/v1/drawings`, the hidden power-flow
    BOOLs read (never written) through the API, and a contact's frame in
    the page following its variable."""
    api = Api(base, token)
    check("the drawings need a token", requests.get(base + "/api/v1/drawings", timeout=10).status_code == 401)
    ds = requests.get(base + "/api/v1/drawings", headers=api.h, timeout=30).json()["drawings"]
    check("one drawing: the crane's LD, run by Ctrl",
          [(x["pou"], x["lang"], x["instances"]) for x in ds] == [("Crane", "LD", ["Ctrl"])], ds and ds[0]["pou"])
    crane = ds[0]
    c23 = next((e for e in crane["elements"] if e["id"] == 23), None)
    check("contact 23 (X7) shows its power flow, relative to the instance",
          c23 and (c23["kind"], c23["text"], c23["power"], c23["x"], c23["y"]) == ("contact", "X7", ".__ld_n23", 80, 300),
          c23)
    check("the drawing is automat draw's SVG", crane["svg"].startswith("<svg ") and 'class="coil"' in crane["svg"])

    # The hidden power flow is read like any variable and refused for writes.
    api.step(1)
    check("Ctrl.__ld_n23 reads FALSE (X7 is not set)", api.read("Ctrl.__ld_n23") == {"Ctrl.__ld_n23": "FALSE"},
          api.read("Ctrl.__ld_n23"))
    r = requests.post(base + "/api/v1/write", headers=api.h, json={"path": "Ctrl.__ld_n23", "value": "TRUE"},
                      timeout=30)
    check("and cannot be written (409, compiler-generated)",
          r.status_code == 409 and "compiler-generated" in r.text, (r.status_code, r.text))
    r = requests.post(base + "/api/v1/force", headers=api.h, json={"path": "Ctrl.__ld_n23", "value": "TRUE"},
                      timeout=30)
    check("nor forced", r.status_code == 409, (r.status_code, r.text))

    # The page: contact 23's frame follows X7 through the WebSocket.
    d.get(base + "/?token=" + token + "#drawings")
    frame = lambda: d.execute_script(
        "const r = document.querySelector('#drawing-area .live rect.power[data-id=\"23\"]');"
        "return r ? r.getAttribute('class') : null;")
    v = wait(d, "frame", lambda: frame() == "power off")
    check("the page draws the LD with contact 23 unpowered", v, frame())
    r = requests.post(base + "/api/v1/write", headers=api.h, json={"path": "Ctrl.X7", "value": "TRUE"}, timeout=30)
    check("X7 written", r.status_code == 200, r.text)
    api.step(1)
    v = wait(d, "powered", lambda: frame() == "power on")
    check("after one scan contact 23 is powered (green)", v, frame())
    check("and coil 24 (M1S) too", d.execute_script(
        "return document.querySelector('#drawing-area .live rect.power[data-id=\"24\"]').getAttribute('class')")
        == "power on")
    time.sleep(0.3)
    shot(d, os.path.join(shots, "drawings.png"))
    r = requests.post(base + "/api/v1/write", headers=api.h, json={"path": "Ctrl.X7", "value": "FALSE"}, timeout=30)
    api.step(1)
    v = wait(d, "unpowered", lambda: frame() == "power off")
    check("X7 FALSE again: contact 23 unpowered", v, frame())
    # The TON's input values sit inside its box (not over the variable boxes
    # wired to it on the left), its outputs' right of it.
    ton = next((e for e in crane["elements"] if e["id"] == 27), None)
    xs = d.execute_script(
        "return [...document.querySelectorAll('#drawing-area .live text.pin[data-id=\"27\"]')]"
        ".map(t => [t.dataset.pin, +t.getAttribute('x')]);")
    inside = ton is not None and [p for p, x in xs if ton["x"] < x < ton["x"] + ton["w"]]
    check("the TON's IN and PT values inside its box, Q and ET right of it",
          sorted(inside or []) == ["IN", "PT"] and sorted(p for p, x in xs if x > ton["x"] + ton["w"]) == ["ET", "Q"],
          (ton, xs))
    errors = console_errors(d)
    check("no script errors on the LD page", not errors, errors)


def slc_ladder(d, base, token):
    """The SLC crane's LAD 2 live: XIC X1 (B3:0/1) framed by its rung
    network's power flow and showing its bit as 1/0, as the API reads them."""
    api = Api(base, token)
    ds = requests.get(base + "/api/v1/drawings", headers=api.h, timeout=30).json()["drawings"]
    check("slc: one drawing, LAD 2 run by SLC",
          [(x["pou"], x["instances"]) for x in ds] == [("LAD 2 MAIN", ["SLC"])], ds and ds[0]["pou"])
    x1 = next((e for e in ds[0]["elements"] if e["kind"] == "contact" and e["text"] == "X1 B3:0/1"), None) if ds else None
    check("slc: XIC X1 has a power flow and its bit", x1 and x1.get("power") and x1.get("value") == "B3:0/1", x1)
    if not x1:
        return
    api.step(3)
    power = api.read("SLC" + x1["power"])["SLC" + x1["power"]]
    bit = api.read("B3:0/1")["B3:0/1"]
    check("slc: step 1 active at rest (X1 = 1: SLC bits read as 1/0), its contact powered", (bit, power) == ("1", "TRUE"), (bit, power))
    d.get(base + "/?token=" + token + "#drawings")
    frame = lambda: d.execute_script(
        f"const r = document.querySelector('#drawing-area .live rect.power[data-id=\"{x1['id']}\"]');"
        "return r ? r.getAttribute('class') : null;")
    text = lambda: d.execute_script(
        f"const t = document.querySelector('#drawing-area .live text.value[data-id=\"{x1['id']}\"]');"
        "return t ? t.textContent : null;")
    v = wait(d, "slc frame", lambda: frame() == "power on" and text() == "1")
    check("slc: the page frames XIC X1 powered (green) and shows B3:0/1 as 1", v, (frame(), text()))
    errors = console_errors(d)
    check("no script errors on the SLC page", not errors, errors)


def main():
    crane_url, crane_token, load_url, load_token, shots, ld_url, ld_token, slc_url, slc_token = sys.argv[1:10]
    d = browser()
    try:
        crane(d, crane_url, crane_token, shots)
        load(d, load_url, load_token, shots)
        ladder(d, ld_url, ld_token, shots)
        slc_ladder(d, slc_url, slc_token)
    finally:
        d.quit()
    print(f"{passed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
