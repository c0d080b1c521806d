// bumpsim view: the page draws (uPlot) and asks; every number it shows
// comes from the bumpsim-view server (or, in a standalone page, from the
// data the page embeds). No signal processing happens here.
(() => {
  'use strict';
  const $ = (id) => document.getElementById(id);
  const embedded = $('bumpsim-data');
  const STATIC = !!embedded;
  const DATA = STATIC ? JSON.parse(embedded.textContent) : null;
  const COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#7f7f7f', '#bcbd22'];
  const state = { inputs: null, selected: [], window: null, ta: null, tb: null, plots: [], signals: [], busy: 0, seq: 0 };
  const hook = { ready: false, readyAt: null, state, errors: [] };
  window.bumpsim = hook;

  const el = (tag, attrs, ...kids) => {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'class') e.className = v; else if (k.startsWith('on')) e.addEventListener(k.slice(2), v); else e.setAttribute(k, v);
    }
    for (const k of kids) e.append(k instanceof Node ? k : document.createTextNode(k == null ? '' : String(k)));
    return e;
  };
  const status = (text, error) => { $('status').textContent = text; $('status').className = error ? 'error' : ''; if (error) hook.errors.push(text); };

  // ---- the request: selection, processing, window, cursors ----
  function processing() {
    const f = $('processing').elements;
    const p = new URLSearchParams();
    if (f.cfc.value) p.append('cfc', f.cfc.value);
    if (f.iso.checked) p.append('iso', '1');
    if (f.bias.checked) p.append('bias', '1');
    if (f.scale.value.trim()) p.append('scale', f.scale.value.trim());
    for (let k = 0; k < +f.integrations.value; k++) p.append('integrate', k === 0 ? (f.initial.value.trim() || '0') : '0');
    if (f.derivative.checked) p.append('derivative', '1');
    if (f.combine.value !== 'none') p.append('combine', f.combine.value);
    for (const u of f.units.value.split(',').map((s) => s.trim()).filter(Boolean)) p.append('unit', u);
    return p;
  }
  function query(extra) {
    const p = processing();
    for (const key of state.selected) p.append('sel', key);
    for (const [k, v] of Object.entries(extra || {})) if (v != null) p.append(k, v);
    return p.toString();
  }
  async function api(name, extra) {
    if (STATIC) return staticApi(name);
    const r = await fetch(`api/${name}?${query(extra)}`);
    const body = await r.json().catch(() => ({ error: `answer ${r.status}` }));
    if (!r.ok) throw new Error(body.error || `answer ${r.status}`);
    return body;
  }
  // a standalone page answers from the raw samples it embeds
  function staticApi(name) {
    if (name === 'inputs') return DATA.inputs;
    if (name === 'series') {
      const signals = state.selected.filter((k) => DATA.raw[k]).map((k) => {
        const s = DATA.raw[k];
        return { ...s, drawn: { time: s.value.map((_, i) => s.start + i * s.step), value: s.value, raw: true } };
      });
      return { signals };
    }
    throw new Error('this needs the server: run bumpsim view with the test');
  }

  // ---- the channel list ----
  function glob(pattern) {
    const re = pattern.replace(/[.+^${}()|[\]\\]/g, '\\$&').replace(/\*/g, '.*').replace(/\?/g, '.');
    return new RegExp(`^${re}$`, 'i');
  }
  function channelRow(t, c) {
    const key = `${t}:${c.i}`;
    const box = el('input', { type: 'checkbox', 'data-key': key, id: `ch-${t}-${c.i}` });
    if (!c.present) box.disabled = true;
    box.checked = state.selected.includes(key);
    box.addEventListener('change', () => toggle(key, box.checked));
    const mark = !c.present ? 'absent' : c.invalid != null ? 'invalid' : '';
    const code = el('td', { class: 'code', title: c.invalid || c.absence || '' }, c.code);
    const row = el('tr', { class: mark, 'data-code': c.code, 'data-name': c.name },
      el('td', {}, box), el('td', {}, c.number), code, el('td', {}, c.name), el('td', {}, c.unit), el('td', { class: 'mark' }, mark));
    row.addEventListener('mouseenter', () => showDecoded(c));
    return row;
  }
  function showDecoded(c) {
    const box = $('decoded');
    box.replaceChildren(el('b', {}, `${c.code} · ${c.name}`));
    if (c.decoded) {
      const rows = c.decoded.fields.map(([field, letters, meaning]) => el('tr', {}, el('td', {}, field), el('td', {}, letters), el('td', {}, meaning)));
      box.append(el('div', {}, c.decoded.standard), el('table', {}, ...rows));
    }
    if (c.invalid != null) box.append(el('div', { class: 'error' }, `marked invalid: ${c.invalid}`));
    if (!c.present) box.append(el('div', { class: 'error' }, c.absence || 'no samples in the files'));
  }
  function renderInputs() {
    const holder = $('tests');
    holder.replaceChildren();
    state.inputs.tests.forEach((test, t) => {
      const speed = test.speed_kmh != null ? ` · ${test.speed_kmh.toPrecision(4)} km/h` : '';
      const mass = test.mass_kg != null ? ` · ${test.mass_kg} kg` : '';
      const body = el('tbody');
      const search = el('input', { class: 'search', placeholder: 'code wildcard (0-LC-*-XG) or name', 'data-test': t });
      const draw = () => {
        const text = search.value.trim();
        const match = text.includes('*') || text.includes('?') ? ((c) => glob(text).test(c.code)) : ((c) => !text || `${c.code} ${c.name}`.toLowerCase().includes(text.toLowerCase()));
        body.replaceChildren(...test.channels.filter(match).map((c) => channelRow(t, c)));
      };
      search.addEventListener('input', draw);
      draw();
      const present = test.channels.filter((c) => c.present).length;
      const head = el('tr', {}, ...['', 'no.', 'code', 'name', 'unit', ''].map((h) => el('th', {}, h)));
      holder.append(el('details', { class: 'test', open: '' },
        el('summary', {}, `T${t + 1}: ${test.title || test.path} (${test.format}${speed}${mass}; ${present} of ${test.channels.length} channels with samples)`),
        el('div', {}, test.path), search, el('table', { class: 'channels' }, el('thead', {}, head), body)));
    });
  }
  function renderResults() {
    const holder = $('results');
    for (const r of state.inputs.results) {
      const rows = r.cases.map((c) => el('tr', {}, el('td', {}, c.name), el('td', { class: 'fit' }, c.fit), el('td', { class: 'rating' }, c.rating)));
      const fields = r.fields.map(([k, v]) => el('tr', {}, el('td', {}, k), el('td', {}, v)));
      holder.append(el('h2', {}, `${r.kind}: ${r.path}`), ...r.model.map((m) => el('div', { class: 'model' }, m)));
      // a test with histories: its name links to its top view and curves below
      const drawn = new Set(r.tests.map((t) => t.name));
      const cell = (v, i) => el('td', {}, i === 0 && drawn.has(v) ? el('a', { href: `#test-${v}` }, v) : v);
      if (r.criteria.length) holder.append(el('table', { class: 'criteria' }, el('tr', {}, ...['test', 'criterion', 'value (SI)', 'limit (SI)', 'margin', 'outcome'].map((h) => el('th', {}, h))), ...r.criteria.map((row) => el('tr', {}, ...row.map(cell)))));
      for (const t of r.tests) holder.append(el('h3', { id: `test-${t.name}` }, `${t.name}: the impact as the verdict ran it`), topView(t.planar, t.name));
      if (rows.length) holder.append(el('table', { class: 'cases' }, el('tr', {}, el('th', {}, 'case'), el('th', {}, 'fit'), el('th', {}, 'ISO/TS 18571')), ...rows));
      else holder.append(el('table', { class: 'fields' }, ...fields));
      if (r.note) holder.append(el('p', { class: 'note' }, r.note));
      for (const c of r.curves) holder.append(curvePlot(c));
      if (r.planar) holder.append(topView(r.planar));
    }
  }
  // a planar result: the top view at the time of the slider (or the cursor), its curves beside
  function topView(p, key = 'planar') {
    const n = p.time.length;
    const canvas = el('canvas', { width: 520, height: 360, class: 'topview' });
    const slider = el('input', { type: 'range', min: 0, max: n - 1, value: 0, class: 'topview-time' });
    const label = el('span', {});
    // from the car's body when the result carries it (bumper line, CG, axles, track), else schematic
    const b = p.body;
    const ahead = b ? b.cg_behind_bumper : 0; // bumper line ahead of the CG, mm
    const L = b ? b.cg_behind_bumper + b.wheelbase - b.cg_behind_front_axle : 2.6 * p.width;
    const W = b ? Math.max(p.width, b.track) : p.width;
    const note = b ? `outline from the car's bumper line, CG (dot), axles and track (wheels at their centres); the car file has no overall length or width, so it ends at the rear axle`
      : `outline schematic: the result holds the bumper's width, not the body's length`;
    const reach = Math.max(...p.x.map(Math.abs));
    const side = Math.max(...p.y.map(Math.abs));
    const scale = Math.min(canvas.width * 0.7 / (L + reach), canvas.height * 0.8 / (W + 2 * side));
    const draw = (k) => {
      const ctx = canvas.getContext('2d');
      const s = scale;
      ctx.clearRect(0, 0, canvas.width, canvas.height);
      ctx.save();
      // x forward to the right (the striker's line at the first contact), y to the left = up
      ctx.translate(canvas.width * 0.75, canvas.height / 2);
      ctx.strokeStyle = '#888'; ctx.beginPath(); ctx.moveTo(0, -canvas.height / 2); ctx.lineTo(0, canvas.height / 2); ctx.stroke();
      // about the CG: it starts `ahead` behind the bumper line
      ctx.translate((p.x[k] - ahead) * s, -p.y[k] * s); ctx.rotate(-p.yaw[k] * Math.PI / 180); ctx.translate(ahead * s, 0);
      ctx.fillStyle = 'rgba(29,53,87,0.15)'; ctx.strokeStyle = '#1d3557';
      ctx.fillRect(-L * s, -W / 2 * s, L * s, W * s); ctx.strokeRect(-L * s, -W / 2 * s, L * s, W * s);
      if (b) {
        ctx.fillStyle = '#1d3557';
        const axles = [b.cg_behind_bumper - b.cg_behind_front_axle, b.cg_behind_bumper + b.wheelbase - b.cg_behind_front_axle];
        for (const a of axles) for (const y of [-b.track / 2, b.track / 2]) ctx.fillRect(-a * s - 6, y * s - 2, 12, 4);
        ctx.beginPath(); ctx.arc(-ahead * s, 0, 4, 0, 2 * Math.PI); ctx.fill();
      }
      ctx.strokeStyle = '#d62728'; ctx.lineWidth = 3; ctx.beginPath(); ctx.moveTo(0, -p.width / 2 * s); ctx.lineTo(0, p.width / 2 * s); ctx.stroke();
      ctx.restore();
      label.textContent = `t = ${fmtTime(p.time[k])} ms · x = ${p.x[k].toFixed(1)} mm · y = ${p.y[k].toFixed(1)} mm · yaw = ${p.yaw[k].toFixed(2)}° · force = ${p.force[k].toFixed(2)} kN (${note})`;
      slider.value = k;
    };
    slider.addEventListener('input', () => draw(+slider.value));
    let timer = null;
    const play = el('button', { type: 'button' }, 'play');
    play.addEventListener('click', () => {
      if (timer) { clearInterval(timer); timer = null; return; }
      let k = 0; const stride = Math.max(1, Math.round(n / 200));
      timer = setInterval(() => { draw(k); k += stride; if (k >= n) { clearInterval(timer); timer = null; draw(n - 1); } }, 30);
    });
    const plots = el('div', { class: 'topview-curves' });
    const opts = (label, data, color) => ({
      title: label, width: 560, height: 170, scales: { x: { time: false } },
      series: [{ label: 'time [ms]', value: (u, v) => (v == null ? '' : fmtTime(v)) }, { label, stroke: color, width: 1.25 }],
      axes: [{ values: (u, splits) => splits.map(fmtTime) }, { size: 60 }],
      cursor: { sync: { key } },
      hooks: { setCursor: [(u) => { if (u.cursor.idx != null) draw(u.cursor.idx); }] },
    });
    new uPlot(opts('striker force [kN]', p.force, '#d62728'), [p.time, p.force], plots);
    new uPlot(opts('yaw [deg]', p.yaw, '#1f77b4'), [p.time, p.yaw], plots);
    draw(0);
    return el('div', { class: 'planar' }, el('div', {}, canvas, el('div', {}, play, slider), label), plots);
  }
  // an identification's case: measured and model displacement, the fitted window marked
  function curvePlot(c) {
    const holder = el('div', { class: 'plot case', 'data-case': c.name });
    const marks = (u) => {
      const ctx = u.ctx;
      ctx.save(); ctx.fillStyle = 'rgba(69,123,157,0.10)';
      const x0 = u.valToPos(c.window[0], 'x', true); const x1 = u.valToPos(c.window[1], 'x', true);
      ctx.fillRect(x0, u.bbox.top, x1 - x0, u.bbox.height); ctx.restore();
    };
    const opts = {
      title: `${c.name}: ${c.fit} · ${c.rating} · shaded: the fitted window`, width: Math.max(300, document.body.clientWidth - 40), height: 240,
      series: [{ label: 'time [ms]', value: (u, v) => (v == null ? '' : fmtTime(v)) }, { label: 'test [mm]', stroke: '#1f77b4', width: 1.25 }, { label: 'model [mm]', stroke: '#d62728', width: 1.25, dash: [6, 3] }],
      scales: { x: { time: false } }, axes: [{ label: 'time [ms]', values: (u, splits) => splits.map(fmtTime) }, { label: 'displacement [mm]', size: 70 }],
      hooks: { drawClear: [marks] },
    };
    new uPlot(opts, [c.time, c.measured, c.model], holder);
    return holder;
  }

  // ---- plots: one per dimension and unit ----
  const fmtTime = (v) => `${+(v * 1e3).toPrecision(6)}`;
  function groups(signals) {
    const out = new Map();
    signals.forEach((s, k) => {
      const key = `${s.dimension} [${s.unit}]`;
      if (!out.has(key)) out.set(key, []);
      out.get(key).push({ s, color: COLORS[k % COLORS.length] });
    });
    return out;
  }
  function plotWidth() { return Math.max(300, $('plots').clientWidth - 10); }
  function makePlot(title, members) {
    const data = uPlot.join(members.map(({ s }) => [s.drawn.time, s.drawn.value]));
    const series = [{ label: 'time [ms]', value: (u, v) => (v == null ? '' : fmtTime(v)) }]
      .concat(members.map(({ s, color }) => ({ label: s.label, stroke: color, width: 1.25, spanGaps: true, points: { show: s.drawn.raw && s.drawn.time.length < 400, size: 4 } })));
    const opts = {
      title, width: plotWidth(), height: 260, series,
      scales: { x: { time: false } },
      axes: [{ label: 'time [ms]', values: (u, splits) => splits.map(fmtTime) }, { label: title, size: 70 }],
      cursor: { sync: { key: 'bumpsim', setSeries: false }, drag: { x: true, y: false, setScale: false } },
      hooks: { setSelect: [onSelect], draw: [drawCursors] },
    };
    const holder = el('div', { class: 'plot' });
    $('plots').append(holder);
    const u = new uPlot(opts, data, holder);
    u.bumpsimSignals = members.map(({ s }) => s);
    attachMouse(u);
    return u;
  }
  function drawCursors(u) {
    const ctx = u.ctx;
    for (const [t, color] of [[state.ta, '#e63946'], [state.tb, '#457b9d']]) {
      if (t == null) continue;
      const x = Math.round(u.valToPos(t, 'x', true));
      if (x < u.bbox.left || x > u.bbox.left + u.bbox.width) continue;
      ctx.save(); ctx.strokeStyle = color; ctx.lineWidth = 1.5 * devicePixelRatio;
      ctx.beginPath(); ctx.moveTo(x, u.bbox.top); ctx.lineTo(x, u.bbox.top + u.bbox.height); ctx.stroke(); ctx.restore();
    }
  }
  // a drag selects a window: the server sends its samples (raw when few)
  function onSelect(u) {
    const sel = u.select;
    if (sel.width < 3) return;
    const t0 = u.posToVal(sel.left, 'x');
    const t1 = u.posToVal(sel.left + sel.width, 'x');
    u.setSelect({ left: 0, top: 0, width: 0, height: 0 }, false);
    zoom(t0, t1);
  }
  function attachMouse(u) {
    let down = null;
    u.over.addEventListener('mousedown', (e) => { down = [e.clientX, e.clientY]; });
    u.over.addEventListener('click', (e) => {
      if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 3) return;
      const t = u.posToVal(e.offsetX, 'x');
      if (e.shiftKey) setCursors(state.ta, t); else setCursors(t, state.tb);
    });
    u.over.addEventListener('wheel', (e) => {
      e.preventDefault();
      const { min, max } = u.scales.x;
      const at = u.posToVal(e.offsetX, 'x');
      const f = e.deltaY > 0 ? 1.25 : 0.8;
      zoom(at - (at - min) * f, at + (max - at) * f);
    }, { passive: false });
  }
  function zoom(t0, t1) {
    state.window = [t0, t1];
    return refresh(false);
  }

  // ---- refresh: ask the server, draw ----
  async function refresh(rebuild) {
    if (!state.selected.length) {
      state.plots.forEach((u) => u.destroy()); state.plots = []; state.signals = [];
      $('readout').replaceChildren(); $('command').textContent = '';
      return;
    }
    const seq = ++state.seq;
    state.busy++;
    try {
      const extra = state.window ? { t0: state.window[0], t1: state.window[1], px: plotWidth() } : { px: plotWidth() };
      const answer = await api('series', extra);
      if (seq !== state.seq) return; // a later request overtook this one
      state.signals = answer.signals;
      const grouped = groups(answer.signals);
      const same = !rebuild && state.plots.length === grouped.size && [...grouped.values()].every((m, k) => state.plots[k].bumpsimSignals.length === m.length);
      if (same) {
        [...grouped.values()].forEach((members, k) => {
          const u = state.plots[k];
          u.setData(uPlot.join(members.map(({ s }) => [s.drawn.time, s.drawn.value])), !state.window);
          if (state.window) u.setScale('x', { min: state.window[0], max: state.window[1] });
          u.bumpsimSignals = members.map(({ s }) => s);
        });
      } else {
        state.plots.forEach((u) => u.destroy());
        $('plots').replaceChildren();
        state.plots = [...grouped.entries()].map(([title, members]) => makePlot(title, members));
        if (state.window) state.plots.forEach((u) => u.setScale('x', { min: state.window[0], max: state.window[1] }));
      }
      const raw = answer.signals.every((s) => s.drawn.raw);
      status(raw ? 'raw samples' : 'min/max per pixel');
      $('plots').dataset.raw = raw ? '1' : '0';
      await Promise.all([readouts(), commandLine()]);
    } catch (e) {
      status(e.message, true);
    } finally {
      state.busy--;
    }
  }
  async function readouts() {
    const table = $('readout');
    if (state.ta == null && state.tb == null) { table.replaceChildren(); return; }
    let rows;
    if (STATIC) rows = staticReadouts(); else rows = (await api('cursor', { ta: state.ta, tb: state.tb })).readouts;
    const cell = (v, scale) => el('td', { 'data-value': v == null ? '' : String(v) }, v == null ? '' : (+(v * (scale || 1)).toPrecision(7)).toString());
    table.replaceChildren(el('tr', {}, ...['signal', 'A time [ms]', 'A value', 'B time [ms]', 'B value', 'B−A time [ms]', 'B−A value', 'unit'].map((h) => el('th', {}, h))),
      ...rows.map((r) => el('tr', { 'data-label': r.label }, el('td', {}, r.label),
        cell(r.a && r.a.time, 1e3), cell(r.a && r.a.value), cell(r.b && r.b.time, 1e3), cell(r.b && r.b.value),
        cell(r.difference && r.difference[0], 1e3), cell(r.difference && r.difference[1]), el('td', {}, r.unit))));
  }
  function staticReadouts() {
    const at = (s, t) => {
      if (t == null) return null;
      const k = Math.min(s.value.length - 1, Math.max(0, Math.round((t - s.start) / s.step)));
      return { time: s.start + k * s.step, value: s.value[k], index: k };
    };
    return state.selected.filter((k) => DATA.raw[k]).map((k) => {
      const s = DATA.raw[k];
      const a = at(s, state.ta); const b = at(s, state.tb);
      return { label: s.label, unit: s.unit, a, b, difference: a && b ? [b.time - a.time, b.value - a.value] : null };
    });
  }
  async function commandLine() {
    if (STATIC) { $('command').textContent = 'standalone page: processing, exports and metrics need the server (bumpsim view PATH...)'; return; }
    const c = await api('command');
    $('command').textContent = c.lines.concat(c.notes.map((n) => `# ${n}`)).join('\n');
  }
  async function setCursors(ta, tb) {
    state.ta = ta; state.tb = tb;
    state.plots.forEach((u) => u.redraw(false));
    try { await readouts(); } catch (e) { status(e.message, true); }
  }
  function toggle(key, on) {
    state.selected = state.selected.filter((k) => k !== key);
    if (on) state.selected.push(key);
    return refresh(true);
  }

  // ---- exports ----
  function download(name, href) { const a = el('a', { href, download: name }); document.body.append(a); a.click(); a.remove(); }
  function viewSvg() {
    const parts = [];
    let y = 0;
    const W = plotWidth();
    for (const u of state.plots) {
      const b = u.bbox; const d = devicePixelRatio; const h = u.height;
      parts.push(`<g transform="translate(0,${y})"><text x="${W / 2}" y="14" text-anchor="middle" font-size="13">${escapeXml(u.root.querySelector('.u-title').textContent)}</text>`);
      parts.push(`<rect x="${b.left / d}" y="${b.top / d}" width="${b.width / d}" height="${b.height / d}" fill="none" stroke="#888"/>`);
      u.series.forEach((s, k) => {
        if (k === 0 || !s.show) return;
        const pts = [];
        for (let i = 0; i < u.data[0].length; i++) {
          const v = u.data[k][i];
          if (v == null || u.data[0][i] < u.scales.x.min || u.data[0][i] > u.scales.x.max) continue;
          pts.push(`${(u.valToPos(u.data[0][i], 'x', true) / d).toFixed(2)},${(u.valToPos(v, 'y', true) / d).toFixed(2)}`);
        }
        parts.push(`<polyline fill="none" stroke="${s.stroke()}" stroke-width="1.2" points="${pts.join(' ')}"/>`);
        parts.push(`<text x="${b.left / d + 6}" y="${b.top / d + 14 * k}" font-size="11" fill="${s.stroke()}">${escapeXml(s.label)}</text>`);
      });
      for (const [t, c] of [[state.ta, '#e63946'], [state.tb, '#457b9d']]) if (t != null) { const x = u.valToPos(t, 'x', true) / d; parts.push(`<line x1="${x}" x2="${x}" y1="${b.top / d}" y2="${(b.top + b.height) / d}" stroke="${c}"/>`); }
      parts.push(`<text x="${b.left / d}" y="${(b.top + b.height) / d + 14}" font-size="11">${fmtTime(u.scales.x.min)} ms</text><text x="${(b.left + b.width) / d}" y="${(b.top + b.height) / d + 14}" font-size="11" text-anchor="end">${fmtTime(u.scales.x.max)} ms</text>`);
      parts.push(`<text x="${b.left / d - 4}" y="${b.top / d + 10}" font-size="11" text-anchor="end">${+u.scales.y.max.toPrecision(4)}</text><text x="${b.left / d - 4}" y="${(b.top + b.height) / d}" font-size="11" text-anchor="end">${+u.scales.y.min.toPrecision(4)}</text></g>`);
      y += h;
    }
    return `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${y}" font-family="sans-serif">${parts.join('')}</svg>`;
  }
  function escapeXml(s) { return String(s).replace(/[<>&"]/g, (c) => ({ '<': '&lt;', '>': '&gt;', '&': '&amp;', '"': '&quot;' }[c])); }
  function viewPng() {
    const W = plotWidth() * devicePixelRatio;
    const H = state.plots.reduce((h, u) => h + u.ctx.canvas.height, 0);
    const canvas = el('canvas', { width: W, height: Math.max(1, H) });
    const ctx = canvas.getContext('2d');
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, W, H);
    let y = 0;
    for (const u of state.plots) { ctx.drawImage(u.ctx.canvas, 0, y); y += u.ctx.canvas.height; }
    return canvas.toDataURL('image/png');
  }
  hook.svg = viewSvg;
  $('svg').addEventListener('click', () => download('view.svg', URL.createObjectURL(new Blob([viewSvg()], { type: 'image/svg+xml' }))));
  $('png').addEventListener('click', () => download('view.png', viewPng()));
  $('csv').addEventListener('click', () => { if (!STATIC) download('view.csv', `api/export.csv?${query()}`); });
  $('iso').addEventListener('click', async () => {
    if (STATIC) return status('ISO-MME export needs the server', true);
    const r = await fetch(`api/export-iso?${query({ name: $('isoname').value.trim() })}`, { method: 'POST' });
    const body = await r.json().catch(() => ({}));
    status(r.ok ? `wrote ${body.wrote} (${body.channels} channels)` : body.error || `answer ${r.status}`, !r.ok);
  });
  $('metrics-button').addEventListener('click', showMetrics);
  async function showMetrics() {
    try {
      const m = (await api('metrics', state.window ? { t0: state.window[0], t1: state.window[1] } : {})).metrics;
      const f = (v, d) => (v == null ? '—' : v.toFixed(d));
      $('metrics').replaceChildren(el('table', {}, el('tr', {}, ...['signal', 'peak [g]', '3 ms clip [g]', 'ΔV [km/h]', 'OLC [g]', 'ASI [1]', 'notes'].map((h) => el('th', {}, h))),
        ...m.map((r) => el('tr', {}, el('td', {}, r.label), el('td', {}, f(r.peak_g, 2)), el('td', {}, f(r.clip_g, 2)), el('td', {}, f(r.delta_v_kmh, 2)), el('td', {}, f(r.olc_g, 2)), el('td', {}, f(r.asi, 3)), el('td', {}, r.notes.join('; '))))));
      return m;
    } catch (e) { status(e.message, true); return []; }
  }
  $('autoscale').addEventListener('click', () => { state.window = null; refresh(true); });
  const pan = (share) => { const w = state.window || (state.plots[0] && [state.plots[0].scales.x.min, state.plots[0].scales.x.max]); if (w) zoom(w[0] + share * (w[1] - w[0]), w[1] + share * (w[1] - w[0])); };
  $('left').addEventListener('click', () => pan(-0.5));
  $('right').addEventListener('click', () => pan(0.5));
  $('processing').addEventListener('change', () => refresh(true));
  if (STATIC) for (const e of $('processing').elements) e.disabled = true;

  // ---- the hooks the tests (and a curious user's console) drive ----
  hook.select = (keys) => { state.selected = keys.slice(); renderInputs(); return refresh(true); };
  hook.zoom = zoom;
  hook.cursors = async (ta, tb) => { await setCursors(ta, tb); return [...$('readout').querySelectorAll('tr[data-label]')].map((r) => ({ label: r.dataset.label, a: r.children[2].dataset.value, b: r.children[4].dataset.value, dv: r.children[6].dataset.value })); };
  hook.form = (values) => { const f = $('processing').elements; for (const [k, v] of Object.entries(values)) { if (f[k].type === 'checkbox') f[k].checked = !!v; else f[k].value = v; } return refresh(true); };
  hook.metrics = showMetrics;
  hook.drawn = () => state.signals.map((s) => ({ label: s.label, unit: s.unit, raw: s.drawn.raw, time: s.drawn.time, value: s.drawn.value }));

  (async () => {
    $('mode').textContent = STATIC ? 'standalone page (data embedded; no server)' : 'served on 127.0.0.1 (read-only)';
    try {
      state.inputs = await api('inputs');
      const first = state.inputs.tests.map((t, k) => { const c = t.channels.find((c) => c.present && c.invalid == null); return c ? `${k}:${c.i}` : null; }).filter(Boolean);
      state.selected = first.slice(0, 1);
      renderInputs();
      renderResults();
      if (!state.inputs.tests.length) document.querySelector('main').style.display = 'none';
      await refresh(true);
    } catch (e) { status(e.message, true); }
    hook.ready = true;
    hook.readyAt = performance.now();
  })();
})();
