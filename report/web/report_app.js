// feedplan's HTML report: draws the JSON in #report-data (report/include/feedplan/report/*_page.hpp write
// it) with uPlot. A plan: the summary and notes, the tool path to scale coloured by a chosen quantity with
// a readout of the sample under the pointer, and force, feed and engagement against path length, zoomed
// together (drag to zoom, double-click or "Reset zoom" for the whole path). A learning history adds each
// cycle's peak error and cycle time and its curves overlaid; a comparison shows its table and figures.
//
// Large plans stay responsive: every chart holds only what its width can show — per pixel column the
// samples with the smallest and largest value of each series — recomputed for the visible range on zoom.
// window.feedplanReport is the page's state, read by the browser test (tests/report).
(function () {
  'use strict';

  const data = JSON.parse(document.getElementById('report-data').textContent);
  const root = document.getElementById('report');
  const state = { ready: false, kind: data.kind, charts: {}, view: null, selected: -1 };
  window.feedplanReport = state;

  const CYCLE_COLOURS = ['#9ecae1', '#6baed6', '#4292c6', '#2171b5', '#08519c', '#08306b', '#041f4a', '#000000'];

  function element(tag, attributes, parent, text) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attributes || {})) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }

  function section(id, heading) {
    const s = element('section', { id: id }, root);
    element('h2', {}, s, heading);
    return s;
  }

  function numberText(v) {
    return v === null || v === undefined || Number.isNaN(v) ? '—' : String(v);
  }

  // ----- summary, notes, tables

  function drawSummary() {
    const s = section('summary', 'Summary');
    const table = element('table', { class: 'summary' }, s);
    for (const [label, value] of data.summary || []) {
      const row = element('tr', {}, table);
      element('th', {}, row, label);
      element('td', {}, row, value);
    }
    if ((data.notes || []).length > 0) {
      const n = section('notes', 'Notes');
      const list = element('ul', {}, n);
      for (const note of data.notes) element('li', { class: 'note' }, list, note);
    }
  }

  function drawTable(parent, id, table) {
    const t = element('table', { id: id, class: 'figures' }, parent);
    const head = element('tr', {}, t);
    for (const c of table.columns) element('th', {}, head, c);
    for (const r of table.rows) {
      const row = element('tr', {}, t);
      for (const cell of r) element('td', {}, row, cell);
    }
    return t;
  }

  // ----- decimation: per pixel column, the first, smallest, largest and last sample of every series

  function lowerBound(xs, v) {
    let lo = 0, hi = xs.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (xs[mid] < v) lo = mid + 1; else hi = mid;
    }
    return lo;
  }

  // Indices of xs (ascending) to draw for [lo, hi] on `columns` pixel columns: all of them when few, else the
  // extremes of every series per column; one sample beyond each end so lines reach the edges.
  function decimatedIndices(xs, series, lo, hi, columns) {
    const first = Math.max(0, lowerBound(xs, lo) - 1);
    const last = Math.min(xs.length - 1, lowerBound(xs, hi));
    const out = [];
    if (last - first + 1 <= 4 * columns) {
      for (let i = first; i <= last; i++) out.push(i);
      return out;
    }
    const width = (hi - lo) / columns;
    let i = first;
    while (i <= last) {
      const column = Math.floor((xs[i] - lo) / width);
      let end = i;
      while (end + 1 <= last && Math.floor((xs[end + 1] - lo) / width) === column) end++;
      const picked = [i, end];
      for (const ys of series) {
        let minI = -1, maxI = -1;
        for (let k = i; k <= end; k++) {
          const y = ys[k];
          if (y === null) continue;
          if (minI < 0 || y < ys[minI]) minI = k;
          if (maxI < 0 || y > ys[maxI]) maxI = k;
        }
        if (minI >= 0) picked.push(minI, maxI);
      }
      picked.sort((a, b) => a - b);
      let previous = -1;
      for (const k of picked) {
        if (k !== previous) out.push(k);
        previous = k;
      }
      i = end + 1;
    }
    return out;
  }

  // ----- linked charts against path length

  const linked = [];  // {chart, xs, columns (series arrays), indices}

  function fullRange() {
    const xs = data.samples.s_mm;
    return [xs[0], xs[xs.length - 1]];
  }

  function chartData(entry) {
    const [lo, hi] = state.view || fullRange();
    const width = Math.max(100, Math.round(entry.chart ? entry.chart.bbox.width / devicePixelRatio : 1000));
    entry.indices = decimatedIndices(entry.xs, entry.columns, lo, hi, width);
    const out = [entry.indices.map((i) => entry.xs[i])];
    for (const ys of entry.columns) out.push(entry.indices.map((i) => ys[i]));
    return out;
  }

  function setView(range) {
    state.view = range;
    for (const entry of linked) entry.chart.setData(chartData(entry));
  }
  state.setView = setView;
  state.resetView = () => setView(null);

  function chartWidth() {
    return Math.max(400, Math.min(1400, root.clientWidth - 20));
  }

  // A chart of `columns` (arrays over the samples) against s, zoomed with every other linked chart.
  function linkedChart(parent, id, title, yLabel, seriesOptions, columns, extra) {
    const holder = element('div', { id: id, class: 'chart' }, parent);
    const entry = { xs: data.samples.s_mm, columns: columns, indices: [] };
    const options = Object.assign({
      title: title,
      width: chartWidth(),
      height: 230,
      scales: { x: { time: false, range: (u, min, max) => state.view || [min, max] } },
      axes: [{ label: 'path length s [mm]' }, { label: yLabel, size: 60 }],
      series: [{ label: 's [mm]' }].concat(seriesOptions),
      cursor: {
        sync: { key: 'feedplan-path', setSeries: false },
        drag: { x: true, y: false, setScale: false },
        bind: { dblclick: () => () => { state.resetView(); return null; } },
      },
      hooks: {
        setSelect: [(u) => {
          if (u.select.width >= 5) {
            const lo = u.posToVal(u.select.left, 'x');
            const hi = u.posToVal(u.select.left + u.select.width, 'x');
            u.setSelect({ left: 0, width: 0, top: 0, height: 0 }, false);
            setView([lo, hi]);
          }
        }],
        setCursor: [(u) => {
          const i = u.cursor.idx;
          if (i !== null && i !== undefined && u.cursor.event) showSample(entry.indices[i]);
        }],
      },
    }, extra || {});
    entry.chart = new uPlot(options, [[]].concat(columns.map(() => [])), holder);
    entry.chart.setData(chartData(entry));
    linked.push(entry);
    state.charts[id] = entry.chart;
    return entry.chart;
  }

  function constant(value) {
    return data.samples.s_mm.map(() => value);
  }

  function drawPathCharts() {
    const sm = data.samples;
    const s = section('along-path', 'Along the path');
    const reset = element('button', { id: 'reset-zoom', type: 'button' }, s, 'Reset zoom');
    reset.addEventListener('click', () => state.resetView());
    element('p', { class: 'hint' }, s, 'Drag across a chart to zoom all three; double-click for the whole path.');
    const target = data.target_force_n;
    const lower = sm.predicted_force_n.map((p, i) => p === null ? null : Math.max(0, 2 * p - sm.upper_force_n[i]));
    const forceSeries = [
      { label: 'predicted [N]', stroke: '#1f77b4', width: 1.5 },
      { label: 'upper bound [N]', stroke: 'rgba(31,119,180,0.4)', dash: [4, 3] },
      { label: 'lower bound [N]', stroke: 'rgba(31,119,180,0.4)', dash: [4, 3] },
      { label: 'target [N]', stroke: '#d62728', width: 1 },
    ];
    const forceColumns = [sm.predicted_force_n, sm.upper_force_n, lower, constant(target)];
    if (sm.measured_peak_n) {
      forceSeries.push({ label: 'measured peak [N]', stroke: '#2ca02c', width: 0, points: { show: true, size: 4, fill: '#2ca02c' } });
      forceColumns.push(sm.measured_peak_n);
    }
    linkedChart(s, 'chart-force', 'Force: predicted with the model\'s uncertainty band, target' +
                (sm.measured_peak_n ? ', measured per-revolution peaks' : ''),
                'force [N]', forceSeries, forceColumns,
                { bands: [{ series: [2, 3], fill: 'rgba(31,119,180,0.12)' }] });
    linkedChart(s, 'chart-feed', 'Feed: planned, its limit, and the machine\'s range', 'feed [mm/min]', [
      { label: 'feed [mm/min]', stroke: '#ff7f0e', width: 1.5 },
      { label: 'feed limit [mm/min]', stroke: 'rgba(127,127,127,0.7)', dash: [3, 3] },
      { label: 'machine max [mm/min]', stroke: '#7f7f7f', width: 1 },
      { label: 'machine min [mm/min]', stroke: '#bcbd22', width: 1 },
    ], [sm.feed_mm_per_min, sm.feed_limit_mm_per_min, constant(data.machine.max_feed_mm_per_min),
        constant(data.machine.min_feed_mm_per_min)]);
    linkedChart(s, 'chart-engagement', 'Engagement', 'engagement [deg]', [
      { label: 'engagement [deg]', stroke: '#9467bd', width: 1.5 },
    ], [sm.engagement_deg]);
  }

  // ----- the tool path to scale

  const COLOURINGS = {
    feed: { label: 'feed [mm/min]', column: 'feed_mm_per_min' },
    predicted: { label: 'predicted force [N]', column: 'predicted_force_n' },
    measured: { label: 'measured per-revolution peak [N]', column: 'measured_peak_n' },
  };

  // Viridis-like ramp, t in [0, 1].
  function colour(t) {
    const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
    const x = Math.min(1, Math.max(0, t)) * (stops.length - 1);
    const k = Math.min(stops.length - 2, Math.floor(x));
    const f = x - k;
    const c = stops[k].map((v, j) => Math.round(v + f * (stops[k + 1][j] - v)));
    return 'rgb(' + c.join(',') + ')';
  }

  const path = { canvas: null, scale: 1, x0: 0, y0: 0, pad: 20, colouring: 'feed', range: [0, 1] };

  function pathPixel(i) {
    const sm = data.samples;
    return [path.pad + (sm.x_mm[i] - path.x0) * path.scale,
            path.canvas.height / devicePixelRatio - path.pad - (sm.y_mm[i] - path.y0) * path.scale];
  }

  const COLOUR_LEVELS = 48;

  // The path coloured by the chosen quantity, drawn once into an offscreen canvas (one stroke per colour
  // level, points closer than a pixel skipped); hovering only copies it and draws the marker.
  function renderPath() {
    const sm = data.samples;
    const values = sm[COLOURINGS[path.colouring].column];
    let lo = Infinity, hi = -Infinity;
    for (let i = 0; i < values.length; i++) {
      const v = values[i];
      if (v === null || !sm.engaged[i]) continue;  // the scale spans the cut: rapids would flatten it
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    }
    if (!(hi >= lo)) { lo = 0; hi = 1; }
    if (hi === lo) hi = lo + 1;
    path.range = [lo, hi];
    const cache = path.cache || document.createElement('canvas');
    cache.width = path.canvas.width;
    cache.height = path.canvas.height;
    path.cache = cache;
    const ctx = cache.getContext('2d');
    ctx.setTransform(devicePixelRatio, 0, 0, devicePixelRatio, 0, 0);
    ctx.lineWidth = 2;
    ctx.lineCap = 'round';
    const levels = Array.from({ length: COLOUR_LEVELS + 1 }, () => new Path2D());
    let [px, py] = pathPixel(0);
    for (let i = 1; i < values.length; i++) {
      const [x, y] = pathPixel(i);
      if (Math.abs(x - px) < 0.7 && Math.abs(y - py) < 0.7 && i < values.length - 1) continue;
      const v = values[i];
      const grey = v === null || !sm.engaged[i];  // out of the cut (air, rapids) or nothing measured
      const level = grey ? COLOUR_LEVELS
                         : Math.min(COLOUR_LEVELS - 1, Math.max(0, Math.round((v - lo) / (hi - lo) * (COLOUR_LEVELS - 1))));
      levels[level].moveTo(px, py);
      levels[level].lineTo(x, y);
      px = x;
      py = y;
    }
    for (let k = 0; k <= COLOUR_LEVELS; k++) {
      ctx.strokeStyle = k === COLOUR_LEVELS ? '#cccccc' : colour(k / (COLOUR_LEVELS - 1));
      ctx.stroke(levels[k]);
    }
    document.getElementById('path-scale-low').textContent = numberText(lo);
    document.getElementById('path-scale-high').textContent = numberText(hi);
    document.getElementById('path-scale-label').textContent = COLOURINGS[path.colouring].label;
  }

  function drawPath() {
    const ctx = path.canvas.getContext('2d');
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, path.canvas.width, path.canvas.height);
    ctx.drawImage(path.cache, 0, 0);
    if (state.selected >= 0) {
      ctx.setTransform(devicePixelRatio, 0, 0, devicePixelRatio, 0, 0);
      const [x, y] = pathPixel(state.selected);
      ctx.strokeStyle = '#d62728';
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.arc(x, y, 6, 0, 2 * Math.PI);
      ctx.stroke();
    }
  }

  const READOUT = [
    ['s_mm', 's [mm]'], ['engagement_deg', 'engagement [deg]'], ['chip_thickness_mm', 't_m [mm]'],
    ['contact_length_mm', 'L [mm]'], ['feed_mm_per_min', 'feed [mm/min]'], ['limit_reason', 'limited by'],
    ['predicted_force_n', 'predicted force [N]'], ['measured_peak_n', 'measured peak [N]'],
  ];

  function showSample(i) {
    if (i === undefined || i < 0) return;
    const sm = data.samples;
    state.selected = i;
    for (const [field] of READOUT) {
      const cell = document.querySelector('#readout [data-field="' + field + '"]');
      if (!cell) continue;
      if (field === 'limit_reason') {
        cell.textContent = data.limit_reasons[sm.limit_reason[i]] + (sm.extrapolated[i] ? ' (model extrapolated)' : '');
      } else {
        cell.textContent = numberText(sm[field] ? sm[field][i] : null);
      }
    }
    document.getElementById('readout').dataset.sample = String(i);
    if (path.canvas) drawPath();
  }
  state.showSample = showSample;

  function nearestSample(x, y) {
    const sm = data.samples;
    let best = -1, bestD = 15 * 15;
    for (let i = 0; i < sm.x_mm.length; i++) {
      const [px, py] = pathPixel(i);
      const d = (px - x) * (px - x) + (py - y) * (py - y);
      if (d < bestD) { bestD = d; best = i; }
    }
    return best;
  }

  function drawPathSection() {
    const sm = data.samples;
    const s = section('tool-path', 'Tool path (to scale)');
    const controls = element('div', { class: 'controls' }, s);
    element('label', { for: 'path-colour' }, controls, 'colour by ');
    const select = element('select', { id: 'path-colour' }, controls);
    for (const [key, c] of Object.entries(COLOURINGS)) {
      if (!sm[c.column]) continue;
      element('option', { value: key }, select, c.label);
    }
    const legend = element('div', { class: 'legend' }, controls);
    element('span', { id: 'path-scale-label' }, legend);
    element('span', { id: 'path-scale-low' }, legend);
    element('span', { class: 'ramp' }, legend);
    element('span', { id: 'path-scale-high' }, legend);
    const body = element('div', { class: 'path-body' }, s);
    const canvas = element('canvas', { id: 'path-canvas' }, body);
    const readout = element('table', { id: 'readout' }, body);
    for (const [field, label] of READOUT) {
      const row = element('tr', {}, readout);
      element('th', {}, row, label);
      element('td', { 'data-field': field }, row, '—');
    }
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (let i = 0; i < sm.x_mm.length; i++) {
      x0 = Math.min(x0, sm.x_mm[i]); x1 = Math.max(x1, sm.x_mm[i]);
      y0 = Math.min(y0, sm.y_mm[i]); y1 = Math.max(y1, sm.y_mm[i]);
    }
    const width = Math.max(300, Math.min(900, root.clientWidth - 360));
    const spanX = Math.max(x1 - x0, 1e-6), spanY = Math.max(y1 - y0, 1e-6);
    path.scale = Math.min((width - 2 * path.pad) / spanX, (600 - 2 * path.pad) / spanY);
    const height = Math.round(spanY * path.scale + 2 * path.pad);
    canvas.width = Math.round(width * devicePixelRatio);
    canvas.height = Math.round(height * devicePixelRatio);
    canvas.style.width = width + 'px';
    canvas.style.height = height + 'px';
    path.canvas = canvas;
    path.x0 = x0;
    path.y0 = y0;
    element('p', { class: 'hint' }, s, 'mm per pixel: ' + (1 / path.scale).toPrecision(3) +
            '. Grey: no tooth in the material (air, rapids) or nothing measured. Point at the path for the sample there.');
    select.addEventListener('change', () => { path.colouring = select.value; renderPath(); drawPath(); });
    canvas.addEventListener('mousemove', (e) => {
      const r = canvas.getBoundingClientRect();
      const i = nearestSample(e.clientX - r.left, e.clientY - r.top);
      if (i >= 0 && i !== state.selected) showSample(i);
    });
    renderPath();
    drawPath();
  }

  state.pathScale = () => path.scale;
  state.sampleCount = () => data.samples.s_mm.length;
  // Client (page) coordinates of sample i on the path canvas: where to point to read it.
  state.pathClientPoint = (i) => {
    const r = path.canvas.getBoundingClientRect();
    const [x, y] = pathPixel(i);
    return { x: r.left + x, y: r.top + y };
  };

  // ----- learning history

  function drawHistory() {
    const h = data.history;
    const s = section('history', 'Learning history: ' + h.cycles.length + (h.cycles.length === 1 ? ' cycle' : ' cycles'));
    if (h.table && h.table.columns.length > 0) drawTable(s, 'cycle-table', h.table);
    const cycles = h.cycles.map((c) => c.cycle);
    const perCycle = element('div', { id: 'chart-cycles', class: 'chart' }, s);
    state.charts['chart-cycles'] = new uPlot({
      title: 'Per cycle: the largest measured peak against the target, and the planned cycle time',
      width: chartWidth(), height: 220,
      scales: { x: { time: false }, err: {}, t: {} },
      axes: [{ label: 'cycle' , incrs: [1, 2, 5, 10]}, { scale: 'err', label: 'largest peak − target [%]', size: 60 },
             { scale: 't', label: 'cycle time [s]', side: 1, grid: { show: false }, size: 60 }],
      series: [{ label: 'cycle' },
               { label: 'largest peak − target [%]', scale: 'err', stroke: '#d62728', width: 2, points: { size: 7 } },
               { label: 'cycle time [s]', scale: 't', stroke: '#1f77b4', width: 2, points: { size: 7 } }],
    }, [cycles, h.cycles.map((c) => c.peak_error_percent), h.cycles.map((c) => c.cycle_time_s)], perCycle);
    const colours = h.cycles.map((c, k) => CYCLE_COLOURS[Math.max(0, CYCLE_COLOURS.length - h.cycles.length + k)]);
    const target = constant(data.target_force_n);
    linkedChart(s, 'chart-history-force', 'Measured per-revolution peaks of every cycle (newest darkest), and the target',
                'force [N]',
                h.cycles.map((c, k) => ({ label: 'cycle ' + c.cycle + ' measured [N]', stroke: colours[k], width: 1 }))
                  .concat([{ label: 'target [N]', stroke: '#d62728', width: 1 }]),
                h.cycles.map((c) => c.measured_n).concat([target]));
    linkedChart(s, 'chart-history-feed', 'Feed of every cycle (newest darkest), and the next plan\'s', 'feed [mm/min]',
                h.cycles.map((c, k) => ({ label: 'cycle ' + c.cycle + ' [mm/min]', stroke: colours[k], width: 1 }))
                  .concat([{ label: 'next plan [mm/min]', stroke: '#ff7f0e', width: 2 }]),
                h.cycles.map((c) => c.feed_mm_per_min).concat([data.samples.feed_mm_per_min]));
  }

  // ----- comparison

  function drawComparison() {
    const c = data.comparison;
    const s = section('comparison', 'Strategies compared');
    // Numbered: the bars carry the numbers, as a dozen strategy names do not fit under them.
    drawTable(s, 'comparison-table', { columns: ['#'].concat(c.table.columns),
                                       rows: c.table.rows.map((r, i) => [String(i + 1)].concat(r)) });
    const names = c.rows.map((r) => r.name);
    const xs = names.map((_, i) => i + 1);
    for (const figure of c.figures) {
      const holder = element('div', { id: 'chart-' + figure.key, class: 'chart' }, s);
      state.charts['chart-' + figure.key] = new uPlot({
        title: figure.label,
        width: chartWidth(), height: 220,
        scales: { x: { time: false, range: [0.5, names.length + 0.5] },
                  y: { range: (u, min, max) => [Math.min(0, min), max > 0 ? 1.1 * max : 1] } },  // bars from zero
        axes: [{ label: 'strategy (# in the table)', values: (u, ticks) => ticks.map((t) => (names[t - 1] ? String(t) : '')),
                 incrs: [1], size: 30 },
               { label: figure.label, size: 60 }],
        series: [{ label: 'strategy', value: (u, v) => (v === null ? '' : names[v - 1] || '') },
                 { label: figure.label, stroke: '#1f77b4', fill: 'rgba(31,119,180,0.3)',
                   paths: uPlot.paths.bars({ size: [0.6, 80] }), points: { show: false } }],
      }, [xs, c.rows.map((r) => r.figures[figure.key])], holder);
    }
  }

  // ----- the page

  drawSummary();
  if (data.kind === 'plan' || data.kind === 'history') {
    drawPathSection();
    drawPathCharts();
    if (data.kind === 'history') drawHistory();
  } else if (data.kind === 'comparison') {
    drawComparison();
  }
  state.ready = true;
  document.body.dataset.ready = 'true';
})();
