// Animated plant pictures, chosen by the mimic the plant model declares
// (`GET /api/v1/plant` → "mimic"). Each is drawn once and then only moved
// and recoloured from the plant's quantities and signals; moves are CSS
// transitions over the 100 ms between two plant reads, so the motion is
// smooth without redrawing. A model with no (or an unknown) mimic gets
// the signal panel alone.
'use strict';

(function () {
  const NS = 'http://www.w3.org/2000/svg';
  function s(tag, attrs, ...children) {
    const e = document.createElementNS(NS, tag);
    for (const [k, v] of Object.entries(attrs || {})) if (v !== undefined && v !== null) {
      if (k === 'text') e.textContent = v; else e.setAttribute(k, String(v));
    }
    for (const c of children) if (c) e.append(c);
    return e;
  }
  const lookup = (d) => {
    const q = new Map(d.quantities.map((x) => [x.name, x.value]));
    const g = new Map(d.signals.map((x) => [x.name, x.value]));
    return { q: (n) => q.get(n) ?? 0, b: (n) => g.get(n) === true, v: (n) => g.get(n) };
  };
  const fixed = (v, n) => Number(v).toFixed(n);
  const toggle = (e, cls, on) => { if (e.classList.contains(cls) !== on) e.classList.toggle(cls, on); };
  const text = (e, t) => { if (e.textContent !== t) e.textContent = t; };
  const move = (e, x, y) => { const t = `translate(${fixed(x, 1)}px, ${fixed(y, 1)}px)`; if (e.style.transform !== t) e.style.transform = t; };

  // The crane: 10 m by 5 m, hook at (x, y), four limit switches, two motors.
  function crane() {
    const X = (m) => 110 + m * 42, Y = (m) => 300 - m * 46;
    const svg = s('svg', { viewBox: '0 0 560 360', role: 'img', 'aria-label': 'Crane mimic' });
    svg.append(s('defs', {}, s('clipPath', { id: 'crane-clip' }, s('rect', { x: 0, y: 44, width: 560, height: 300 }))));
    svg.append(s('rect', { class: 'frame', x: X(0), y: Y(5), width: X(10) - X(0), height: Y(0) - Y(5) }));
    svg.append(s('line', { class: 'rail', x1: X(0) - 10, y1: 40, x2: X(10) + 10, y2: 40 }));
    svg.append(s('line', { class: 'track', x1: X(0) - 20, y1: Y(0) + 14, x2: X(10) + 20, y2: Y(0) + 14 }));
    const hook = s('g', { class: 'move' }, s('line', { class: 'cable', x1: 0, y1: -10, x2: 0, y2: -400 }), s('rect', { class: 'hook', x: -13, y: -10, width: 26, height: 18, rx: 3 }));
    svg.append(s('g', { 'clip-path': 'url(#crane-clip)' }, hook));
    const trolley = s('g', { class: 'move' }, s('rect', { class: 'trolley', x: -22, y: 32, width: 44, height: 16, rx: 3 }));
    svg.append(trolley);
    const sw = {};
    const mk = (name, x, y, label, dx) => {
      sw[name] = s('circle', { class: 'switch', cx: x, cy: y, r: 7 });
      svg.append(sw[name], s('text', { x: x + dx, y: y + 4, 'text-anchor': dx < 0 ? 'end' : 'start', text: label }));
    };
    mk('l3', X(0) - 14, 24, 'l3 left', 10);
    mk('l4', X(10) + 14, 24, 'l4 right', -10);
    mk('l2', X(0) - 14, Y(5) + 20, 'l2 top', -10);
    mk('l1', X(0) - 14, Y(0) - 6, 'l1 bottom', -10);
    const motors = {};
    [['M1S', '← M1S', 40], ['M1D', 'M1D →', 120], ['M2S', '↑ M2S', 200], ['M2J', '↓ M2J', 280]].forEach(([n, label, x]) => {
      const r = s('rect', { class: 'motor', x, y: 326, width: 70, height: 24, rx: 5 });
      motors[n] = r;
      svg.append(r, s('text', { x: x + 35, y: 342, 'text-anchor': 'middle', text: label }));
    });
    const pos = s('text', { class: 'big', x: 370, y: 344 });
    const cyc = s('text', { x: X(10), y: Y(5) + 18, 'text-anchor': 'end' });
    svg.append(pos, cyc);
    return {
      svg,
      update(d) {
        const L = lookup(d);
        move(trolley, X(L.q('x')), 0);
        move(hook, X(L.q('x')), Y(L.q('y')));
        for (const n of ['l1', 'l2', 'l3', 'l4']) toggle(sw[n], 'on', L.b(n));
        for (const n of Object.keys(motors)) toggle(motors[n], 'on', L.b(n));
        text(pos, `x ${fixed(L.q('x'), 2)} m  y ${fixed(L.q('y'), 2)} m`);
        text(cyc, `cycles ${L.q('cycles')}  conflicts ${L.q('conflicts')} ms  end stops ${L.q('end_stops')}`);
      },
    };
  }

  // The tank-temperature loop: tank 1 (60 L) heated and cooled, valve 1
  // filling it, valve 2 with the pump transferring to tank 2 (10 L) and
  // its two level switches. The valves are TRUE = closed, as in the source.
  function tank() {
    const svg = s('svg', { viewBox: '0 0 560 380', role: 'img', 'aria-label': 'Tank temperature mimic' });
    const T1 = { x: 70, y: 90, w: 190, h: 230 }, T2 = { x: 370, y: 170, w: 130, h: 150 };
    const in1 = s('path', { class: 'pipe', d: `M20,50 H${T1.x + 40} V${T1.y}` });
    const xfer = s('path', { class: 'pipe', d: `M${T1.x + T1.w},${T1.y + T1.h - 20} H${T2.x + 30} V${T2.y}` });
    const drain = s('path', { class: 'pipe on', d: `M${T2.x + T2.w / 2},${T2.y + T2.h} V${T2.y + T2.h + 40}` });
    svg.append(in1, xfer, drain);
    const liq1 = s('rect', { class: 'liquid', x: T1.x + 2, width: T1.w - 4, y: T1.y + T1.h, height: 0 });
    const liq2 = s('rect', { class: 'liquid', x: T2.x + 2, width: T2.w - 4, y: T2.y + T2.h, height: 0 });
    svg.append(liq1, liq2, s('rect', { class: 'tank', x: T1.x, y: T1.y, width: T1.w, height: T1.h }), s('rect', { class: 'tank', x: T2.x, y: T2.y, width: T2.w, height: T2.h }));
    let zig = `M${T1.x + 30},${T1.y + T1.h - 18}`;
    for (let i = 0; i < 10; i++) zig += ` l7,${i % 2 ? 10 : -10} l7,${i % 2 ? -10 : 10}`;
    const heater = s('path', { class: 'heater', d: zig });
    const fan = s('circle', { class: 'motor', cx: T1.x - 30, cy: T1.y + 120, r: 18 });
    svg.append(heater, fan, s('text', { x: T1.x - 30, y: T1.y + 156, 'text-anchor': 'middle', text: 'racire' }),
      s('text', { x: T1.x + 30, y: T1.y + T1.h + 18, text: 'rezistenta' }));
    const v1 = s('rect', { class: 'motor', x: T1.x + 28, y: 40, width: 24, height: 20 });
    const v2 = s('rect', { class: 'motor', x: T1.x + T1.w + 20, y: T1.y + T1.h - 30, width: 24, height: 20 });
    const pump = s('circle', { class: 'motor', cx: T1.x + T1.w + 80, cy: T1.y + T1.h - 20, r: 14 });
    svg.append(v1, v2, pump,
      s('text', { x: T1.x + 58, y: 36, text: 'valva_1' }),
      s('text', { x: T1.x + T1.w + 12, y: T1.y + T1.h + 4, text: 'valva_2' }),
      s('text', { x: T1.x + T1.w + 66, y: T1.y + T1.h + 12, text: 'pompa' }));
    const plin = s('circle', { class: 'switch', cx: T2.x + T2.w + 16, cy: T2.y + T2.h * 0.2, r: 7 });
    const gol = s('circle', { class: 'switch', cx: T2.x + T2.w + 16, cy: T2.y + T2.h * 0.8, r: 7 });
    svg.append(plin, gol, s('text', { x: T2.x + T2.w + 28, y: T2.y + T2.h * 0.2 + 4, text: 'plin' }), s('text', { x: T2.x + T2.w + 28, y: T2.y + T2.h * 0.8 + 4, text: 'gol' }));
    const temp = s('text', { class: 'big', x: T1.x + T1.w / 2, y: T1.y + 40, 'text-anchor': 'middle' });
    const l1 = s('text', { x: T1.x + T1.w / 2, y: T1.y + 60, 'text-anchor': 'middle' });
    const l2 = s('text', { x: T2.x + T2.w / 2, y: T2.y + 24, 'text-anchor': 'middle' });
    svg.append(temp, l1, l2, s('text', { x: T1.x, y: T1.y - 8, text: 'tank 1' }), s('text', { x: T2.x, y: T2.y - 8, text: 'tank 2' }));
    const level = (r, T, frac) => {
      const h = Math.max(0, Math.min(1, frac)) * (T.h - 2);
      r.setAttribute('y', fixed(T.y + T.h - 1 - h, 1));
      r.setAttribute('height', fixed(h, 1));
    };
    return {
      svg,
      update(d) {
        const L = lookup(d);
        const t = L.q('temp');
        level(liq1, T1, L.q('level1') / 60);
        level(liq2, T2, L.q('level2') / 10);
        // Blue at 20 °C to red at 70 °C.
        const k = Math.max(0, Math.min(1, (t - 20) / 50));
        liq1.setAttribute('fill', `rgb(${Math.round(90 + 150 * k)},${Math.round(150 - 60 * k)},${Math.round(230 - 170 * k)})`);
        text(temp, `${fixed(t, 1)} °C`);
        text(l1, `${fixed(L.q('level1'), 1)} L`);
        text(l2, `${fixed(L.q('level2'), 2)} L`);
        toggle(heater, 'on', L.b('rezistenta'));
        toggle(fan, 'on', L.b('racire'));
        const open1 = !L.b('valva_1'), open2 = !L.b('valva_2');
        toggle(v1, 'on', open1); toggle(in1, 'on', open1);
        toggle(v2, 'on', open2); toggle(pump, 'on', L.b('pompa'));
        toggle(xfer, 'on', open2 && L.b('pompa'));
        toggle(plin, 'on', L.b('senzor_plin'));
        toggle(gol, 'on', L.b('senzor_gol'));
      },
    };
  }

  // Three trains on 1 m tracks with end sensors and buffer stops 5 cm out.
  function trains() {
    const X = (m) => 110 + m * 390;
    const svg = s('svg', { viewBox: '0 0 660 320', role: 'img', 'aria-label': 'Trains mimic' });
    const rows = [1, 2, 3].map((i) => {
      const y = 20 + i * 80;
      svg.append(s('line', { class: 'track', x1: X(-0.05), y1: y + 12, x2: X(1.05), y2: y + 12 }),
        s('rect', { class: 'buffer', x: X(-0.05) - 6, y: y - 4, width: 6, height: 18 }),
        s('rect', { class: 'buffer', x: X(1.05), y: y - 4, width: 6, height: 18 }),
        s('text', { x: 8, y: y + 6, text: 'track ' + i }));
      const left = s('circle', { class: 'switch', cx: X(0), cy: y - 16, r: 6 });
      const right = s('circle', { class: 'switch', cx: X(1), cy: y - 16, r: 6 });
      const body = s('rect', { class: 'train', x: -22, y: -8, width: 44, height: 18, rx: 4 });
      const arrow = s('text', { x: 0, y: 6, 'text-anchor': 'middle', fill: '#fff', text: '' });
      const train = s('g', { class: 'move' }, body, arrow);
      const info = s('text', { x: X(1.05) + 14, y: y + 6 });
      svg.append(left, right, train, info, s('text', { x: X(0) - 8, y: y - 26, text: 'Left' + i }), s('text', { x: X(1) - 28, y: y - 26, text: 'Right' + i }));
      return { i, y, left, right, train, body, arrow, info };
    });
    const total = s('text', { x: 8, y: 304 });
    svg.append(total);
    return {
      svg,
      update(d) {
        const L = lookup(d);
        for (const r of rows) {
          move(r.train, X(L.q('x' + r.i)), r.y);
          toggle(r.left, 'on', L.b('Left' + r.i));
          toggle(r.right, 'on', L.b('Right' + r.i));
          const v = L.q('v' + r.i);
          text(r.arrow, v > 0 ? '▶' : v < 0 ? '◀' : '■');
          text(r.info, `${L.v('Speed' + r.i)} · ${fixed(v, 2)} m/s`);
        }
        text(total, `trips ${L.q('trips1')} / ${L.q('trips2')} / ${L.q('trips3')}   crashes ${L.q('crashes')}   direction faults ${L.q('dir_faults')}`);
      },
    };
  }

  const KINDS = { crane, 'tank-temperature': tank, trains };
  function make(kind, data) {
    const f = KINDS[kind];
    if (!f) return null;
    const m = f();
    m.update(data);
    return m;
  }
  window.Mimics = { make };
})();
