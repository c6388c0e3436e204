// LD rungs and FBD networks drawn live: the drawing is the one `automat
// draw` makes (`GET /api/v1/drawings` gives it as SVG with the box of every
// element), and this file lays the live state over it: a contact or coil
// whose power flow (the hidden BOOL `__ld_n<localId>`) is TRUE gets a green
// frame, a FALSE one a grey frame; a variable element shows its value
// under it, a block instance the value of each pin beside the pin (an
// input's inside the block, after the pin's name, so that it never runs
// over the variable box wired to it on the left).
'use strict';

(function () {
  const NS = 'http://www.w3.org/2000/svg';

  function s(tag, attrs) {
    const e = document.createElementNS(NS, tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (v === undefined || v === null) continue;
      if (k === 'text') e.textContent = v; else e.setAttribute(k, String(v));
    }
    return e;
  }

  /** The full path of an answer's path for instance `inst` (`.x` is
   * relative to the instance, anything else a global). */
  const full = (inst, p) => (p.startsWith('.') ? inst + p : p);

  // The drawing's estimate of a character's width (`text_w` in
  // crates/cli/src/draw) and of the value font's (11px monospace).
  const NAME_CH = 6;
  const VALUE_CH = 6.7;

  /** Where the value of input `pin` of block `e` goes: after the pin's
   * name inside the block, with the room left before the name of the output
   * on the same row (or the block's edge), in characters. */
  function inputLabel(e, pin) {
    const x = pin.x + 4 + NAME_CH * (pin.name.length + 1);
    const out = (e.pins || []).find((o) => o.output && Math.abs(o.y - pin.y) < 1);
    const end = e.x + e.w - 4 - (out ? NAME_CH * out.name.length + 4 : 0);
    return { x, y: pin.y + 4, chars: Math.max(1, Math.floor((end - x) / VALUE_CH)) };
  }

  /** `v` cut to `n` characters (the last one an ellipsis when cut). */
  const fit = (v, n) => (v.length <= n ? v : v.slice(0, Math.max(0, n - 1)) + '\u2026');

  /** Parses the server's SVG (never as HTML: nothing in it runs). */
  function svgOf(text) {
    const doc = new DOMParser().parseFromString(text, 'image/svg+xml');
    const root = doc.documentElement;
    if (!root || root.nodeName !== 'svg') return s('svg', { width: 10, height: 10 });
    for (const bad of root.querySelectorAll('script, foreignObject')) bad.remove();
    return document.importNode(root, true);
  }

  /** Draws drawing `d` for instance `inst`: { svg, paths, update(values) }. */
  function draw(d, inst) {
    const svg = svgOf(d.svg);
    svg.classList.add('ld');
    const layer = s('g', { class: 'live' });
    svg.append(layer);
    const paths = [];
    const marks = [];
    // SLC-500 bits read 1/0, as RSLogix shows them.
    const shown = (v) => (d.dialect === 'slc' && (v === 'TRUE' || v === 'FALSE') ? (v === 'TRUE' ? '1' : '0') : String(v));
    for (const e of d.elements) {
      if (e.power) {
        const p = full(inst, e.power);
        paths.push(p);
        const r = s('rect', { class: 'power', x: e.x - 3, y: e.y - 3, width: e.w + 6, height: e.h + 6, rx: 3, 'data-id': e.id });
        layer.append(r);
        marks.push((values) => {
          const v = values.get(p);
          r.classList.toggle('on', v === 'TRUE');
          r.classList.toggle('off', v === 'FALSE');
        });
      }
      if (e.value) {
        const p = full(inst, e.value);
        paths.push(p);
        const t = s('text', { class: 'value', x: e.x + e.w / 2, y: e.y + e.h + 12, 'text-anchor': 'middle', 'data-id': e.id });
        layer.append(t);
        marks.push((values) => {
          const v = values.get(p);
          t.textContent = v === undefined ? '' : shown(v);
          // An SLC bit reads as 1/0 from the API, an IEC BOOL as TRUE/FALSE.
          t.classList.toggle('on', v === 'TRUE' || (d.dialect === 'slc' && v === '1'));
        });
      }
      for (const pin of e.pins || []) {
        const p = full(inst, pin.path);
        paths.push(p);
        // An output's value above its wire, right of the block; an input's
        // inside the block (its wire's left end is a variable box).
        const at = pin.output ? { x: pin.x + 6, y: pin.y - 4, chars: Infinity } : inputLabel(e, pin);
        const t = s('text', {
          class: 'value pin', x: at.x, y: at.y,
          'text-anchor': 'start', 'data-id': e.id, 'data-pin': pin.name,
        });
        const tip = s('title');
        t.append(tip);
        layer.append(t);
        marks.push((values) => {
          const v = values.get(p);
          const text = v === undefined ? '' : shown(v);
          // The whole value stays readable as the label's tooltip.
          t.textContent = fit(text, at.chars);
          tip.textContent = text;
          t.append(tip);
          t.classList.toggle('on', v === 'TRUE');
        });
      }
    }
    return { svg, paths, update(values) { for (const m of marks) m(values); } };
  }

  window.LdDrawing = { draw };
})();
