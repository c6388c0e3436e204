// SFC charts drawn as SVG from the compiler's own chart model
// (`GET /api/v1/charts`), so every dialect (textual SFC, ISaGRAF, PL7,
// PLCopen graphical SFC through its importer) is drawn the same way.
//
// Layout: steps in levels from the initial steps, breadth first, each
// transition under its preceding steps, the following steps under it; a
// transition back to a step already placed above is drawn as a jump
// (`↑ GS1`, the Grafcet step reference) instead of a long loop line.
// Links are orthogonal; a transition with several preceding or following
// steps gets the double line of a simultaneous convergence or divergence,
// several transitions leaving one step share its single line (a
// selection).
'use strict';

(function () {
  const NS = 'http://www.w3.org/2000/svg';
  const STEP_W = 110, STEP_H = 44, ACT_W = 190, ACT_ROW = 18, GAP = 34;

  function s(tag, attrs, ...children) {
    const e = document.createElementNS(NS, tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (v === undefined || v === null) continue;
      if (k === 'text') e.textContent = v; else e.setAttribute(k, String(v));
    }
    for (const c of children) if (c) e.append(c);
    return e;
  }

  const key = (n) => n.toLowerCase();

  /** The number a value's text stands for (BOOL as 1/0, INT, REAL, TIME
   * in ns), or null. */
  function num(text) {
    if (text === undefined || text === null) return null;
    const u = String(text).toUpperCase();
    if (u === 'TRUE') return 1;
    if (u === 'FALSE') return 0;
    const t = /^L?T(?:IME)?#(-)?(.*)$/.exec(u);
    if (t) {
      let ns = 0, seen = false;
      for (const [, n, unit] of t[2].replace(/_/g, '').matchAll(/([0-9.]+)(D|H|MS|M|S|US|NS)/g)) {
        ns += parseFloat(n) * { D: 86400e9, H: 3600e9, M: 60e9, S: 1e9, MS: 1e6, US: 1e3, NS: 1 }[unit];
        seen = true;
      }
      return seen ? (t[1] ? -ns : ns) : null;
    }
    const n = Number(u.replace(/^[A-Z_]+#/, '').replace(/_/g, ''));
    return Number.isFinite(n) ? n : null;
  }

  /** A transition condition as the HMI can evaluate it from watched
   * values: variables, TRUE/FALSE, numbers and durations, NOT, AND/&, XOR,
   * OR, comparisons and parentheses (IEC precedence). `resolve` gives a
   * name's path or null; anything else (calls, arithmetic, names the
   * program does not have) gives null: the transition is then only
   * marked enabled, never guessed. */
  function compile(text, resolve) {
    const toks = [];
    // `%Xi`, `%Xi.X`, `%Xi.T`: a PL7 step's activity and time (the step
    // `_Xi` of the chart model).
    const re = /\s*(>=|<=|<>|[()&<>=]|L?T(?:IME)?#[-0-9A-Za-z_.]+|%X[0-9]+(?:\.[TX])?|[0-9][0-9_.]*(?:[eE][-+]?[0-9]+)?|[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*)*)/iy;
    let at = 0;
    const src = text.trim();
    while (at < src.length) {
      re.lastIndex = at;
      const m = re.exec(src);
      if (!m) return null;
      toks.push(m[1]);
      at = re.lastIndex;
      while (at < src.length && /\s/.test(src[at])) at++;
    }
    let i = 0;
    const paths = [];
    const peek = () => (toks[i] || '').toUpperCase();
    const fail = () => { throw new Error('not evaluable'); };
    function primary() {
      const t = toks[i++];
      if (t === undefined) fail();
      if (t === '(') { const e = or(); if (toks[i++] !== ')') fail(); return e; }
      const u = t.toUpperCase();
      if (u === 'TRUE' || u === 'FALSE' || /^[0-9]/.test(t) || /^L?T(IME)?#/.test(u)) {
        const v = num(t);
        if (v === null) fail();
        return () => v;
      }
      if (['AND', 'OR', 'XOR', 'NOT', 'MOD'].includes(u)) fail();
      const pl7 = /^%X([0-9]+)(?:\.([TX]))?$/.exec(u);
      const p = resolve(pl7 ? `_X${pl7[1]}.${pl7[2] || 'X'}` : t);
      if (!p) fail();
      paths.push(p);
      return (values) => num(values.get(p));
    }
    function unary() {
      if (peek() === 'NOT') { i++; const e = unary(); return (v) => { const x = e(v); return x === null ? null : (x ? 0 : 1); }; }
      return primary();
    }
    const ops = { '>=': (a, b) => a >= b, '<=': (a, b) => a <= b, '>': (a, b) => a > b, '<': (a, b) => a < b, '=': (a, b) => a === b, '<>': (a, b) => a !== b };
    function cmp() {
      const a = unary();
      const op = ops[peek()];
      if (!op) return a;
      i++;
      const b = unary();
      return (v) => { const x = a(v), y = b(v); return x === null || y === null ? null : (op(x, y) ? 1 : 0); };
    }
    const chain = (next, names, f) => () => {
      let e = next();
      while (names.includes(peek())) {
        i++;
        const l = e, r = next();
        e = (v) => { const x = l(v), y = r(v); return x === null || y === null ? null : f(x !== 0, y !== 0) ? 1 : 0; };
      }
      return e;
    };
    const and = chain(cmp, ['AND', '&'], (a, b) => a && b);
    const xor = chain(and, ['XOR'], (a, b) => a !== b);
    const or = chain(xor, ['OR'], (a, b) => a || b);
    try {
      const e = or();
      if (i !== toks.length) return null;
      return { paths, value: (values) => { const x = e(values); return x === null ? null : x !== 0; } };
    } catch (_) {
      return null;
    }
  }

  function layout(chart) {
    // Columns leave room for the action tables beside the steps.
    const COL = chart.steps.some((st) => st.actions.length) ? STEP_W + ACT_W + 60 : 190;
    const steps = new Map();
    chart.steps.forEach((st, i) => steps.set(key(st.name), { st, i, level: null, x: 0 }));
    const trs = chart.transitions.map((t, i) => ({ t, i, level: null, x: 0, back: [] }));
    const outOf = new Map();
    for (const tr of trs) for (const f of tr.t.from) {
      const k = key(f);
      if (!outOf.has(k)) outOf.set(k, []);
      outOf.get(k).push(tr);
    }
    const queue = [];
    const place = (node, level, x) => { node.level = level; node.x = x; queue.push(node); };
    const roots = chart.steps.filter((st) => st.initial);
    let x0 = 0;
    for (const st of roots.length ? roots : chart.steps.slice(0, 1)) { place(steps.get(key(st.name)), 0, x0); x0 += COL * 2; }
    const run = () => {
      while (queue.length) {
        const n = queue.shift();
        const outs = (outOf.get(key(n.st.name)) || []).filter((tr) => tr.level === null);
        // Priority first (ISaGRAF and PL7 keep the written order).
        outs.sort((a, b) => (a.t.priority ?? a.i) - (b.t.priority ?? b.i));
        outs.forEach((tr, j) => {
          const froms = tr.t.from.map((f) => steps.get(key(f))).filter((m) => m && m.level !== null);
          tr.level = Math.max(...froms.map((m) => m.level));
          const mid = froms.reduce((a, m) => a + m.x, 0) / froms.length;
          tr.x = froms.length > 1 ? mid : n.x + (j - (outs.length - 1) / 2) * COL;
          const tos = tr.t.to.map((t) => steps.get(key(t))).filter(Boolean);
          const fresh = tos.filter((m) => m.level === null && !tr.t.jump);
          tos.forEach((m) => { if (m.level !== null || tr.t.jump) tr.back.push(m); });
          fresh.forEach((m, k) => place(m, tr.level + 1, tr.x + (k - (fresh.length - 1) / 2) * COL));
        });
      }
    };
    run();
    // Steps no transition reaches from an initial step: drawn below.
    for (const n of steps.values()) {
      if (n.level === null) {
        const deepest = Math.max(0, ...[...steps.values()].filter((m) => m.level !== null).map((m) => m.level));
        place(n, deepest + 1, 0);
        run();
      }
    }
    for (const tr of trs) if (tr.level === null) { tr.level = 0; tr.x = -COL; }
    // Forward links may now point up after all: drawn as jumps too.
    for (const tr of trs) {
      tr.fwd = tr.t.to.map((t) => steps.get(key(t))).filter((m) => m && !tr.back.includes(m));
      for (const m of tr.fwd.filter((m) => m.level <= tr.level)) tr.back.push(m);
      tr.fwd = tr.fwd.filter((m) => m.level > tr.level);
    }
    // Nodes of a level left to right, at least a column apart.
    const spread = (nodes) => {
      const byLevel = new Map();
      for (const n of nodes) { if (!byLevel.has(n.level)) byLevel.set(n.level, []); byLevel.get(n.level).push(n); }
      for (const row of byLevel.values()) {
        row.sort((a, b) => a.x - b.x);
        for (let i = 1; i < row.length; i++) if (row[i].x < row[i - 1].x + COL) row[i].x = row[i - 1].x + COL;
      }
    };
    spread([...steps.values()]);
    spread(trs);
    const levels = Math.max(0, ...[...steps.values()].map((n) => n.level), ...trs.map((t) => t.level)) + 1;
    // Each level as tall as its steps' action lists.
    const heights = new Array(levels).fill(STEP_H);
    for (const n of steps.values()) heights[n.level] = Math.max(heights[n.level], STEP_H, n.st.actions.length * ACT_ROW + 6);
    const tops = [];
    let y = 40;
    for (let l = 0; l < levels; l++) { tops.push(y); y += heights[l] + GAP * 2 + 12; }
    const minX = Math.min(...[...steps.values()].map((n) => n.x), ...trs.map((t) => t.x));
    const shift = 30 + STEP_W / 2 - minX;
    for (const n of steps.values()) n.x += shift;
    for (const t of trs) t.x += shift;
    const maxX = Math.max(...[...steps.values()].map((n) => n.x + STEP_W / 2 + (n.st.actions.length ? ACT_W + 16 : 0)), ...trs.map((t) => t.x + 260));
    return { steps, trs, tops, heights, width: maxX + 30, height: y + 20 };
  }

  function draw(chart, inst) {
    const c = chart.chart;
    const L = layout(c);
    const svg = s('svg', { class: 'sfc', width: L.width, height: L.height, viewBox: `0 0 ${L.width} ${L.height}`, role: 'img', 'aria-label': `SFC chart of ${chart.pou}` });
    svg.append(s('text', { class: 'title', x: 12, y: 22, text: `${chart.pou}${inst ? ' — ' + inst : ''}` }));
    const links = s('g'), nodes = s('g');
    svg.append(links, nodes);
    const at = (n) => ({ top: L.tops[n.level], bottom: L.tops[n.level] + STEP_H });
    const barY = (tr) => L.tops[tr.level] + L.heights[tr.level] + GAP;
    const prefix = inst ? inst + '.' : '';
    const paths = [];
    const types = (window.automatHmi && window.automatHmi.types) || new Map();
    const live = { steps: [], trs: [] };

    for (const n of L.steps.values()) {
      const { top } = at(n);
      const g = s('g', { class: 'step', 'data-step': n.st.name });
      const x = n.x - STEP_W / 2;
      g.append(s('rect', { x, y: top, width: STEP_W, height: STEP_H }));
      if (n.st.initial) g.append(s('rect', { x: x + 4, y: top + 4, width: STEP_W - 8, height: STEP_H - 8 }));
      if (n.st.body) {
        // A macro-step: the IEC symbol's lines at the top and the bottom.
        g.append(s('line', { class: 'link', x1: x, y1: top + 5, x2: x + STEP_W, y2: top + 5 }));
        g.append(s('line', { class: 'link', x1: x, y1: top + STEP_H - 5, x2: x + STEP_W, y2: top + STEP_H - 5 }));
      }
      g.append(s('text', { class: 'name', x: n.x, y: top + 19, 'text-anchor': 'middle', text: n.st.name }));
      const time = s('text', { class: 'time', x: n.x, y: top + 35, 'text-anchor': 'middle' });
      g.append(time);
      g.append(s('title', { text: `${n.st.initial ? 'initial step' : n.st.body ? 'macro-step' : 'step'} ${n.st.name} (line ${n.st.line})` }));
      if (n.st.actions.length) {
        const ax = n.x + STEP_W / 2 + 16;
        const a = s('g', { class: 'act' });
        a.append(s('line', { class: 'link', x1: n.x + STEP_W / 2, y1: top + STEP_H / 2, x2: ax, y2: top + STEP_H / 2 }));
        n.st.actions.forEach((act, i) => {
          const ay = top + i * ACT_ROW;
          a.append(s('rect', { x: ax, y: ay, width: 48, height: ACT_ROW }));
          a.append(s('rect', { x: ax + 48, y: ay, width: ACT_W - 48, height: ACT_ROW }));
          a.append(s('text', { class: 'q', x: ax + 4, y: ay + 13, text: act.qualifier + (act.time ? ' ' + act.time : '') }));
          const label = act.name + (act.indicators && act.indicators.length ? ' (' + act.indicators.join(', ') + ')' : '');
          a.append(s('text', { x: ax + 52, y: ay + 13, text: label.length > 24 ? label.slice(0, 23) + '…' : label }, s('title', { text: label })));
        });
        g.append(a);
      }
      nodes.append(g);
      const px = prefix + n.st.name + '.X', pt = prefix + n.st.name + '.T';
      // Only paths the program has (a macro body's steps may not be
      // readable by these names): a refused path would stop the others.
      if (inst && (!types.size || types.has(key(px)))) paths.push(px, pt);
      live.steps.push({ g, time, px, pt, name: key(n.st.name), on: null, t: null });
    }

    for (const tr of L.trs) {
      const y = barY(tr);
      const from = tr.t.from.map((f) => L.steps.get(key(f))).filter(Boolean);
      const g = s('g', { class: 'tr' });
      if (from.length > 1) {
        // Simultaneous convergence: a double line above the transition.
        const xs = from.map((m) => m.x).concat(tr.x);
        const dy = y - 16;
        links.append(s('line', { class: 'double', x1: Math.min(...xs) - 10, y1: dy - 3, x2: Math.max(...xs) + 10, y2: dy - 3 }));
        links.append(s('line', { class: 'double', x1: Math.min(...xs) - 10, y1: dy, x2: Math.max(...xs) + 10, y2: dy }));
        for (const m of from) links.append(s('path', { class: 'link', d: `M${m.x},${at(m).bottom} V${dy - 3}` }));
        links.append(s('path', { class: 'link', d: `M${tr.x},${dy} V${y}` }));
      } else {
        for (const m of from) links.append(s('path', { class: 'link', d: `M${m.x},${at(m).bottom} V${y - 14} H${tr.x} V${y}` }));
      }
      if (tr.fwd.length > 1) {
        const xs = tr.fwd.map((m) => m.x).concat(tr.x);
        const dy = y + 16;
        links.append(s('line', { class: 'double', x1: Math.min(...xs) - 10, y1: dy, x2: Math.max(...xs) + 10, y2: dy }));
        links.append(s('line', { class: 'double', x1: Math.min(...xs) - 10, y1: dy + 3, x2: Math.max(...xs) + 10, y2: dy + 3 }));
        links.append(s('path', { class: 'link', d: `M${tr.x},${y} V${dy}` }));
        for (const m of tr.fwd) links.append(s('path', { class: 'link', d: `M${m.x},${dy + 3} V${at(m).top}` }));
      } else {
        for (const m of tr.fwd) links.append(s('path', { class: 'link', d: `M${tr.x},${y} V${y + 16} H${m.x} V${at(m).top}` }));
      }
      if (tr.back.length) {
        links.append(s('path', { class: 'link', d: `M${tr.x},${y} V${y + 20}` }));
        g.append(s('text', { class: 'jump', x: tr.x + 6, y: y + 26, text: '↑ ' + tr.back.map((m) => m.st.name).join(', ') }));
      }
      g.append(s('line', { class: 'bar', x1: tr.x - 16, y1: y, x2: tr.x + 16, y2: y }));
      const cond = tr.t.condition || '';
      const label = (tr.t.name ? tr.t.name + ': ' : '') + (tr.t.priority !== null && tr.t.priority !== undefined ? `(${tr.t.priority}) ` : '') + cond;
      g.append(s('text', { x: tr.x + 22, y: y + 4, text: label.length > 38 ? label.slice(0, 37) + '…' : label }, s('title', { text: label + ` (line ${tr.t.line})` })));
      nodes.append(g);
      // The condition's variables are watched and the condition
      // evaluated, so a transition that can fire is marked.
      const resolve = (name) => types.has(key(prefix + name)) ? prefix + name : types.has(key(name)) ? name : null;
      const test = inst ? compile(cond, resolve) : null;
      if (test) paths.push(...test.paths);
      live.trs.push({ g, from: tr.t.from.map(key), test, cls: null });
    }

    function update(values) {
      const active = new Set();
      for (const st of live.steps) {
        const on = values.get(st.px) === 'TRUE';
        if (on) active.add(st.name);
        if (on !== st.on) { st.g.classList.toggle('active', on); st.on = on; }
        const t = on ? (values.get(st.pt) || '') : '';
        if (t !== st.t) { st.time.textContent = t; st.t = t; }
      }
      for (const tr of live.trs) {
        const enabled = tr.from.length > 0 && tr.from.every((f) => active.has(f));
        const cls = enabled ? (tr.test && tr.test.value(values) === true ? 'firable' : 'enabled') : '';
        if (cls !== tr.cls) {
          tr.g.classList.remove('enabled', 'firable');
          if (cls) tr.g.classList.add(cls);
          tr.cls = cls;
        }
      }
    }
    // Macro-step bodies, each drawn as a chart of its own below.
    const bodies = c.steps.filter((st) => st.body && st.body.chart).map((st) => draw({
      pou: `${chart.pou}: macro-step ${st.name}${st.body.exit ? ' (exit ' + st.body.exit + ')' : ''}`,
      chart: st.body.chart,
    }, inst));
    if (bodies.length) {
      const wrap = document.createElement('div');
      wrap.append(svg, ...bodies.map((b) => b.svg));
      return {
        svg: wrap,
        paths: paths.concat(...bodies.map((b) => b.paths)),
        update(values) { update(values); for (const b of bodies) b.update(values); },
      };
    }
    return { svg, paths, update };
  }

  window.SfcChart = { draw, layout, compile };
})();
