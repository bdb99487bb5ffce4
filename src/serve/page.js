// The page of `nurbs-box serve`: a curve editor whose every edit is enclosed by the server in a
// verified box (POST /api/enclose), with the de Boor construction at a parameter u
// (POST /api/eval) and the default knot vectors (GET /api/knots). No dependencies.
'use strict';
(() => {
  const $ = (id) => document.getElementById(id);
  const canvas = $('canvas');
  const ctx = canvas.getContext('2d');
  // The grid lies on a canvas of its own under the editor's: it is redrawn only when the view
  // changes, so an edit repaints (and the browser rasterizes) only what moves.
  const gridCanvas = $('grid-layer');
  const gridCtx = gridCanvas.getContext('2d', { alpha: false });
  const COLORS = {
    hull: '#7f7f7f', bezier: '#1f77b4', newton: '#d62728', 'newton-thesis': '#ff7f0e',
    'search-region': '#9467bd', 'search-region-verified': '#2ca02c',
  };
  const AXIS_COLORS = ['#d62728', '#1f77b4', '#2ca02c'];
  const OBLIQUE = 0.5 * Math.SQRT1_2; // 3-D: z drawn along the diagonal, shortened by half
  const HIT_RADIUS = 8;

  const state = {
    dim: 2,
    degree: 3,
    points: [], // [[x, y(, z)], ...]
    weights: [], // one per point
    knots: [],
    knotsCustom: false,
    knotKind: 'clamped',
    strategies: [],
    defaultStrategy: 'newton',
    limits: null,
    result: null, // last /api/enclose reply
    samples: [], // points of the curve, for drawing
    evalResult: null, // last /api/eval reply
    message: '',
    isError: false,
    view: { ox: 60, oy: 0, s: 40 },
    drag: null,
    pan: null,
    hover: -1,
    roundTrips: [], // ms, request to redrawn canvas
  };

  // ---------------------------------------------------------------- curve <-> JSON

  function rational() {
    return state.weights.some((w) => w !== 1);
  }

  function curveJSON() {
    const c = { degree: state.degree, knots: state.knots.slice(), control_points: state.points.map((p) => p.slice()) };
    if (rational()) c.weights = state.weights.slice();
    return c;
  }

  function ready() {
    return state.points.length >= state.degree + 1 && state.knots.length === state.points.length + state.degree + 1;
  }

  function domain() {
    if (state.result) return state.result.domain;
    const p = state.degree, n = state.points.length;
    return state.knots.length === n + p + 1 ? [state.knots[p], state.knots[n]] : [0, 1];
  }

  function num(x) {
    // the API writes non-finite bounds as "inf" / "-inf"
    return typeof x === 'number' ? x : x === 'inf' ? Infinity : x === '-inf' ? -Infinity : NaN;
  }

  function fmt(x, digits = 4) {
    x = num(x);
    if (!Number.isFinite(x)) return String(x);
    if (x !== 0 && (Math.abs(x) < 1e-3 || Math.abs(x) >= 1e5)) return x.toExponential(digits - 1);
    return String(+x.toFixed(digits));
  }

  // ---------------------------------------------------------------- requests

  // `later`: the status line may be rewritten with the next text update (see scheduleText)
  // instead of now; state.message always holds the latest text.
  function setMessage(text, isError = false, later = false) {
    state.message = text;
    state.isError = isError;
    if (later) {
      scheduleText();
    } else {
      renderStatus();
    }
  }

  function renderStatus() {
    const el = $('status');
    if (el.textContent !== state.message) el.textContent = state.message;
    el.classList.toggle('error', state.isError);
  }

  // The text views of a result (the strategy table, the status line) change with every edit.
  // While a point is dragged they are rewritten at most every TEXT_INTERVAL_MS, and always
  // after the last edit: a reader cannot follow faster, and every rewrite costs the browser a
  // layout and a paint of the panel, which would delay the next box. The canvas, box included,
  // is redrawn on every edit.
  const TEXT_INTERVAL_MS = 100;
  let textTimer = null, textPending = false, lastText = -Infinity;

  function scheduleText() {
    textPending = true;
    const since = performance.now() - lastText;
    if (since >= TEXT_INTERVAL_MS) {
      flushText();
    } else if (!textTimer) {
      textTimer = setTimeout(flushText, TEXT_INTERVAL_MS - since);
    }
  }

  function flushText() {
    if (textTimer) {
      clearTimeout(textTimer);
      textTimer = null;
    }
    if (!textPending) return;
    textPending = false;
    lastText = performance.now();
    renderResult();
    renderStatus();
  }

  // Requests go over one WebSocket when it is open (a message costs a fraction of a
  // millisecond, a fetch several), over fetch otherwise; the replies are the same JSON.
  let socket = null;
  const waiting = []; // resolvers of the requests sent on the socket, in order

  function openSocket() {
    const ws = new WebSocket(`ws://${location.host}/api/ws`);
    ws.onmessage = (ev) => {
      const w = waiting.shift();
      if (w) w.resolve(JSON.parse(ev.data));
    };
    ws.onclose = () => {
      if (socket === ws) socket = null;
      while (waiting.length) waiting.shift().reject(new Error('socket closed'));
    };
    socket = ws;
    return new Promise((resolve) => {
      ws.onopen = resolve;
      ws.onerror = resolve;
    });
  }

  async function api(path, body) {
    if (!socket) openSocket();
    if (socket.readyState === WebSocket.OPEN) {
      try {
        const r = await new Promise((resolve, reject) => {
          waiting.push({ resolve, reject });
          socket.send(`${body === undefined ? 'GET' : 'POST'} ${path}\n${body === undefined ? '' : body}`);
        });
        return { ok: r.status < 400, status: r.status, json: r.body };
      } catch (e) {
        // fall through to fetch
      }
    }
    const init = body === undefined ? {} : { method: 'POST', body, headers: { 'Content-Type': 'application/json' } };
    const r = await fetch(path, init);
    const j = await r.json();
    return { ok: r.ok, status: r.status, json: j };
  }

  // Structural edits (point count, degree, knot kind) need the default knots again.
  let structuralRuns = 0; // knot requests under way (settle waits for them too)

  async function structural() {
    structuralRuns++;
    try {
      await reknot();
    } finally {
      structuralRuns--;
    }
    renderTable();
    return update();
  }

  async function reknot() {
    const p = state.degree, n = state.points.length;
    if (state.knotsCustom && state.knots.length !== n + p + 1) {
      state.knotsCustom = false;
    }
    if (!state.knotsCustom) {
      if (n >= p + 1) {
        const r = await api(`/api/knots?degree=${p}&points=${n}&kind=${state.knotKind}`);
        state.knots = r.ok ? r.json.knots : [];
        if (!r.ok) setMessage(r.json.error.message, true);
      } else {
        state.knots = [];
      }
    }
  }

  let inFlight = null;
  let dirty = false;

  // Enclose the current curve (coalescing: edits made while a request runs are sent together
  // after it). Resolves when the canvas shows the latest curve.
  function update() {
    if (inFlight) {
      dirty = true;
      return inFlight;
    }
    inFlight = (async () => {
      do {
        dirty = false;
        await encloseOnce();
      } while (dirty);
      inFlight = null;
    })();
    return inFlight;
  }

  function selectedStrategy() {
    return $('strategy').value || state.defaultStrategy;
  }

  // The text views of the curve (not updated while the user types in them).
  function renderText() {
    const k = state.knots.join(', ');
    if (document.activeElement !== $('knots') && $('knots').value !== k) $('knots').value = k;
    if ($('json-details').open && document.activeElement !== $('json')) $('json').value = JSON.stringify(curveJSON());
  }

  async function encloseOnce() {
    if (!state.drag) renderText();
    if (!ready()) {
      state.result = null;
      state.evalResult = null;
      const p = state.degree, n = state.points.length;
      setMessage(n < p + 1
        ? `Degree ${p} needs at least ${p + 1} control points: add ${p + 1 - n} more, or lower the degree.`
        : `The knot vector needs ${n + p + 1} numbers (n + p + 2), it has ${state.knots.length}.`, n >= p + 1);
      draw();
      return;
    }
    const strategy = $('show-all').checked ? 'all' : selectedStrategy();
    const body = JSON.stringify(curveJSON());
    const t0 = performance.now();
    // The box comes from the server; the polyline drawn is sampled here (the same de Boor
    // corner cutting in f64; /api/enclose?samples=N returns the server's samples), which
    // keeps the reply small.
    const r = await api(`/api/enclose?strategy=${encodeURIComponent(strategy)}`, body);
    const tReply = performance.now();
    if (r.ok) {
      state.result = r.json;
      state.samples = sampleCurve();
    } else {
      state.result = null;
      state.evalResult = null;
    }
    draw();
    const tDrawn = performance.now();
    const ms = tDrawn - t0;
    state.roundTrips.push(ms);
    state.lastSplit = [tReply - t0, tDrawn - tReply];
    if (state.roundTrips.length > 10000) state.roundTrips.shift();
    if (r.ok) {
      const rec = mainRecord();
      const t = rec ? ` (${rec.strategy}: ${fmt(rec.time_s * 1e3, 3)} ms on the server)` : '';
      setMessage(`Box verified; round trip ${ms.toFixed(2)} ms${t}.`, false, true);
    } else {
      setMessage(r.json.error.message, true);
      renderResult();
    }
    if (r.ok && $('show-deboor').checked) await evalOnce();
  }

  // About 400 points of the curve (at least 8 per knot span) by de Boor corner cutting on the
  // homogeneous points (w P, w), for drawing. Call only when ready().
  function sampleCurve() {
    const p = state.degree, k = state.knots, P = state.points, W = state.weights;
    const d = state.dim, h = d + 1, n = P.length;
    const spans = [];
    for (let s = p; s < n; s++) if (k[s] < k[s + 1]) spans.push(s);
    const per = Math.max(8, Math.ceil(400 / spans.length));
    const buf = new Float64Array((p + 1) * h);
    const at = (s, u) => {
      for (let j = 0; j <= p; j++) {
        const i = s - p + j;
        for (let c = 0; c < d; c++) buf[j * h + c] = P[i][c] * W[i];
        buf[j * h + d] = W[i];
      }
      for (let r = 1; r <= p; r++) {
        for (let j = p; j >= r; j--) {
          const i = s - p + j;
          const a = (u - k[i]) / (k[i + p + 1 - r] - k[i]);
          for (let c = 0; c < h; c++) buf[j * h + c] = (1 - a) * buf[(j - 1) * h + c] + a * buf[j * h + c];
        }
      }
      const pt = [];
      for (let c = 0; c < d; c++) pt.push(buf[p * h + c] / buf[p * h + d]);
      return pt;
    };
    const out = [];
    for (const s of spans) for (let t = 0; t < per; t++) out.push(at(s, k[s] + ((k[s + 1] - k[s]) * t) / per));
    const last = spans[spans.length - 1];
    out.push(at(last, k[last + 1]));
    return out;
  }

  function sliderU() {
    const [a, b] = domain();
    const t = $('u-slider').value / 1000;
    return t >= 1 ? b : a + (b - a) * t;
  }

  async function evalOnce() {
    if (!ready() || !state.result) return;
    const u = sliderU();
    const r = await api(`/api/eval?u=${u}`, JSON.stringify(curveJSON()));
    state.evalResult = r.ok ? r.json : null;
    $('u-value').textContent = r.ok
      ? `u = ${fmt(u)}, C(u) = (${r.json.point.map((x) => fmt(x)).join(', ')}), span ${r.json.span}`
      : r.json.error.message;
    draw();
  }

  function mainRecord() {
    if (!state.result) return null;
    const recs = state.result.records;
    return recs.find((r) => r.strategy === selectedStrategy()) || recs[0];
  }

  // ---------------------------------------------------------------- view

  function project(p) {
    return p.length >= 3 ? [p[0] + OBLIQUE * p[2], p[1] + OBLIQUE * p[2]] : [p[0], p[1]];
  }

  function toPx(p) {
    const [x, y] = project(p);
    const v = state.view;
    return [v.ox + x * v.s, v.oy - y * v.s];
  }

  function toWorld(px, py) {
    const v = state.view;
    return [(px - v.ox) / v.s, (v.oy - py) / v.s];
  }

  function round(x) {
    return Math.round(x * 1000) / 1000;
  }

  function fit() {
    const pts = state.points.map(project);
    if (state.result) pts.push(...state.samples.map(project));
    if (!pts.length) return;
    const xs = pts.map((p) => p[0]), ys = pts.map((p) => p[1]);
    const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    const [w, h] = size();
    const s = Math.min((w - 120) / Math.max(x1 - x0, 1e-9), (h - 140) / Math.max(y1 - y0, 1e-9));
    state.view.s = Math.max(1e-6, Math.min(s, 1e6));
    state.view.ox = w / 2 - ((x0 + x1) / 2) * state.view.s;
    state.view.oy = h / 2 + ((y0 + y1) / 2) * state.view.s - 20;
    draw();
  }

  // The canvas's CSS size, read once per layout change (reading it in every draw would force a
  // layout of the whole page after each DOM update).
  let cssSize = null;
  new ResizeObserver(() => { cssSize = null; draw(); }).observe(canvas);

  function size() {
    if (!cssSize) cssSize = [canvas.clientWidth, canvas.clientHeight];
    return cssSize;
  }

  function resize() {
    const dpr = window.devicePixelRatio || 1;
    const [w, h] = size();
    for (const [c, g] of [[canvas, ctx], [gridCanvas, gridCtx]]) {
      if (c.width !== Math.round(w * dpr) || c.height !== Math.round(h * dpr)) {
        c.width = Math.round(w * dpr);
        c.height = Math.round(h * dpr);
      }
      g.setTransform(dpr, 0, 0, dpr, 0, 0);
    }
  }

  // ---------------------------------------------------------------- drawing

  function niceStep(x) {
    const e = Math.pow(10, Math.floor(Math.log10(x)));
    const f = x / e;
    return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * e;
  }

  let layerKey = '';

  // The layer under the editor's canvas: the grid and the knot vector, redrawn only when what
  // they show changes (view, size, toggles, knots, the parameter marker).
  function drawStaticLayer(w, h) {
    const grid = $('show-grid').checked, knots = $('show-knots').checked;
    const key = JSON.stringify([grid, knots, w, h, window.devicePixelRatio || 1, state.view, state.dim,
      knots ? [state.knots, state.degree, state.points.length, state.knotsCustom, state.knotKind,
        state.evalResult && state.evalResult.param] : 0]);
    if (key === layerKey) return;
    layerKey = key;
    gridCtx.fillStyle = '#fff';
    gridCtx.fillRect(0, 0, w, h);
    if (grid) drawGrid(gridCtx, w, h);
    if (knots) drawKnots(gridCtx, w, h);
  }

  function drawGrid(ctx, w, h) {
    const step = niceStep(40 / state.view.s);
    const [x0, y1] = toWorld(0, 0), [x1, y0] = toWorld(w, h);
    const xs = [], ys = [];
    for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) xs.push(x);
    for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) ys.push(y);
    ctx.lineWidth = 1;
    for (const axes of [false, true]) {
      ctx.beginPath();
      for (const x of xs) {
        if ((Math.abs(x) < step / 2) !== axes) continue;
        const [px] = toPx([x, 0]);
        ctx.moveTo(px, 0);
        ctx.lineTo(px, h);
      }
      for (const y of ys) {
        if ((Math.abs(y) < step / 2) !== axes) continue;
        const [, py] = toPx([0, y]);
        ctx.moveTo(0, py);
        ctx.lineTo(w, py);
      }
      ctx.strokeStyle = axes ? '#bbb' : '#eee';
      ctx.stroke();
    }
    ctx.font = '10px system-ui, sans-serif';
    ctx.fillStyle = '#999';
    for (const x of xs) ctx.fillText(fmt(x, 3), toPx([x, 0])[0] + 2, h - 30);
    for (const y of ys) ctx.fillText(fmt(y, 3), 2, toPx([0, y])[1] - 2);
  }

  function line(x0, y0, x1, y1) {
    ctx.beginPath();
    ctx.moveTo(x0, y0);
    ctx.lineTo(x1, y1);
    ctx.stroke();
  }

  function polyline(pts) {
    if (!pts.length) return;
    ctx.beginPath();
    pts.forEach((p, i) => {
      const [x, y] = toPx(p);
      if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y);
    });
    ctx.stroke();
  }

  function dot(p, r, fill, stroke) {
    const [x, y] = toPx(p);
    ctx.beginPath();
    ctx.arc(x, y, r, 0, 2 * Math.PI);
    if (fill) { ctx.fillStyle = fill; ctx.fill(); }
    if (stroke) { ctx.strokeStyle = stroke; ctx.stroke(); }
  }

  // The box [lo, hi] (2-D: a rectangle, 3-D: the projected cuboid).
  function drawBox(lo, hi, color, dash, width) {
    lo = lo.map(num);
    hi = hi.map(num);
    if (![...lo, ...hi].every(Number.isFinite)) return;
    ctx.strokeStyle = color;
    ctx.lineWidth = width;
    ctx.setLineDash(dash);
    if (lo.length === 2) {
      const [x0, y0] = toPx(lo), [x1, y1] = toPx(hi);
      ctx.strokeRect(x0, y1, x1 - x0, y0 - y1);
    } else {
      const corner = (i) => [i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]];
      for (let i = 0; i < 8; i++) {
        for (const b of [1, 2, 4]) {
          if (!(i & b)) polyline([corner(i), corner(i | b)]);
        }
      }
    }
    ctx.setLineDash([]);
  }

  function drawExtrema(rec) {
    rec.argmin.forEach((list, j) => list.forEach((x) => x.point && marker(x.point, j, 'min')));
    rec.argmax.forEach((list, j) => list.forEach((x) => x.point && marker(x.point, j, 'max')));
  }

  function marker(p, j, side) {
    const [x, y] = toPx(p);
    ctx.fillStyle = AXIS_COLORS[j % 3];
    ctx.strokeStyle = '#fff';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    if (side === 'min') ctx.rect(x - 5, y - 5, 10, 10); else ctx.arc(x, y, 5.5, 0, 2 * Math.PI);
    ctx.fill();
    ctx.stroke();
  }

  function drawKnots(ctx, w, h) {
    const k = state.knots;
    if (!k.length) return;
    const [a, b] = [k[0], k[k.length - 1]];
    const [da, db] = domain();
    const x0 = 60, x1 = w - 60, y = h - 48;
    const X = (u) => x0 + (b > a ? ((u - a) / (b - a)) * (x1 - x0) : 0);
    ctx.strokeStyle = '#ccc';
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(X(a), y);
    ctx.lineTo(X(b), y);
    ctx.stroke();
    ctx.strokeStyle = '#444';
    ctx.beginPath();
    ctx.moveTo(X(da), y);
    ctx.lineTo(X(db), y);
    ctx.stroke();
    ctx.lineWidth = 1;
    ctx.fillStyle = '#444';
    ctx.font = '10px ui-monospace, monospace';
    const seen = new Map();
    ctx.beginPath();
    for (const u of k) {
      const m = (seen.get(u) || 0) + 1;
      seen.set(u, m);
      ctx.moveTo(X(u), y - 4);
      ctx.lineTo(X(u), y + 4);
      ctx.rect(X(u) - 2, y - 6 - 5 * m, 4, 4);
    }
    ctx.stroke();
    ctx.fill();
    if (seen.size <= MAX_LABELS) for (const [u] of seen) ctx.fillText(fmt(u, 3), X(u) - 6, y + 14);
    if (state.evalResult) {
      ctx.fillStyle = '#d62728';
      const u = state.evalResult.param;
      ctx.beginPath();
      ctx.moveTo(X(u), y + 2);
      ctx.lineTo(X(u) - 5, y + 10);
      ctx.lineTo(X(u) + 5, y + 10);
      ctx.fill();
    }
    ctx.fillStyle = '#444';
    const shown = k.length > 40 ? [...k.slice(0, 20).map((u) => fmt(u, 3)), '…', ...k.slice(-4).map((u) => fmt(u, 3))] : k.map((u) => fmt(u, 3));
    ctx.fillText(`knots (${state.knotsCustom ? 'custom' : state.knotKind}, ${k.length}): [${shown.join(', ')}]`, 8, 14);
  }

  function drawDeBoor(e) {
    const levels = e.de_boor;
    levels.forEach((pts, r) => {
      const t = levels.length > 1 ? r / (levels.length - 1) : 1;
      const color = `hsl(${200 - 200 * t}, 70%, 45%)`;
      ctx.strokeStyle = color;
      ctx.lineWidth = 1;
      ctx.setLineDash(r === 0 ? [2, 3] : []);
      polyline(pts);
      ctx.setLineDash([]);
      pts.forEach((p) => dot(p, r === levels.length - 1 ? 5 : 3, color, null));
    });
    dot(e.point, 5, '#d62728', '#fff');
  }

  // The control points: one path per style (text and many small paths are what costs most
  // when the browser rasterises the canvas); index labels up to MAX_LABELS points, or with
  // the coordinates.
  const MAX_LABELS = 30;
  // A control point (a disc of radius 4.5 with a dark rim) drawn once into a small bitmap per
  // fill and pixel ratio; drawing 100 points is then 100 bitmap copies, which the browser
  // rasterizes far faster than 100 anti-aliased arcs.
  const POINT_SPRITE_RADIUS = 6;
  const sprites = new Map();
  function pointSprite(weighted, dpr) {
    const key = `${weighted} ${dpr}`;
    let c = sprites.get(key);
    if (!c) {
      const r = POINT_SPRITE_RADIUS;
      c = document.createElement('canvas');
      c.width = c.height = Math.ceil(2 * r * dpr);
      const g = c.getContext('2d');
      g.setTransform(dpr, 0, 0, dpr, 0, 0);
      g.beginPath();
      g.arc(r, r, 4.5, 0, 2 * Math.PI);
      g.fillStyle = weighted ? '#f5b041' : '#fff';
      g.fill();
      g.strokeStyle = '#333';
      g.lineWidth = 1;
      g.stroke();
      sprites.set(key, c);
    }
    return c;
  }

  function drawPoints() {
    const active = state.drag ? state.drag.i : state.hover;
    const dpr = window.devicePixelRatio || 1;
    const r = POINT_SPRITE_RADIUS;
    state.points.forEach((p, i) => {
      if (i === active) return;
      const [x, y] = toPx(p);
      ctx.drawImage(pointSprite(state.weights[i] !== 1, dpr), x - r, y - r, 2 * r, 2 * r);
    });
    if (active >= 0 && active < state.points.length) dot(state.points[active], 6, '#fff', '#d62728');
    const coords = $('show-coords').checked;
    if (!coords && state.points.length > MAX_LABELS) return;
    ctx.font = '11px system-ui, sans-serif';
    ctx.fillStyle = '#333';
    state.points.forEach((p, i) => {
      const [x, y] = toPx(p);
      let label = `${i}`;
      if (coords) label += ` (${p.map((v) => fmt(v, 3)).join(', ')}${state.weights[i] !== 1 ? '; w ' + fmt(state.weights[i], 3) : ''})`;
      ctx.fillText(label, x + 7, y - 7);
    });
  }

  function draw() {
    resize();
    const [w, h] = size();
    if (!state.view.oy) state.view.oy = h - 90;
    ctx.clearRect(0, 0, w, h);
    drawStaticLayer(w, h);
    const res = state.result;
    if (res) {
      const main = mainRecord();
      for (const rec of res.records) {
        if (rec === main) continue;
        drawBox(rec.lo, rec.hi, COLORS[rec.strategy] || '#555', rec.verified ? [] : [6, 4], 1);
      }
      if (main) {
        drawBox(main.inner_lo, main.inner_hi, COLORS[main.strategy] || '#555', [4, 3], 1);
        drawBox(main.lo, main.hi, COLORS[main.strategy] || '#555', main.verified ? [] : [6, 4], 2);
      }
    }
    if ($('show-polygon').checked && state.points.length) {
      ctx.strokeStyle = '#9aa';
      ctx.lineWidth = 1;
      polyline(state.points);
    }
    if (res) {
      ctx.strokeStyle = '#111';
      ctx.lineWidth = 2;
      polyline(state.samples);
      const main = mainRecord();
      if (main && $('show-extrema').checked) drawExtrema(main);
    }
    if (state.evalResult && $('show-deboor').checked) drawDeBoor(state.evalResult);
    if ($('show-points').checked) drawPoints();
  }

  function renderResult() {
    const t = $('result');
    const res = state.result;
    if (!res) { t.innerHTML = ''; return; }
    const rows = ['<tr><th></th><th>strategy</th><th>ms</th><th>gap</th><th>✓</th></tr>'];
    for (const r of res.records) {
      const gap = Math.max(...r.gap.map(num));
      rows.push(`<tr><td class="swatch" style="background:${COLORS[r.strategy] || '#555'}"></td><th>${r.strategy}</th>` +
        `<td>${fmt(r.time_s * 1e3, 3)}</td><td>${fmt(gap, 2)}</td><td>${r.verified ? 'yes' : 'no'}</td></tr>`);
    }
    const m = mainRecord();
    if (m) {
      const axes = ['x', 'y', 'z'];
      m.lo.forEach((lo, j) => {
        rows.push(`<tr><th>${axes[j]}</th><td colspan="4">[${fmt(lo, 8)}, ${fmt(m.hi[j], 8)}] gap ${fmt(m.gap[j], 2)}</td></tr>`);
      });
      rows.push(`<tr><th colspan="2">termination</th><td colspan="3">${m.stats.termination}</td></tr>`);
    }
    t.innerHTML = rows.join('');
  }

  function renderTable() {
    const t = $('points-table');
    const axes = ['x', 'y', 'z'].slice(0, state.dim);
    const head = `<tr><th>#</th>${axes.map((a) => `<th>${a}</th>`).join('')}<th>w</th></tr>`;
    const rows = state.points.map((p, i) => `<tr><th>${i}</th>` +
      p.map((v, j) => `<td><input type="number" step="any" data-i="${i}" data-j="${j}" value="${v}"></td>`).join('') +
      `<td><input type="number" step="any" min="0" data-i="${i}" data-j="w" value="${state.weights[i]}"></td></tr>`);
    t.innerHTML = head + rows.join('');
    $('ins-index').max = String(state.points.length);
  }

  function updateRow(i) {
    for (const el of $('points-table').querySelectorAll(`input[data-i="${i}"]`)) {
      const j = el.dataset.j;
      el.value = j === 'w' ? state.weights[i] : state.points[i][+j];
    }
  }

  // ---------------------------------------------------------------- edits

  function hit(px, py) {
    let best = -1, bd = HIT_RADIUS;
    state.points.forEach((p, i) => {
      const [x, y] = toPx(p);
      const d = Math.hypot(x - px, y - py);
      if (d <= bd) { bd = d; best = i; }
    });
    return best;
  }

  function fromWorld(x, y, z = 0) {
    return state.dim === 3 ? [round(x - OBLIQUE * z), round(y - OBLIQUE * z), z] : [round(x), round(y)];
  }

  function insertPoint(i, p, w = 1) {
    if (state.limits && state.points.length >= state.limits.max_points) {
      setMessage(`This server takes at most ${state.limits.max_points} control points.`, true);
      return Promise.resolve();
    }
    state.points.splice(i, 0, p);
    state.weights.splice(i, 0, w);
    return structural();
  }

  function deletePoint(i) {
    state.points.splice(i, 1);
    state.weights.splice(i, 1);
    state.hover = -1;
    return structural();
  }

  function movePoint(i, x, y) {
    const z = state.dim === 3 ? state.points[i][2] : 0;
    state.points[i] = fromWorld(x, y, z);
    updateRow(i);
    return update();
  }

  function pos(ev) {
    const r = canvas.getBoundingClientRect();
    return [ev.clientX - r.left, ev.clientY - r.top];
  }

  canvas.addEventListener('mousedown', (ev) => {
    if (ev.button !== 0) return;
    const [px, py] = pos(ev);
    const i = hit(px, py);
    if (i >= 0) {
      state.drag = { i };
    } else if (ev.shiftKey) {
      state.pan = { px, py, ox: state.view.ox, oy: state.view.oy };
    } else {
      const [x, y] = toWorld(px, py);
      insertPoint(state.points.length, fromWorld(x, y));
      state.drag = { i: state.points.length - 1 };
    }
    canvas.focus();
    ev.preventDefault();
  });

  window.addEventListener('mousemove', (ev) => {
    const [px, py] = pos(ev);
    if (state.drag) {
      const [x, y] = toWorld(px, py);
      movePoint(state.drag.i, x, y);
    } else if (state.pan) {
      state.view.ox = state.pan.ox + px - state.pan.px;
      state.view.oy = state.pan.oy + py - state.pan.py;
      draw();
    } else if (ev.target === canvas) {
      const i = hit(px, py);
      if (i !== state.hover) { state.hover = i; draw(); }
    }
  });

  window.addEventListener('mouseup', () => {
    if (state.drag) renderText();
    state.drag = null;
    state.pan = null;
  });

  canvas.addEventListener('contextmenu', (ev) => {
    ev.preventDefault();
    const [px, py] = pos(ev);
    const i = hit(px, py);
    if (i >= 0) deletePoint(i);
  });

  canvas.addEventListener('wheel', (ev) => {
    ev.preventDefault();
    const [px, py] = pos(ev);
    const f = Math.exp(-ev.deltaY * 0.0015);
    const v = state.view;
    v.ox = px - (px - v.ox) * f;
    v.oy = py - (py - v.oy) * f;
    v.s *= f;
    draw();
  }, { passive: false });

  $('points-table').addEventListener('change', (ev) => {
    const el = ev.target;
    if (!el.dataset || el.dataset.i === undefined) return;
    const i = +el.dataset.i, v = parseFloat(el.value);
    if (!Number.isFinite(v)) { setMessage('Expected a number.', true); return; }
    if (el.dataset.j === 'w') state.weights[i] = v; else state.points[i][+el.dataset.j] = v;
    update();
  });

  $('insert-form').addEventListener('submit', (ev) => {
    ev.preventDefault();
    const i = Math.max(0, Math.min(state.points.length, parseInt($('ins-index').value, 10) || 0));
    const x = parseFloat($('ins-x').value), y = parseFloat($('ins-y').value), w = parseFloat($('ins-w').value);
    if (![x, y, w].every(Number.isFinite)) { setMessage('Insert: x, y and w must be numbers.', true); return; }
    insertPoint(i, state.dim === 3 ? [x, y, 0] : [x, y], w);
  });

  $('degree').addEventListener('change', () => {
    state.degree = parseInt($('degree').value, 10);
    state.knotsCustom = false;
    structural();
  });

  $('knot-kind').addEventListener('change', () => {
    state.knotKind = $('knot-kind').value;
    state.knotsCustom = false;
    structural();
  });

  $('knots-apply').addEventListener('click', () => {
    const k = $('knots').value.split(/[\s,;[\]]+/).filter((s) => s).map(Number);
    if (!k.every(Number.isFinite)) { setMessage('Knots: expected numbers separated by commas.', true); return; }
    state.knots = k;
    state.knotsCustom = true;
    update();
  });

  $('knots-default').addEventListener('click', () => {
    state.knotsCustom = false;
    structural();
  });

  $('u-slider').addEventListener('input', () => evalOnce());
  $('show-deboor').addEventListener('change', () => { state.evalResult = null; draw(); evalOnce(); });
  for (const id of ['show-polygon', 'show-points', 'show-knots', 'show-coords', 'show-grid', 'show-extrema']) {
    $(id).addEventListener('change', draw);
  }
  $('show-all').addEventListener('change', () => update());
  $('strategy').addEventListener('change', () => update());
  $('fit').addEventListener('click', fit);
  $('clear').addEventListener('click', () => {
    state.points = [];
    state.weights = [];
    state.knotsCustom = false;
    structural();
  });

  $('help-button').addEventListener('click', () => { $('help').hidden = false; $('help-button').setAttribute('aria-expanded', 'true'); });
  $('help-close').addEventListener('click', () => { $('help').hidden = true; $('help-button').setAttribute('aria-expanded', 'false'); });
  $('help').addEventListener('click', (ev) => { if (ev.target === $('help')) $('help').hidden = true; });

  // Load: one curve object, a JSON array of curves (the first), or JSON Lines (the first line).
  function parseCurveText(text) {
    let v;
    try {
      v = JSON.parse(text);
    } catch (e) {
      const first = text.split('\n').find((l) => l.trim());
      v = JSON.parse(first);
    }
    return Array.isArray(v) ? v[0] : v;
  }

  // Set the whole curve (load, the JSON box, tests). The server validates it.
  function setCurve(c) {
    if (!c || typeof c !== 'object' || !Array.isArray(c.control_points) || !Number.isInteger(c.degree)) {
      setMessage('Load: expected a curve object {"degree", "knots", "control_points", "weights"}.', true);
      return Promise.resolve();
    }
    const dims = new Set(c.control_points.map((p) => (Array.isArray(p) ? p.length : 0)));
    const dim = dims.size === 1 ? [...dims][0] : 0;
    if (dim !== 2 && dim !== 3) {
      setMessage('Load: this page shows 2-D and 3-D curves (all control points of one dimension).', true);
      return Promise.resolve();
    }
    state.dim = dim;
    state.degree = c.degree;
    state.points = c.control_points.map((p) => p.map(Number));
    state.weights = Array.isArray(c.weights) ? c.weights.map(Number) : state.points.map(() => 1);
    if (Array.isArray(c.knots)) {
      state.knots = c.knots.map(Number);
      state.knotsCustom = true;
    } else {
      state.knotsCustom = false;
    }
    if (state.degree >= 1 && state.degree <= maxDegree()) $('degree').value = String(state.degree);
    renderTable();
    return (state.knotsCustom ? update() : structural()).then(fit);
  }

  $('load').addEventListener('change', async () => {
    const f = $('load').files[0];
    if (!f) return;
    try {
      await setCurve(parseCurveText(await f.text()));
    } catch (e) {
      setMessage(`Load: not JSON (${e.message}).`, true);
    }
    $('load').value = '';
  });

  $('json-apply').addEventListener('click', () => {
    try {
      setCurve(parseCurveText($('json').value));
    } catch (e) {
      setMessage(`Curve JSON: ${e.message}`, true);
    }
  });

  $('save').addEventListener('click', () => {
    const blob = new Blob([JSON.stringify(curveJSON()) + '\n'], { type: 'application/json' });
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = 'curve.json';
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  });

  $('json-details').addEventListener('toggle', renderText);

  function maxDegree() {
    return state.limits ? state.limits.max_degree : 40;
  }

  async function init() {
    await openSocket();
    const r = await api('/api/strategies');
    if (r.ok) {
      state.strategies = r.json.strategies;
      state.defaultStrategy = r.json.default;
      state.limits = r.json.limits;
    }
    $('strategy').innerHTML = state.strategies
      .map((s) => `<option value="${s.name}"${s.name === state.defaultStrategy ? ' selected' : ''}>${s.name}${s.verified ? '' : ' (heuristic)'}</option>`)
      .join('');
    const degrees = [];
    for (let p = 1; p <= maxDegree(); p++) degrees.push(`<option value="${p}"${p === state.degree ? ' selected' : ''}>${p}</option>`);
    $('degree').innerHTML = degrees.join('');
    renderTable();
    draw();
    setMessage('Click to add control points; right click deletes one; Help explains the rest.');
    document.body.dataset.ready = 'true';
  }

  // For scripts and the browser test.
  window.nurbsBox = {
    state,
    curveJSON,
    setCurve,
    update,
    fit,
    draw,
    api,
    toPx,
    movePoint: (i, p) => {
      state.points[i] = p.slice();
      updateRow(i);
      return update();
    },
    // resolves when every edit so far is enclosed and drawn
    settle: async () => {
      while (structuralRuns > 0 || inFlight) {
        await (inFlight || new Promise((r) => setTimeout(r, 2)));
      }
      flushText();
    },
  };

  init();
})();
