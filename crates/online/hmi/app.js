// automat HMI: a single page over the documented online API
// (docs/online-api.md). No framework and no build step: the DOM is built
// once per structure change and only changed values are written after
// that, from one requestAnimationFrame per batch of updates, so nothing
// flickers and a fast WebSocket never makes the page fall behind.
'use strict';

const $ = (sel) => document.querySelector(sel);

/** An HTML element with attributes (`on*` are listeners) and children. */
function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v === undefined || v === null || v === false) continue;
    if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else if (k === 'class') e.className = v;
    else if (k === 'text') e.textContent = v;
    else e.setAttribute(k, v === true ? '' : String(v));
  }
  for (const c of children) if (c !== null && c !== undefined) e.append(c);
  return e;
}

/** `T#1m4s990ms` as the runtime writes durations (`--trace`, `--print`). */
function duration(ns) {
  if (ns === 0) return 'T#0s';
  let out = 'T#';
  if (ns < 0) { out += '-'; ns = -ns; }
  const units = [['d', 86400e9], ['h', 3600e9], ['m', 60e9], ['s', 1e9], ['ms', 1e6], ['us', 1e3], ['ns', 1]];
  for (const [name, size] of units) {
    const n = Math.floor(ns / size);
    ns -= n * size;
    if (n > 0) out += n + name;
  }
  return out;
}

function us(v) { return v === null || v === undefined ? '–' : v.toFixed(1) + ' µs'; }

// ---------------------------------------------------------------- state

const S = {
  token: null, role: null, user: null,
  status: null,
  values: new Map(),      // path -> IEC literal text
  forced: new Set(),      // watched paths that are forced
  invalid: new Set(),     // paths the server refused
  plcNs: 0, scans: 0,
  // The number of the newest snapshot whose values are shown: a reply
  // about an older one (a read answered after the next scan's update)
  // is left out.
  seq: 0,
  symbols: [], types: new Map(), leaves: [],
  charts: [],
  view: 'overview',
  dirty: false,
  // Figures the browser test reads (window.automatHmi.stats).
  stats: { messages: 0, renders: 0, renderedPlcNs: 0, messagePlcNs: 0 },
};
window.automatHmi = S;

const ROLE_RANK = { viewer: 0, operator: 1, engineer: 2 };
const may = (role) => (ROLE_RANK[S.role] ?? -1) >= ROLE_RANK[role];

function say(text, isError) {
  const m = $('#message');
  m.textContent = text;
  m.className = 'message' + (isError ? ' error' : '');
  m.hidden = !text;
  clearTimeout(say.timer);
  if (text) say.timer = setTimeout(() => { m.hidden = true; }, isError ? 8000 : 3000);
}

class ApiError extends Error {
  constructor(status, message) { super(message); this.status = status; }
}

async function api(method, path, body) {
  const headers = { Authorization: 'Bearer ' + S.token };
  if (body !== undefined) headers['Content-Type'] = 'application/json';
  const r = await fetch(path, { method, headers, body: body === undefined ? undefined : JSON.stringify(body) });
  let data = null;
  try { data = await r.json(); } catch (_) { data = null; }
  if (r.status === 401) { logout('The session has expired or the token is wrong: log in again.'); }
  if (!r.ok) throw new ApiError(r.status, (data && data.error) || r.statusText);
  return data;
}

// ---------------------------------------------------------------- login

function saveAuth() {
  sessionStorage.setItem('automat.auth', JSON.stringify({ token: S.token, role: S.role, user: S.user }));
}

function loadAuth() {
  const q = new URLSearchParams(location.search);
  const t = q.get('token');
  if (t) {
    // The token file's token has the engineer's rights. It leaves the
    // address bar at once (history, screenshots, shoulders).
    S.token = t; S.role = 'engineer'; S.user = 'token';
    saveAuth();
    q.delete('token');
    const rest = q.toString();
    history.replaceState(null, '', location.pathname + (rest ? '?' + rest : '') + location.hash);
    return true;
  }
  try {
    const a = JSON.parse(sessionStorage.getItem('automat.auth') || 'null');
    if (a && a.token) { Object.assign(S, a); return true; }
  } catch (_) { /* nothing stored */ }
  return false;
}

function logout(why) {
  sessionStorage.removeItem('automat.auth');
  S.token = null;
  Watcher.close();
  for (const v of document.querySelectorAll('.view')) v.hidden = true;
  $('#tabs').hidden = true;
  $('#logout').hidden = true;
  $('#who').textContent = '';
  $('#login').hidden = false;
  $('#login-error').textContent = why || '';
  $('#login-user').focus();
}

$('#login-form').addEventListener('submit', async (ev) => {
  ev.preventDefault();
  const user = $('#login-user').value, password = $('#login-password').value;
  $('#login-error').textContent = '';
  try {
    const r = await fetch('/api/v1/login', {
      method: 'POST', headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify({ user, password }),
    });
    const data = await r.json().catch(() => ({}));
    if (!r.ok) { $('#login-error').textContent = data.error || r.statusText; return; }
    S.token = data.token; S.role = data.role; S.user = user;
    $('#login-password').value = '';
    saveAuth();
    start();
  } catch (e) {
    $('#login-error').textContent = 'The PLC does not answer: ' + e.message;
  }
});
$('#logout').addEventListener('click', () => logout(''));

// ---------------------------------------------------------------- WebSocket

/** One subscription holding every path the page needs now. */
const Watcher = {
  ws: null, paths: [], retry: 0, timer: null, pending: false,
  wanted() {
    const set = new Set();
    for (const v of Object.values(Views)) for (const p of v.paths()) if (!S.invalid.has(p)) set.add(p);
    return [...set].slice(0, 1000);
  },
  /** Resubscribes (soon, once) when the set of paths changed. */
  update() {
    if (this.pending) return;
    this.pending = true;
    setTimeout(() => {
      this.pending = false;
      const want = this.wanted();
      if (want.join('\n') === this.paths.join('\n') && this.ws) return;
      this.paths = want;
      this.send();
    }, 30);
  },
  send() {
    if (!this.ws) { this.open(); return; }
    if (this.ws.readyState === WebSocket.OPEN) {
      this.ws.send(JSON.stringify({ subscribe: this.paths, period_ms: Trends.period }));
    }
  },
  open() {
    if (!S.token) return;
    const scheme = location.protocol === 'https:' ? 'wss' : 'ws';
    const ws = new WebSocket(`${scheme}://${location.host}/api/v1/watch?token=${encodeURIComponent(S.token)}`);
    this.ws = ws;
    // A restarted server numbers its snapshots from 0 again.
    ws.onopen = () => { this.retry = 0; S.seq = 0; this.send(); };
    ws.onmessage = (ev) => this.message(ev.data);
    ws.onclose = () => {
      if (this.ws !== ws) return;
      this.ws = null;
      if (!S.token) return;
      this.retry = Math.min(this.retry + 1, 5);
      clearTimeout(this.timer);
      this.timer = setTimeout(() => this.open(), 400 * this.retry);
    };
  },
  close() {
    if (this.ws) { const ws = this.ws; this.ws = null; ws.close(); }
  },
  message(text) {
    let m;
    try { m = JSON.parse(text); } catch (_) { return; }
    if (m.error) {
      // A path the program does not have (a watch list of another
      // version): left out, the rest watched.
      const named = [...m.error.matchAll(/`([^`]+)`/g)].map((x) => x[1]);
      const bad = this.paths.filter((p) => named.some((n) => n.toLowerCase() === p.toLowerCase()));
      if (bad.length) { for (const p of bad) S.invalid.add(p); say(m.error, true); this.update(); kick(); }
      else say(m.error, true);
      return;
    }
    S.stats.messages++;
    S.stats.messagePlcNs = m.plc_time_ns;
    if (m.seq >= S.seq) {
      S.seq = m.seq;
      S.plcNs = m.plc_time_ns; S.scans = m.scans;
      for (const [k, v] of Object.entries(m.values)) S.values.set(k, v);
      S.forced = new Set(m.forced || []);
    }
    Trends.sample(m);
    kick();
  },
};

// ---------------------------------------------------------------- rendering

let raf = 0;
function kick() {
  S.dirty = true;
  if (!raf) raf = requestAnimationFrame(frame);
}
function frame() {
  raf = 0;
  if (!S.dirty) return;
  S.dirty = false;
  $('#clock').textContent = duration(S.plcNs);
  const v = Views[S.view];
  if (v && v.render) v.render();
  S.stats.renders++;
  S.stats.renderedPlcNs = S.plcNs;
}

function setText(node, text) { if (node.textContent !== text) node.textContent = text; }

// ---------------------------------------------------------------- overview

const Overview = {
  paths() { return []; },
  init() {
    for (const b of document.querySelectorAll('#control button')) {
      b.addEventListener('click', () => this.control(b.dataset.command));
    }
  },
  async control(command) {
    const body = { command };
    if (command === 'step') body.scans = Math.max(1, parseInt($('#ctl-scans').value, 10) || 1);
    try { await api('POST', '/api/v1/control', body); say(`${command.replace('_', ' ')}: done`); }
    catch (e) { say(e.message, true); }
    poll();
  },
  show() {
    const eng = may('engineer');
    for (const b of document.querySelectorAll('#control button')) b.disabled = !eng;
    $('#ctl-scans').disabled = !eng;
    setText($('#control-note'), eng ? '' : `Run control needs the engineer role (you are ${S.role}).`);
  },
  render() {
    const s = S.status;
    if (!s) return;
    setText($('#ov-project'), s.project || '(source files)');
    setText($('#ov-state'), s.state);
    setText($('#ov-time'), duration(Math.max(s.plc_time_ns, S.plcNs)));
    setText($('#ov-scans'), String(Math.max(s.scans, S.scans)));
    setText($('#ov-scan'), `${us(s.scan_time_us.min)} / ${us(s.scan_time_us.avg)} / ${us(s.scan_time_us.max)}`);
    setText($('#ov-overruns'), String(s.overruns));
    setText($('#ov-cycle'), duration(s.cycle_time_ns));
    const f = $('#ov-fault');
    f.hidden = !s.fault;
    if (s.fault) { setText($('#ov-fault-message'), s.fault.message); setText($('#ov-fault-site'), s.fault.site); }
    const key = JSON.stringify(s.tasks);
    if (this.tasksKey !== key) {
      this.tasksKey = key;
      $('#ov-tasks').replaceChildren(...(s.tasks || []).map((t) => el('tr', {},
        el('td', { text: t.name }),
        el('td', { text: t.interval_ns === null ? 'cyclic' : duration(t.interval_ns) }),
        el('td', { text: String(t.priority) }),
        el('td', { text: t.programs.join(', ') }))));
    }
  },
};

async function poll() {
  if (!S.token) return;
  try {
    const s = await api('GET', '/api/v1/status');
    const before = S.status && S.status.state;
    S.status = s;
    const b = $('#state');
    setText(b, s.state);
    b.className = 'badge ' + s.state;
    setText($('#project'), s.project || '');
    if (s.plc_time_ns > S.plcNs) S.plcNs = s.plc_time_ns;
    if (before !== s.state && S.view === 'overview') Overview.show();
    kick();
  } catch (e) {
    if (e.status !== 401) { setText($('#state'), 'offline'); $('#state').className = 'badge fault'; }
  }
}

// ---------------------------------------------------------------- watch

/** Named watch lists, kept per project in the browser. */
const Lists = {
  key() { return 'automat.hmi.watch.' + ((S.status && S.status.project) || 'sources'); },
  load() {
    try {
      const d = JSON.parse(localStorage.getItem(this.key()) || 'null');
      if (d && d.lists && Object.keys(d.lists).length) { this.data = d; return; }
    } catch (_) { /* a damaged entry starts over */ }
    this.data = { current: 'Watch 1', lists: { 'Watch 1': [] } };
  },
  save() { localStorage.setItem(this.key(), JSON.stringify(this.data)); },
  get current() { return this.data.lists[this.data.current] || []; },
};

const Watch = {
  rows: new Map(),
  paths() { return S.view === 'watch' ? Lists.current : []; },
  init() {
    $('#sym-filter').addEventListener('input', () => this.tree());
    $('#wl-select').addEventListener('change', (e) => { Lists.data.current = e.target.value; Lists.save(); this.build(); });
    $('#wl-new').addEventListener('click', () => {
      const name = prompt('Name of the new watch list', 'Watch ' + (Object.keys(Lists.data.lists).length + 1));
      if (!name) return;
      if (!Lists.data.lists[name]) Lists.data.lists[name] = [];
      Lists.data.current = name; Lists.save(); this.build();
    });
    $('#wl-rename').addEventListener('click', () => {
      const old = Lists.data.current;
      const name = prompt('New name of the list', old);
      if (!name || name === old || Lists.data.lists[name]) return;
      Lists.data.lists[name] = Lists.data.lists[old];
      delete Lists.data.lists[old];
      Lists.data.current = name; Lists.save(); this.build();
    });
    $('#wl-delete').addEventListener('click', () => {
      if (Object.keys(Lists.data.lists).length === 1) { Lists.data.lists[Lists.data.current] = []; }
      else { delete Lists.data.lists[Lists.data.current]; Lists.data.current = Object.keys(Lists.data.lists)[0]; }
      Lists.save(); this.build();
    });
    const add = () => { const p = $('#wl-add-path').value.trim(); if (p) { this.add(p); $('#wl-add-path').value = ''; } };
    $('#wl-add').addEventListener('click', add);
    $('#wl-add-path').addEventListener('keydown', (e) => { if (e.key === 'Enter') add(); });
    $('#unforce-all').addEventListener('click', async () => {
      try { await api('POST', '/api/v1/unforce', { all: true }); say('every force released'); }
      catch (e) { say(e.message, true); }
      refresh();
    });
  },
  add(path) {
    const list = Lists.current;
    if (list.some((p) => p.toLowerCase() === path.toLowerCase())) return;
    list.push(path);
    Lists.data.lists[Lists.data.current] = list;
    S.invalid.delete(path);
    Lists.save(); this.build();
  },
  remove(path) {
    Lists.data.lists[Lists.data.current] = Lists.current.filter((p) => p !== path);
    Lists.save(); this.build();
  },
  show() { this.build(); if (!this.treeBuilt) this.tree(); },
  /** The symbol tree, children made when a node is opened. */
  tree() {
    this.treeBuilt = true;
    const f = $('#sym-filter').value.trim().toLowerCase();
    const root = el('ul', { role: 'tree' });
    const matches = (n) => !f || n.path.toLowerCase().includes(f) || (n.children || []).some(matches);
    const item = (n, depth) => {
      const li = el('li', { role: 'treeitem' });
      const row = el('div', { class: 'node' });
      if (n.children) {
        const sub = el('ul', { role: 'group' });
        let open = !!f && depth < 6;
        const tw = el('button', { type: 'button', class: 'twist', 'aria-expanded': String(open), 'aria-label': (open ? 'Close ' : 'Open ') + n.path, text: open ? '▾' : '▸' });
        const fill = () => { sub.replaceChildren(...n.children.filter(matches).map((c) => item(c, depth + 1))); if (n.more) sub.append(el('li', { class: 'hint', text: `… ${n.more} more elements (watch them by path)` })); };
        tw.addEventListener('click', () => {
          open = !open; tw.textContent = open ? '▾' : '▸'; tw.setAttribute('aria-expanded', String(open));
          tw.setAttribute('aria-label', (open ? 'Close ' : 'Open ') + n.path);
          if (open) fill(); else sub.replaceChildren();
        });
        row.append(tw, el('span', { text: n.name }), el('span', { class: 'ty', text: n.type }));
        li.append(row, sub);
        if (open) fill();
      } else {
        row.append(el('button', { type: 'button', class: 'add', 'aria-label': 'Watch ' + n.path, title: 'Add to the watch list', text: '+', onclick: () => this.add(n.path) }),
          el('span', { text: n.name }), el('span', { class: 'ty', text: n.type + (n.writable ? '' : ' (read-only)') }));
        li.append(row);
      }
      return li;
    };
    root.append(...S.symbols.filter(matches).map((n) => item(n, 0)));
    $('#sym-tree').replaceChildren(root);
  },
  /** The rows of the current list (made once per list change). */
  build() {
    const sel = $('#wl-select');
    sel.replaceChildren(...Object.keys(Lists.data.lists).map((n) => el('option', { value: n, text: n, selected: n === Lists.data.current })));
    const operator = may('operator');
    this.rows = new Map();
    const rows = Lists.current.map((path) => {
      const info = S.types.get(path.toLowerCase()) || {};
      const value = el('td', { class: 'value', 'data-path': path });
      const input = el('input', { class: 'newval', 'aria-label': 'New value of ' + path, placeholder: info.type === 'BOOL' ? 'TRUE / FALSE' : 'value', disabled: !operator || info.writable === false });
      const act = (what) => async () => {
        try {
          if (what === 'unforce') await api('POST', '/api/v1/unforce', { path });
          else {
            let v = input.value.trim();
            if (!v && info.type === 'BOOL') v = S.values.get(path) === 'TRUE' ? 'FALSE' : 'TRUE';
            if (!v) { say('type a value first', true); input.focus(); return; }
            await api('POST', '/api/v1/' + what, { path, value: v });
          }
          say(`${what} ${path}: ok`);
        } catch (e) { say(e.message, true); }
        refresh();
      };
      const can = operator && info.writable !== false;
      input.addEventListener('keydown', (e) => { if (e.key === 'Enter') act('write')(); });
      const tr = el('tr', { 'data-path': path },
        el('td', { class: 'mono', text: path }),
        el('td', { text: info.type || '' }),
        value,
        el('td', {}, input),
        el('td', { class: 'acts' },
          el('button', { type: 'button', disabled: !can, onclick: act('write'), 'aria-label': 'Write ' + path, text: 'Write' }), ' ',
          el('button', { type: 'button', disabled: !can, onclick: act('force'), 'aria-label': 'Force ' + path, text: 'Force' }), ' ',
          el('button', { type: 'button', disabled: !can, onclick: act('unforce'), 'aria-label': 'Unforce ' + path, text: 'Unforce' }), ' ',
          el('button', { type: 'button', onclick: () => Trends.add(path), 'aria-label': 'Plot ' + path, text: 'Plot' }), ' ',
          el('button', { type: 'button', onclick: () => this.remove(path), 'aria-label': 'Remove ' + path, text: '✕' })));
      this.rows.set(path, { tr, value, forced: null, text: null, invalid: null });
      return tr;
    });
    $('#wl-rows').replaceChildren(...rows);
    $('#wl-empty').hidden = rows.length > 0;
    Watcher.update();
    kick();
  },
  render() {
    for (const [path, r] of this.rows) {
      const text = S.values.get(path);
      if (text !== undefined && text !== r.text) { r.value.textContent = text; r.text = text; }
      const forced = S.forced.has(path);
      if (forced !== r.forced) { r.tr.classList.toggle('forced', forced); r.forced = forced; r.tr.title = forced ? 'forced' : ''; }
      const invalid = S.invalid.has(path);
      if (invalid !== r.invalid) { r.tr.classList.toggle('invalid', invalid); r.invalid = invalid; if (invalid) r.value.textContent = 'unknown path'; }
    }
  },
};

/** Values and forces read at once after a write or force: a stopped PLC
 * (or the virtual clock) sends no WebSocket update until its next scan. */
async function refresh() {
  const paths = Lists.current.filter((p) => !S.invalid.has(p)).slice(0, 1000);
  try {
    const f = await api('GET', '/api/v1/forces');
    const forced = new Set(Object.keys(f.forces).map((p) => p.toLowerCase()));
    let r = { seq: f.seq, values: {} };
    if (paths.length) {
      const q = paths.map((p) => 'path=' + encodeURIComponent(p)).join('&');
      r = await api('GET', '/api/v1/read?' + q);
    }
    // An update of a later scan came while these requests ran (a step
    // right after the click): it is newer, the replies are dropped.
    if (f.seq < S.seq || r.seq < S.seq) return;
    S.seq = r.seq;
    for (const [k, v] of Object.entries(r.values)) S.values.set(k, v);
    // Forces given under another name of the same location show at the
    // next scan's update.
    S.forced = new Set([...S.forced].filter((p) => forced.has(p.toLowerCase())).concat(paths.filter((p) => forced.has(p.toLowerCase()))));
    kick();
  } catch (_) { /* the next update shows it */ }
}

async function loadSymbols() {
  const r = await api('GET', '/api/v1/symbols');
  S.symbols = r.symbols;
  Watch.treeBuilt = false;
  S.types = new Map(); S.leaves = [];
  const walk = (n) => {
    S.types.set(n.path.toLowerCase(), { type: n.type, writable: n.writable });
    if (n.children) n.children.forEach(walk); else S.leaves.push(n.path);
  };
  S.symbols.forEach(walk);
  $('#tr-paths').replaceChildren(...S.leaves.map((p) => el('option', { value: p })));
}

// ---------------------------------------------------------------- charts

const Charts = {
  paths() { return S.view === 'charts' && this.drawn ? this.drawn.paths : []; },
  init() {
    $('#chart-select').addEventListener('change', () => { this.fillInstances(); this.draw(); });
    $('#chart-instance').addEventListener('change', () => this.draw());
  },
  async load() {
    const r = await api('GET', '/api/v1/charts');
    S.charts = r.charts;
    $('#chart-select').replaceChildren(...S.charts.map((c, i) => el('option', { value: String(i), text: `${c.pou} (${c.kind}, ${c.file.split('/').pop()}:${c.line})` })));
    this.fillInstances();
  },
  fillInstances() {
    const c = S.charts[+$('#chart-select').value];
    $('#chart-instance').replaceChildren(...(c ? c.instances : []).map((p) => el('option', { value: p, text: p })));
  },
  show() {
    if (!S.charts.length) { $('#chart-area').replaceChildren(el('p', { class: 'hint', text: 'The program has no SFC chart.' })); return; }
    this.draw();
  },
  draw() {
    const c = S.charts[+$('#chart-select').value];
    if (!c) return;
    const inst = $('#chart-instance').value || '';
    this.drawn = window.SfcChart.draw(c, inst);
    $('#chart-area').replaceChildren(this.drawn.svg);
    Watcher.update();
    kick();
  },
  render() { if (this.drawn) this.drawn.update(S.values); },
};

// ---------------------------------------------------------------- LD/FBD drawings

const Drawings = {
  list: [],
  paths() { return S.view === 'drawings' && this.drawn ? this.drawn.paths : []; },
  init() {
    $('#drawing-select').addEventListener('change', () => { this.fillInstances(); this.draw(); });
    $('#drawing-instance').addEventListener('change', () => this.draw());
  },
  async load() {
    const r = await api('GET', '/api/v1/drawings');
    this.list = r.drawings;
    $('#drawing-select').replaceChildren(...this.list.map((d, i) => el('option', { value: String(i), text: `${d.pou} (${d.lang}, ${d.file.split('/').pop()})` })));
    this.fillInstances();
  },
  fillInstances() {
    const d = this.list[+$('#drawing-select').value];
    $('#drawing-instance').replaceChildren(...(d ? d.instances : []).map((p) => el('option', { value: p, text: p })));
  },
  show() {
    if (!this.list.length) { $('#drawing-area').replaceChildren(el('p', { class: 'hint', text: 'The program has no LD or FBD body.' })); return; }
    this.draw();
  },
  draw() {
    const d = this.list[+$('#drawing-select').value];
    if (!d) return;
    const inst = $('#drawing-instance').value || '';
    this.drawn = window.LdDrawing.draw(d, inst);
    $('#drawing-area').replaceChildren(this.drawn.svg);
    Watcher.update();
    kick();
  },
  render() { if (this.drawn) this.drawn.update(S.values); },
};

// ---------------------------------------------------------------- trends

const COLORS = ['#1f5fbf', '#e0462b', '#2e9d4f', '#9b51e0', '#d98b00', '#00838f', '#c2185b', '#5d4037', '#455a64', '#7cb342'];

const Trends = {
  period: 0,
  paths() { return this.columns; },
  columns: [],          // the plotted paths, in column order
  rows: [],             // [plc_time_ns, [text per column]]
  max: 50000,
  span: 10e9,           // visible time span in ns
  end: null,            // right edge in ns; null: follows the newest sample
  paused: false,
  init() {
    const c = $('#tr-canvas');
    this.ctx = c.getContext('2d');
    $('#tr-add').addEventListener('click', () => { const p = $('#tr-path').value.trim(); if (p) { this.add(p); $('#tr-path').value = ''; } });
    $('#tr-path').addEventListener('keydown', (e) => { if (e.key === 'Enter') $('#tr-add').click(); });
    $('#tr-pause').addEventListener('click', () => this.pause(!this.paused));
    $('#tr-live').addEventListener('click', () => { this.end = null; this.pause(false); });
    $('#tr-zoom-in').addEventListener('click', () => this.zoom(0.5));
    $('#tr-zoom-out').addEventListener('click', () => this.zoom(2));
    $('#tr-clear').addEventListener('click', () => { this.rows = []; kick(); });
    $('#tr-csv').addEventListener('click', () => this.csv());
    c.addEventListener('wheel', (e) => {
      e.preventDefault();
      const r = c.getBoundingClientRect();
      this.zoom(e.deltaY > 0 ? 1.25 : 0.8, (e.clientX - r.left - this.plotLeft) / Math.max(1, r.width - this.plotLeft - 10));
    }, { passive: false });
    c.addEventListener('pointerdown', (e) => {
      c.setPointerCapture(e.pointerId);
      this.drag = { x: e.clientX, end: this.rightEdge() };
      c.style.cursor = 'grabbing';
    });
    c.addEventListener('pointermove', (e) => {
      if (!this.drag) return;
      const w = c.getBoundingClientRect().width - this.plotLeft - 10;
      this.end = this.drag.end - (e.clientX - this.drag.x) / Math.max(1, w) * this.span;
      this.pause(true); kick();
    });
    c.addEventListener('pointerup', () => { this.drag = null; c.style.cursor = ''; });
    c.addEventListener('keydown', (e) => {
      const step = this.span / 10;
      if (e.key === 'ArrowLeft') { this.end = this.rightEdge() - step; this.pause(true); }
      else if (e.key === 'ArrowRight') { this.end = this.rightEdge() + step; this.pause(true); }
      else if (e.key === '+' || e.key === '=') this.zoom(0.5);
      else if (e.key === '-') this.zoom(2);
      else return;
      e.preventDefault(); kick();
    });
    this.plotLeft = 150;
  },
  pause(on) {
    this.paused = on;
    if (on && this.end === null) this.end = this.newest();
    if (!on) this.end = null;
    $('#tr-pause').setAttribute('aria-pressed', String(on));
    kick();
  },
  zoom(f, at) {
    const right = this.rightEdge();
    const frac = at === undefined ? 1 : Math.min(1, Math.max(0, at));
    const pivot = right - this.span * (1 - frac);
    this.span = Math.min(3600e9, Math.max(50e6, this.span * f));
    if (at !== undefined || this.end !== null) { this.end = pivot + this.span * (1 - frac); if (!this.paused && at !== undefined && frac < 1) this.pause(true); }
    kick();
  },
  newest() { return this.rows.length ? this.rows[this.rows.length - 1][0] : S.plcNs; },
  rightEdge() { return this.end === null ? this.newest() : this.end; },
  add(path) {
    if (this.columns.includes(path)) { setView('trends'); return; }
    // A new column starts a new recording: every row has every column,
    // as in a `--trace` file.
    this.columns = [...this.columns, path];
    this.rows = [];
    this.legend();
    Watcher.update();
    setView('trends');
  },
  remove(path) {
    this.columns = this.columns.filter((p) => p !== path);
    this.rows = [];
    this.legend(); Watcher.update(); kick();
  },
  legend() {
    $('#tr-legend').replaceChildren(...this.columns.map((p, i) => el('span', { class: 'item' },
      el('span', { class: 'sw', 'data-color': String(i) }), el('span', { class: 'mono', text: p }),
      el('button', { type: 'button', 'aria-label': 'Stop plotting ' + p, text: '✕', onclick: () => this.remove(p) }))));
    // Swatch colours through the CSSOM (no inline style attributes).
    for (const sw of document.querySelectorAll('#tr-legend .sw')) sw.style.background = COLORS[+sw.dataset.color % COLORS.length];
  },
  sample(m) {
    if (!this.columns.length) return;
    const vals = this.columns.map((p) => m.values[p]);
    if (vals.some((v) => v === undefined)) return;
    const last = this.rows[this.rows.length - 1];
    if (last && last[0] === m.plc_time_ns) { last[1] = vals; return; }
    this.rows.push([m.plc_time_ns, vals]);
    if (this.rows.length > this.max) this.rows.splice(0, this.rows.length - this.max);
  },
  /** The recording in the `--trace` CSV format. */
  csv() {
    const cell = (t) => /[,"\n\r]/.test(t) ? '"' + t.replace(/"/g, '""') + '"' : t;
    const lines = [['time', ...this.columns.map(cell)].join(',')];
    for (const [t, vals] of this.rows) lines.push([duration(t), ...vals.map(cell)].join(','));
    const blob = new Blob([lines.join('\n') + '\n'], { type: 'text/csv' });
    const a = el('a', { href: URL.createObjectURL(blob), download: ((S.status && S.status.project) || 'trace') + '.csv' });
    document.body.append(a); a.click(); a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    this.lastCsv = lines.join('\n') + '\n';
  },
  render() {
    const c = $('#tr-canvas'), ctx = this.ctx;
    const dpr = window.devicePixelRatio || 1;
    const w = c.clientWidth, h = c.clientHeight;
    if (c.width !== Math.round(w * dpr) || c.height !== Math.round(h * dpr)) { c.width = Math.round(w * dpr); c.height = Math.round(h * dpr); }
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, w, h);
    ctx.font = '12px system-ui, sans-serif';
    let right = this.rightEdge(), left = right - this.span;
    // Following a recording shorter than the span: it starts at the left.
    if (this.end === null && this.rows.length && left < this.rows[0][0]) { left = this.rows[0][0]; right = left + this.span; }
    setText($('#tr-window'), `${duration(Math.max(0, Math.round(left)))} … ${duration(Math.max(0, Math.round(right)))}${this.paused ? ' (paused)' : ''}`);
    const x0 = this.plotLeft, x1 = w - 10;
    const X = (t) => x0 + (t - left) / this.span * (x1 - x0);
    // Booleans (and step flags as bands) in lanes at the bottom, numbers
    // as lines above, as `automat plot` draws them.
    const kinds = this.columns.map((p, i) => {
      const first = this.rows.length ? this.rows[this.rows.length - 1][1][i] : '';
      return first === 'TRUE' || first === 'FALSE' ? (/\.x$/i.test(p) ? 'band' : 'bool') : 'num';
    });
    const lanes = kinds.filter((k) => k !== 'num').length;
    // Without numbers the lanes share the height.
    const laneH = kinds.includes('num') ? 22 : Math.max(22, Math.min(70, (h - 50) / Math.max(1, lanes)));
    const numTop = 10, numBottom = h - 24 - lanes * laneH - (lanes ? 8 : 0);
    // Grid and time axis.
    ctx.strokeStyle = '#e5e7eb'; ctx.fillStyle = '#5d6675'; ctx.lineWidth = 1;
    const stepNs = niceStep(this.span / 8);
    for (let t = Math.ceil(left / stepNs) * stepNs; t <= right; t += stepNs) {
      const x = Math.round(X(t)) + 0.5;
      ctx.beginPath(); ctx.moveTo(x, numTop); ctx.lineTo(x, h - 22); ctx.stroke();
      ctx.fillText(duration(Math.round(t)), x + 2, h - 8);
    }
    if (!this.columns.length) { ctx.fillText('Choose paths to plot (Plot in the watch table, or the field above).', x0, 40); return; }
    const visible = this.rows.filter(([t], k) => t >= left - this.span && t <= right + this.span || k === 0);
    // Numbers share one autoscaled axis.
    let lo = Infinity, hi = -Infinity;
    kinds.forEach((k, i) => {
      if (k !== 'num') return;
      for (const [t, v] of visible) { if (t < left || t > right) continue; const n = numeric(v[i]); if (n !== null) { lo = Math.min(lo, n); hi = Math.max(hi, n); } }
    });
    if (lo === Infinity) { lo = 0; hi = 1; }
    if (lo === hi) { lo -= 1; hi += 1; }
    const Y = (n) => numBottom - (n - lo) / (hi - lo) * (numBottom - numTop);
    if (kinds.includes('num')) {
      // TIME values (step times, timers) are labelled as durations.
      const newest = this.rows.length ? this.rows[this.rows.length - 1][1] : [];
      const times = newest.length > 0 && kinds.every((k, i) => k !== 'num' || /^L?T#/i.test(newest[i]));
      const label = (n) => times ? duration(Math.round(n / 1e6) * 1e6) : fmt(n);
      ctx.fillStyle = '#5d6675';
      ctx.fillText(label(hi), 8, numTop + 10); ctx.fillText(label(lo), 8, numBottom);
      ctx.strokeStyle = '#c9ced6'; ctx.beginPath(); ctx.moveTo(x0, numBottom + 0.5); ctx.lineTo(x1, numBottom + 0.5); ctx.stroke();
    }
    let lane = 0;
    kinds.forEach((k, i) => {
      const color = COLORS[i % COLORS.length];
      ctx.strokeStyle = color; ctx.fillStyle = color; ctx.lineWidth = 1.6;
      if (k === 'num') {
        ctx.beginPath();
        let started = false;
        for (const [t, v] of visible) {
          const n = numeric(v[i]);
          if (n === null) continue;
          const x = X(t), y = Y(n);
          if (!started) { ctx.moveTo(x, y); started = true; } else ctx.lineTo(x, y);
        }
        ctx.stroke();
        return;
      }
      const top = numBottom + 8 + lane * laneH, bottom = top + laneH - 6;
      lane++;
      ctx.fillStyle = '#1d2430';
      ctx.fillText(shorten(this.columns[i], 20), 8, bottom - 2);
      ctx.fillStyle = color;
      if (k === 'band') {
        ctx.globalAlpha = 0.55;
        let from = null;
        for (const [t, v] of visible) {
          if (v[i] === 'TRUE' && from === null) from = t;
          if (v[i] !== 'TRUE' && from !== null) { ctx.fillRect(X(from), top, X(t) - X(from), bottom - top); from = null; }
        }
        if (from !== null) ctx.fillRect(X(from), top, X(this.newest()) - X(from), bottom - top);
        ctx.globalAlpha = 1;
      } else {
        ctx.beginPath();
        let prev = null;
        for (const [t, v] of visible) {
          const y = v[i] === 'TRUE' ? top : bottom;
          const x = X(t);
          if (prev === null) ctx.moveTo(x, y); else { ctx.lineTo(x, prev); ctx.lineTo(x, y); }
          prev = y;
        }
        ctx.stroke();
      }
    });
  },
};

function niceStep(ns) {
  const steps = [1e6, 2e6, 5e6, 10e6, 20e6, 50e6, 100e6, 200e6, 500e6, 1e9, 2e9, 5e9, 10e9, 15e9, 30e9, 60e9, 120e9, 300e9, 600e9, 1800e9, 3600e9];
  return steps.find((s) => s >= ns) || 3600e9;
}
/** The number a value's text stands for (INT, REAL, TIME in ns), or null. */
function numeric(text) {
  if (text === undefined) return null;
  if (text === 'TRUE') return 1;
  if (text === 'FALSE') return 0;
  const t = /^L?T#(-)?(.*)$/i.exec(text);
  if (t) {
    let ns = 0;
    for (const [, n, u] of t[2].matchAll(/([0-9.]+)(d|h|ms|m|s|us|ns)/g)) ns += parseFloat(n) * { d: 86400e9, h: 3600e9, m: 60e9, s: 1e9, ms: 1e6, us: 1e3, ns: 1 }[u];
    return t[1] ? -ns : ns;
  }
  const n = Number(text.replace(/^[A-Z_]+#/i, '').replace(/_/g, ''));
  return Number.isFinite(n) ? n : null;
}
function fmt(n) { return Math.abs(n) >= 1e6 || (Math.abs(n) < 0.01 && n !== 0) ? n.toExponential(2) : String(+n.toFixed(3)); }
function shorten(s, n) { return s.length > n ? '…' + s.slice(-n + 1) : s; }

// ---------------------------------------------------------------- plant

const Plant = {
  data: null, rows: new Map(), timer: null, missing: false,
  paths() { return []; },
  show() { this.fetch(); clearInterval(this.timer); this.timer = setInterval(() => this.fetch(), 100); },
  hide() { clearInterval(this.timer); this.timer = null; },
  async fetch() {
    if (this.busy) return;
    this.busy = true;
    try {
      const d = await api('GET', '/api/v1/plant');
      const shape = d.signals.map((s) => s.name).join() + '|' + d.quantities.map((q) => q.name).join();
      this.data = d;
      if (shape !== this.shape) { this.shape = shape; this.build(); }
      kick();
    } catch (e) {
      if (e.status === 404) { this.hide(); this.missing = true; $('#plant-title').textContent = 'No plant'; $('#mimic').replaceChildren(el('p', { class: 'hint', text: e.message })); }
    } finally { this.busy = false; }
  },
  async op(body) {
    try { await api('POST', '/api/v1/plant', body); } catch (e) { say(e.message, true); }
    this.fetch();
  },
  build() {
    const d = this.data, operator = may('operator');
    $('#plant-title').textContent = `Plant: ${d.model}`;
    this.mimic = window.Mimics.make(d.mimic, d);
    $('#mimic').replaceChildren(this.mimic ? this.mimic.svg : el('p', { class: 'hint', text: 'This model declares no mimic: the panel shows every signal.' }));
    this.rows = new Map();
    $('#plant-signals').replaceChildren(...d.signals.map((s) => {
      const value = el('td', { class: 'value' });
      const ops = el('td', { class: 'acts' });
      if (s.dir === 'operator' && s.kind === 'BOOL') {
        // Press: held while the pointer or the key is down. Hold: latched.
        const press = el('button', { type: 'button', class: 'press', disabled: !operator, text: 'Press', 'aria-label': 'Press ' + s.name, 'data-signal': s.name });
        let down = false;
        const on = (e) => { if (down) return; down = true; press.classList.add('down'); this.op({ action: 'press', signal: s.name }); if (e.pointerId !== undefined) press.setPointerCapture(e.pointerId); };
        const off = () => { if (!down) return; down = false; press.classList.remove('down'); this.op({ action: 'release', signal: s.name }); };
        press.addEventListener('pointerdown', on);
        press.addEventListener('pointerup', off);
        press.addEventListener('pointercancel', off);
        press.addEventListener('keydown', (e) => { if ((e.key === ' ' || e.key === 'Enter') && !e.repeat) { e.preventDefault(); on(e); } });
        press.addEventListener('keyup', (e) => { if (e.key === ' ' || e.key === 'Enter') { e.preventDefault(); off(); } });
        press.addEventListener('blur', off);
        const hold = el('button', { type: 'button', 'aria-pressed': 'false', disabled: !operator, text: 'Hold', 'aria-label': 'Hold ' + s.name });
        hold.addEventListener('click', () => {
          const now = hold.getAttribute('aria-pressed') !== 'true';
          hold.setAttribute('aria-pressed', String(now));
          this.op({ action: now ? 'press' : 'release', signal: s.name });
        });
        const pulse = el('button', { type: 'button', disabled: !operator, text: '200 ms', 'aria-label': 'Press ' + s.name + ' for 200 ms', onclick: () => this.op({ action: 'press', signal: s.name, for_ms: 200 }) });
        ops.append(press, ' ', hold, ' ', pulse);
      } else {
        const input = el('input', { class: 'newval', disabled: !operator, 'aria-label': (s.dir === 'operator' ? 'Set ' : 'Hold ') + s.name + ' at', placeholder: s.kind === 'BOOL' ? 'TRUE / FALSE' : s.kind });
        const set = el('button', { type: 'button', disabled: !operator, text: s.dir === 'operator' ? 'Set' : 'Hold at', onclick: () => { if (input.value.trim()) this.op({ action: 'set', signal: s.name, value: input.value.trim() }); } });
        ops.append(input, ' ', set);
        if (s.dir !== 'operator') ops.append(' ', el('button', { type: 'button', disabled: !operator, text: 'Free', 'aria-label': 'Free ' + s.name, onclick: () => this.op({ action: 'unstick', signal: s.name }) }));
      }
      const tr = el('tr', { title: s.doc },
        el('td', {}, el('strong', { text: s.name }), el('span', { class: 'dir', text: s.dir })),
        el('td', { text: s.kind }), el('td', { class: 'mono', text: s.bound || '–' }), value, ops);
      this.rows.set(s.name, { tr, value, text: null });
      return tr;
    }));
    this.qrows = d.quantities.map((q) => {
      const value = el('td', { class: 'value' });
      $('#plant-quantities').append(el('tr', {}, el('td', { text: q.name }), value, el('td', { class: 'hint', text: q.doc })));
      return value;
    });
    $('#plant-quantities').replaceChildren(...this.qrows.map((v) => v.parentElement));
  },
  render() {
    const d = this.data;
    if (!d) return;
    for (const s of d.signals) {
      const r = this.rows.get(s.name);
      if (!r) continue;
      const text = (typeof s.value === 'boolean' ? (s.value ? 'TRUE' : 'FALSE') : String(s.value)) + (s.stuck ? ' (held)' : '');
      if (text !== r.text) {
        r.text = text;
        r.value.replaceChildren(...(typeof s.value === 'boolean' ? [el('span', { class: 'lamp' + (s.value ? ' on' : '') })] : []), text);
      }
    }
    d.quantities.forEach((q, i) => {
      const v = this.qrows && this.qrows[i];
      if (v) setText(v, `${fmt(q.value)} ${q.unit}`.trim());
    });
    if (this.mimic) this.mimic.update(d);
  },
};

// ---------------------------------------------------------------- views

const Views = { overview: Overview, watch: Watch, charts: Charts, drawings: Drawings, trends: Trends, plant: Plant };
S.views = Views;

function setView(name) {
  if (!Views[name]) name = 'overview';
  const before = Views[S.view];
  if (before && before.hide && S.view !== name) before.hide();
  S.view = name;
  for (const b of document.querySelectorAll('#tabs button')) {
    const on = b.dataset.view === name;
    b.setAttribute('aria-selected', String(on));
    b.tabIndex = on ? 0 : -1;
  }
  for (const v of Object.keys(Views)) $('#' + v).hidden = v !== name;
  if (location.hash !== '#' + name) history.replaceState(null, '', '#' + name);
  const v = Views[name];
  if (v.show) v.show();
  Watcher.update();
  kick();
}

for (const b of document.querySelectorAll('#tabs button')) {
  b.addEventListener('click', () => setView(b.dataset.view));
  // Arrow keys move between tabs (the WAI-ARIA tabs pattern).
  b.addEventListener('keydown', (e) => {
    const tabs = [...document.querySelectorAll('#tabs button')];
    const i = tabs.indexOf(b);
    const next = e.key === 'ArrowRight' ? tabs[(i + 1) % tabs.length] : e.key === 'ArrowLeft' ? tabs[(i - 1 + tabs.length) % tabs.length] : null;
    if (next) { e.preventDefault(); next.focus(); setView(next.dataset.view); }
  });
}
window.addEventListener('resize', kick);

let started = false;
async function start() {
  $('#login').hidden = true;
  $('#tabs').hidden = false;
  $('#logout').hidden = false;
  $('#who').textContent = `${S.user} (${S.role})`;
  if (!started) {
    started = true;
    Overview.init(); Watch.init(); Charts.init(); Drawings.init(); Trends.init();
    setInterval(poll, 500);
  }
  await poll();
  if (!S.token) return;
  Lists.load();
  try { await loadSymbols(); await Charts.load(); await Drawings.load(); } catch (e) { say(e.message, true); }
  Watcher.open();
  setView(location.hash.slice(1) || 'overview');
}

if (loadAuth()) start(); else logout('');
