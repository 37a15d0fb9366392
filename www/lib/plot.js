// Charts shared by the panels: time/frequency series through uPlot, and
// small canvas charts for paths (equal aspect), polar traces and bars.
// Every function draws into `el` and returns { el, update(opts) }.
import uPlot from '../vendor/uPlot.esm.js';

export const PALETTE = ['#0b6bcb', '#d9480f', '#2b8a3e', '#862e9c', '#c2255c', '#1098ad', '#5c940d', '#495057'];

function frame(el, title) {
  el.classList.add('chart');
  el.replaceChildren();
  if (title) el.append(Object.assign(document.createElement('div'), { className: 'chart-title', textContent: title }));
}

/** Line chart over a shared x: data = [xs, ys1, ys2, …]. */
export function lineChart(el, opts) {
  let plot;
  const build = (o) => {
    plot?.destroy();
    frame(el, o.title);
    const host = document.createElement('div');
    el.append(host);
    const width = Math.max(200, el.clientWidth || 600);
    const drawExtras = (u) => {
      const { ctx, bbox } = u;
      // the visible y range, for readers of the page (and its tests)
      el.dataset.yMin = String(u.scales.y.min);
      el.dataset.yMax = String(u.scales.y.max);
      ctx.save();
      for (const b of o.bands || []) {
        const x0 = u.valToPos(b.from, 'x', true);
        const x1 = u.valToPos(b.to, 'x', true);
        ctx.fillStyle = b.color || 'rgba(11,107,203,0.08)';
        ctx.fillRect(Math.max(bbox.left, x0), bbox.top, Math.min(bbox.left + bbox.width, x1) - Math.max(bbox.left, x0), bbox.height);
        if (b.label) {
          ctx.fillStyle = '#5b6673';
          ctx.font = `${11 * devicePixelRatio}px system-ui`;
          ctx.fillText(b.label, Math.max(bbox.left, x0) + 4, bbox.top + 14 * devicePixelRatio);
        }
      }
      for (const l of o.hLines || []) {
        const y = u.valToPos(l.y, 'y', true);
        ctx.strokeStyle = l.color || '#b3261e';
        ctx.setLineDash([6, 4]);
        ctx.beginPath();
        ctx.moveTo(bbox.left, y);
        ctx.lineTo(bbox.left + bbox.width, y);
        ctx.stroke();
        if (l.label) {
          ctx.fillStyle = l.color || '#b3261e';
          ctx.font = `${11 * devicePixelRatio}px system-ui`;
          // at the right end, inside the plot, below the line when it is near the top
          ctx.textAlign = 'right';
          ctx.fillText(l.label, bbox.left + bbox.width - 4, y - 4 < bbox.top + 12 * devicePixelRatio ? y + 12 * devicePixelRatio : y - 4);
          ctx.textAlign = 'left';
        }
      }
      ctx.restore();
    };
    el.append(hint('drag to zoom, double-click to reset'));
    plot = new uPlot(
      {
        width,
        height: o.height || 260,
        // Horizontal lines (a torque limit) are always in view: the y range
        // covers them as well as the data (the ±725 N·m limit never showed
        // on a 0–300 N·m torque).
        scales: { x: { time: false }, ...(o.hLines?.length ? { y: { range: (_u, min, max) => coverLines(min, max, o.hLines) } } : {}), ...(o.scales || {}) },
        axes: [{ label: o.xLabel }, { label: o.yLabel, size: 60 }],
        series: [{ label: o.xLabel || 'x' }, ...o.series.map((s, i) => ({ label: s.label, stroke: s.color || PALETTE[i % PALETTE.length], width: s.width || 1.5, dash: s.dash, points: { show: false } }))],
        hooks: { draw: [drawExtras] },
      },
      o.data,
      host,
    );
  };
  build(opts);
  // A ResizeObserver also reports once when it starts: only a real change
  // of width resizes (uPlot's setSize clears and redraws the whole chart
  // even at the same size, which doubled the drawing of every new chart).
  observe(el, () => plot && el.clientWidth && el.clientWidth !== plot.width && plot.setSize({ width: el.clientWidth, height: opts.height || 260 }), () => plot?.destroy());
  return {
    el,
    plot: () => plot,
    update(o) {
      opts = { ...opts, ...o };
      build(opts);
    },
  };
}

/** A y range [lo, hi] over the data's [min, max] and every line's y, with
 * 5 % of the span as margin so a line at the edge stays visible. */
export function coverLines(min, max, lines) {
  const ys = lines.map((l) => l.y).filter(Number.isFinite);
  let lo = Math.min(Number.isFinite(min) ? min : Infinity, ...ys);
  let hi = Math.max(Number.isFinite(max) ? max : -Infinity, ...ys);
  if (!Number.isFinite(lo) || !Number.isFinite(hi)) return [0, 1];
  if (lo === hi) [lo, hi] = [lo - 1, hi + 1];
  const pad = 0.05 * (hi - lo);
  return [lo - pad, hi + pad];
}

/** One ResizeObserver per chart element: a redraw into the same element
 * disconnects the previous one, and an element taken out of the page
 * disconnects its own (no observer or plot outlives its chart). */
function observe(el, onResize, onGone) {
  el._mtObserver?.disconnect();
  const ro = new ResizeObserver(() => {
    if (!el.isConnected) {
      ro.disconnect();
      onGone?.();
      return;
    }
    onResize();
  });
  ro.observe(el);
  el._mtObserver = ro;
}

function hint(text) {
  return Object.assign(document.createElement('div'), { className: 'chart-hint', textContent: text });
}

function niceTicks(lo, hi, n = 5) {
  if (!(hi > lo)) return [lo];
  const raw = (hi - lo) / n;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) || raw;
  const out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  return out;
}

// Below 1e-12 (in any unit the page plots: mm, µm, rad, deg) a label is
// numerical noise (4.4e-14 on a colour bar of a zero range): it reads 0.
const tick = (v) => (Math.abs(v) < 1e-12 ? '0' : Math.abs(v) >= 1e4 || Math.abs(v) < 1e-3 ? v.toExponential(1) : String(+v.toPrecision(6)));

/** True on a touch screen without a mouse (a phone): hints say pinch, not wheel. */
const COARSE = () => typeof matchMedia === 'function' && matchMedia('(pointer: coarse)').matches;

function canvasChart(el, opts, draw) {
  // Zoom and pan: the draw function reads state.view (null = fit) and
  // leaves in state.map how to turn canvas pixels into its view.
  const state = { view: null, map: null };
  let canvas;
  const paint = () => {
    frame(el, opts.title);
    canvas = document.createElement('canvas');
    el.append(canvas);
    const w = Math.max(200, el.clientWidth || 600);
    const hgt = opts.height || Math.min(420, Math.max(240, w * 0.75));
    const dpr = window.devicePixelRatio || 1;
    canvas.width = w * dpr;
    canvas.height = hgt * dpr;
    canvas.style.height = `${hgt}px`;
    const ctx = canvas.getContext('2d');
    ctx.scale(dpr, dpr);
    ctx.font = '11px system-ui';
    const legend = draw(ctx, w, hgt, state) || [];
    if (state.map) el.append(hint(COARSE() ? 'pinch to zoom, drag sideways to pan, double-tap to reset' : 'wheel to zoom, drag to pan, double-click to reset'));
    if (legend.length) {
      const lg = document.createElement('div');
      lg.className = 'legend';
      for (const { label, color } of legend) {
        const item = document.createElement('span');
        const sw = document.createElement('i');
        sw.style.background = color;
        item.append(sw, label);
        lg.append(item);
      }
      el.append(lg);
    }
  };
  paint();
  let width = el.clientWidth;
  observe(el, () => {
    if (el.clientWidth && Math.abs(el.clientWidth - width) > 2) {
      width = el.clientWidth;
      paint();
    }
  });
  // Listeners on the element (it outlives each repaint's canvas), once.
  el._mtState = state;
  el._mtPaint = paint;
  if (!el._mtInteractive) {
    el._mtInteractive = true;
    const at = (e) => {
      const r = el._mtCanvas().getBoundingClientRect();
      return [e.clientX - r.left, e.clientY - r.top];
    };
    el._mtCanvas = () => el.querySelector('canvas');
    el.addEventListener('wheel', (e) => {
      const st = el._mtState;
      if (!st.map || e.target.tagName !== 'CANVAS') return;
      e.preventDefault();
      st.view = st.map.zoom(at(e), Math.exp(Math.sign(e.deltaY) * 0.15));
      el._mtPaint();
    }, { passive: false });
    // One pointer pans; two (a pinch on a touch screen) zoom about their
    // midpoint by the change of their distance. The canvas leaves vertical
    // swipes to the page (touch-action: pan-y, style.css), so a phone still
    // scrolls past a chart.
    let drag = null;
    const pointers = new Map();
    let pinch = null;
    const spread = () => {
      const [a, b] = [...pointers.values()];
      return { d: Math.hypot(a[0] - b[0], a[1] - b[1]), mid: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] };
    };
    el.addEventListener('pointerdown', (e) => {
      if (!el._mtState.map || e.target.tagName !== 'CANVAS') return;
      pointers.set(e.pointerId, at(e));
      e.target.setPointerCapture?.(e.pointerId);
      if (pointers.size === 2) {
        drag = null;
        pinch = spread();
      } else if (pointers.size === 1) drag = { p: at(e), map: el._mtState.map };
    });
    el.addEventListener('pointermove', (e) => {
      if (!pointers.has(e.pointerId)) return;
      pointers.set(e.pointerId, at(e));
      if (pinch && pointers.size === 2) {
        const now = spread();
        if (now.d > 0 && pinch.d > 0) {
          el._mtState.view = el._mtState.map.zoom(now.mid, pinch.d / now.d);
          el._mtPaint();
        }
        pinch = now;
        return;
      }
      if (!drag) return;
      const p = at(e);
      el._mtState.view = drag.map.pan(p[0] - drag.p[0], p[1] - drag.p[1]);
      el._mtPaint();
    });
    const end = (e) => {
      pointers.delete(e.pointerId);
      if (pointers.size < 2) pinch = null;
      drag = null;
    };
    el.addEventListener('pointerup', end);
    el.addEventListener('pointercancel', end);
    el.addEventListener('dblclick', () => {
      el._mtState.view = null;
      el._mtPaint();
    });
  }
  return {
    el,
    update(o) {
      Object.assign(opts, o);
      paint();
    },
  };
}

/** Viridis-like colour for t in [0, 1], in 256 steps: a table built once,
 * so a path coloured per point costs no string building per segment, and
 * neighbouring segments share one colour (one stroke) more often. */
export function colorScale(t) {
  const k = Math.round(Math.max(0, Math.min(1, Number.isFinite(t) ? t : 0)) * 255);
  return (COLOR_TABLE ??= buildColorTable())[k];
}
let COLOR_TABLE = null;
function buildColorTable() {
  const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  return Array.from({ length: 256 }, (_, k) => {
    const x = (k / 255) * (stops.length - 1);
    const i = Math.min(stops.length - 2, Math.floor(x));
    const f = x - i;
    const c = stops[i].map((a, j) => Math.round(a + (stops[i + 1][j] - a) * f));
    return `rgb(${c[0]},${c[1]},${c[2]})`;
  });
}

function axesBox(ctx, w, hgt, xr, yr, o) {
  const m = { l: 58, r: o.colorLabel ? 70 : 12, t: 8, b: 38 };
  const pw = w - m.l - m.r;
  const ph = hgt - m.t - m.b;
  let [x0, x1] = xr;
  let [y0, y1] = yr;
  if (o.equal !== false) {
    const sx = (x1 - x0) / pw;
    const sy = (y1 - y0) / ph;
    const s = Math.max(sx, sy);
    const cx = (x0 + x1) / 2;
    const cy = (y0 + y1) / 2;
    [x0, x1] = [cx - (s * pw) / 2, cx + (s * pw) / 2];
    [y0, y1] = [cy - (s * ph) / 2, cy + (s * ph) / 2];
  }
  const X = (x) => m.l + ((x - x0) / (x1 - x0)) * pw;
  const Y = (y) => m.t + ph - ((y - y0) / (y1 - y0)) * ph;
  ctx.strokeStyle = '#d9dee4';
  ctx.fillStyle = '#5b6673';
  ctx.lineWidth = 1;
  for (const v of o.noXTicks ? [] : niceTicks(x0, x1)) {
    ctx.beginPath();
    ctx.moveTo(X(v), m.t);
    ctx.lineTo(X(v), m.t + ph);
    ctx.stroke();
    ctx.fillText(tick(v), X(v) - 12, m.t + ph + 14);
  }
  for (const v of niceTicks(y0, y1)) {
    ctx.beginPath();
    ctx.moveTo(m.l, Y(v));
    ctx.lineTo(m.l + pw, Y(v));
    ctx.stroke();
    ctx.fillText(tick(v), 4, Y(v) + 4);
  }
  ctx.strokeStyle = '#9aa5b1';
  ctx.strokeRect(m.l, m.t, pw, ph);
  if (o.xLabel) ctx.fillText(o.xLabel, m.l + pw / 2 - 20, hgt - 6);
  if (o.yLabel) {
    ctx.save();
    ctx.translate(12, m.t + ph / 2 + 20);
    ctx.rotate(-Math.PI / 2);
    ctx.fillText(o.yLabel, 0, 0);
    ctx.restore();
  }
  return { X, Y, m, pw, ph, x0, x1, y0, y1 };
}

/** Zoom/pan of a rectangular view (data ranges) drawn by axesBox. */
function rectMap(b) {
  const { m, pw, ph, x0, x1, y0, y1 } = b;
  return {
    zoom([px, py], f) {
      const x = x0 + ((px - m.l) / pw) * (x1 - x0);
      const y = y1 - ((py - m.t) / ph) * (y1 - y0);
      return { xr: [x - (x - x0) * f, x + (x1 - x) * f], yr: [y - (y - y0) * f, y + (y1 - y) * f] };
    },
    pan(dx, dy) {
      const sx = ((x1 - x0) / pw) * dx;
      const sy = ((y1 - y0) / ph) * dy;
      return { xr: [x0 - sx, x1 - sx], yr: [y0 + sy, y1 + sy] };
    },
  };
}

function range(arrays, pad = 0.05) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const a of arrays) for (const v of a) if (Number.isFinite(v)) (lo = Math.min(lo, v)), (hi = Math.max(hi, v));
  if (!Number.isFinite(lo)) return [0, 1];
  if (hi - lo < 1e-12) return [lo - 1, hi + 1];
  const p = (hi - lo) * pad;
  return [lo - p, hi + p];
}

/** Paths in the plane (equal aspect by default); `values` colours a trace per point. */
export function xyChart(el, opts) {
  return canvasChart(el, opts, (ctx, w, hgt, state) => {
    const traces = opts.traces || [];
    const box = axesBox(ctx, w, hgt, state.view?.xr || range(traces.map((t) => t.x)), state.view?.yr || range(traces.map((t) => t.y)), state.view ? { ...opts, equal: false } : opts);
    const { X, Y, m, pw, ph } = box;
    state.map = rectMap(box);
    const allV = traces.filter((t) => t.values).map((t) => t.values);
    // opts.valueRange: one colour scale shared by several charts (before/after).
    const [v0, v1] = opts.valueRange || (allV.length ? range(allV, 0) : [0, 1]);
    ctx.save();
    ctx.beginPath();
    ctx.rect(m.l, m.t, pw, ph);
    ctx.clip();
    const legend = [];
    traces.forEach((t, k) => {
      const color = t.color || PALETTE[k % PALETTE.length];
      ctx.lineWidth = t.width || 1.5;
      ctx.setLineDash(t.dash || []);
      if (t.points) {
        ctx.fillStyle = color;
        for (let i = 0; i < t.x.length; i++) ctx.fillRect(X(t.x[i]) - 2, Y(t.y[i]) - 2, 4, 4);
      } else if (t.values) {
        // Segment i takes the colour of point i; consecutive segments of
        // the same colour are one stroke (the colours are whole RGB values,
        // so neighbours often share one): far fewer strokes to rasterise.
        let run = null;
        for (let i = 1; i < t.x.length; i++) {
          const c = colorScale((t.values[i] - v0) / (v1 - v0 || 1));
          if (c !== run) {
            if (run !== null) ctx.stroke();
            run = c;
            ctx.strokeStyle = c;
            ctx.beginPath();
            ctx.moveTo(X(t.x[i - 1]), Y(t.y[i - 1]));
          }
          ctx.lineTo(X(t.x[i]), Y(t.y[i]));
        }
        if (run !== null) ctx.stroke();
      } else {
        ctx.strokeStyle = color;
        ctx.beginPath();
        for (let i = 0; i < t.x.length; i++) (i ? ctx.lineTo : ctx.moveTo).call(ctx, X(t.x[i]), Y(t.y[i]));
        ctx.stroke();
      }
      if (t.label) legend.push({ label: t.label, color: t.values ? colorScale(0.7) : color });
    });
    ctx.restore();
    if (allV.length) {
      const x = w - m.r + 14;
      for (let i = 0; i < ph; i++) {
        ctx.fillStyle = colorScale(1 - i / ph);
        ctx.fillRect(x, m.t + i, 12, 1);
      }
      ctx.fillStyle = '#5b6673';
      ctx.fillText(tick(v1), x + 14, m.t + 8);
      ctx.fillText(tick(v0), x + 14, m.t + ph);
      if (opts.colorLabel) ctx.fillText(opts.colorLabel, Math.min(x - 8, w - ctx.measureText(opts.colorLabel).width - 2), m.t + ph + 24);
    }
    return legend;
  });
}

/** Polar traces (angle in rad, r in any unit) with reference circles and markers. */
export function polarChart(el, opts) {
  return canvasChart(el, { height: 380, ...opts }, (ctx, w, hgt, state) => {
    const traces = opts.traces || [];
    const v = state.view || { zoom: 1, dx: 0, dy: 0 };
    const rmax = (Math.max(1e-12, ...traces.flatMap((t) => Array.from(t.r, Math.abs)), ...(opts.circles || []).map((c) => c.r)) * 1.05) / v.zoom;
    const cx = w / 2 + v.dx;
    const cy = hgt / 2 + v.dy;
    const R = Math.min(w, hgt) / 2 - 20;
    state.map = {
      zoom: ([px, py], f) => ({ zoom: v.zoom / f, dx: px - w / 2 - (px - cx) / f, dy: py - hgt / 2 - (py - cy) / f }),
      pan: (dx, dy) => ({ ...v, dx: v.dx + dx, dy: v.dy + dy }),
    };
    ctx.save();
    ctx.beginPath();
    ctx.rect(0, 0, w, hgt);
    ctx.clip();
    // Rings are labelled with what they mean: r − rOffset (the deviation
    // when r = base circle + deviation).
    const rOff = opts.rOffset || 0;
    const P = (a, r) => [cx + (r / rmax) * R * Math.cos(a), cy - (r / rmax) * R * Math.sin(a)];
    ctx.strokeStyle = '#d9dee4';
    ctx.fillStyle = '#5b6673';
    const step = niceTicks(0, rmax, 4)[1] || rmax;
    const rings = [];
    for (let t = rOff - Math.floor(rOff / step) * step; t <= rmax * (1 + 1e-9); t += step) if (t > step * 1e-6) rings.push(t);
    for (const ring of rings) {
      ctx.beginPath();
      ctx.arc(cx, cy, (ring / rmax) * R, 0, 2 * Math.PI);
      ctx.stroke();
      ctx.fillText(tick(+(ring - rOff).toPrecision(6)), cx + (ring / rmax) * R + 2, cy - 2);
    }
    for (let d = 0; d < 360; d += 30) {
      const [x, y] = P((d * Math.PI) / 180, rmax);
      ctx.beginPath();
      ctx.moveTo(cx, cy);
      ctx.lineTo(x, y);
      ctx.stroke();
      ctx.fillText(`${d}°`, cx + (x - cx) * 1.06 - 8, cy + (y - cy) * 1.06 + 4);
    }
    const legend = [];
    for (const [k, c] of (opts.circles || []).entries()) {
      ctx.strokeStyle = c.color || '#9aa5b1';
      ctx.setLineDash([5, 4]);
      ctx.beginPath();
      ctx.arc(cx, cy, (c.r / rmax) * R, 0, 2 * Math.PI);
      ctx.stroke();
      ctx.setLineDash([]);
      if (c.label) legend.push({ label: c.label, color: c.color || '#9aa5b1' });
      void k;
    }
    traces.forEach((t, k) => {
      const color = t.color || PALETTE[k % PALETTE.length];
      ctx.strokeStyle = color;
      ctx.lineWidth = t.width || 1.5;
      ctx.beginPath();
      for (let i = 0; i < t.angle.length; i++) {
        const [x, y] = P(t.angle[i], t.r[i]);
        (i ? ctx.lineTo : ctx.moveTo).call(ctx, x, y);
      }
      ctx.stroke();
      if (t.label) legend.push({ label: t.label, color });
    });
    for (const mk of opts.markers || []) {
      const x = cx + (mk.x / rmax) * R;
      const y = cy - (mk.y / rmax) * R;
      ctx.fillStyle = mk.color || '#b3261e';
      ctx.beginPath();
      ctx.arc(x, y, 4, 0, 2 * Math.PI);
      ctx.fill();
      if (mk.label) ctx.fillText(mk.label, x + 6, y - 6);
    }
    ctx.restore();
    return legend;
  });
}

/** Vertical bars with category labels. */
export function barChart(el, opts) {
  return canvasChart(el, { height: 240, ...opts }, (ctx, w, hgt) => {
    const vals = Array.from(opts.values);
    const lo = Math.min(0, ...vals);
    const hi = Math.max(0, ...vals) || 1;
    const { X, Y, m, pw } = axesBox(ctx, w, hgt, [0, vals.length], [lo, hi + (hi - lo) * 0.05], { ...opts, equal: false, noXTicks: true });
    const bw = (pw / Math.max(1, vals.length)) * 0.7;
    vals.forEach((v, i) => {
      ctx.fillStyle = opts.color || PALETTE[0];
      const x = X(i + 0.5) - bw / 2;
      ctx.fillRect(x, Math.min(Y(0), Y(v)), bw, Math.abs(Y(v) - Y(0)));
      ctx.fillStyle = '#5b6673';
      ctx.fillText(String(opts.labels?.[i] ?? i), x, hgt - m.b + 26);
    });
    return [];
  });
}

/**
 * 3D path on a canvas: orthographic projection, equal scale on x, y and z
 * (fixed by the bounding sphere, so rotating never rescales), drag to rotate,
 * axes triad in the lower-left corner.
 * opts: { title, traces: [{ x, y, z, label, color?, width? }], height? }.
 */
export function xyzChart(el, opts) {
  const view = { az: (-35 * Math.PI) / 180, el: (25 * Math.PI) / 180 };
  let canvas;
  let ctx;
  let w = 0;
  let hgt = 0;
  const project = (x, y, z) => {
    const ca = Math.cos(view.az), sa = Math.sin(view.az), ce = Math.cos(view.el), se = Math.sin(view.el);
    const x1 = x * ca - y * sa;
    const y1 = x * sa + y * ca;
    return [x1, z * ce + y1 * se];
  };
  const draw = () => {
    const traces = opts.traces || [];
    ctx.clearRect(0, 0, w, hgt);
    // Centre and radius of the bounding box: one scale for all three axes.
    const lo = [Infinity, Infinity, Infinity];
    const hi = [-Infinity, -Infinity, -Infinity];
    for (const t of traces) {
      [t.x, t.y, t.z].forEach((a, k) => {
        for (const v of a) if (Number.isFinite(v)) [lo[k], hi[k]] = [Math.min(lo[k], v), Math.max(hi[k], v)];
      });
    }
    if (!Number.isFinite(lo[0])) return;
    const c = lo.map((l, k) => (l + hi[k]) / 2);
    const r = Math.hypot(...lo.map((l, k) => (hi[k] - l) / 2)) || 1;
    const s = (0.45 * Math.min(w, hgt)) / r;
    const P = (x, y, z) => {
      const [u, v] = project(x - c[0], y - c[1], z - c[2]);
      return [w / 2 + s * u, hgt / 2 - s * v];
    };
    traces.forEach((t, k) => {
      ctx.strokeStyle = t.color || PALETTE[k % PALETTE.length];
      ctx.lineWidth = t.width || 1.5;
      ctx.beginPath();
      for (let i = 0; i < t.x.length; i++) (i ? ctx.lineTo : ctx.moveTo).apply(ctx, P(t.x[i], t.y[i], t.z[i]));
      ctx.stroke();
    });
    // Axes triad: unit vectors of the data frame, 28 px long.
    const o = [36, hgt - 36];
    [['x', [1, 0, 0], '#d9480f'], ['y', [0, 1, 0], '#2b8a3e'], ['z', [0, 0, 1], '#0b6bcb']].forEach(([name, e, col]) => {
      const [u, v] = project(...e);
      const tip = [o[0] + 28 * u, o[1] - 28 * v];
      ctx.strokeStyle = col;
      ctx.fillStyle = col;
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(...o);
      ctx.lineTo(...tip);
      ctx.stroke();
      ctx.fillText(name, tip[0] + 3 * Math.sign(u || 1), tip[1] - 3 * Math.sign(v || 1));
    });
    ctx.fillStyle = '#5b6673';
    ctx.fillText(`equal scale; ${tick(2 * r)} mm across — drag to rotate`, 8, 14);
  };
  const paint = () => {
    frame(el, opts.title);
    canvas = document.createElement('canvas');
    canvas.style.cursor = 'grab';
    canvas.style.touchAction = 'none';
    el.append(canvas);
    w = Math.max(200, el.clientWidth || 400);
    hgt = opts.height || Math.min(420, Math.max(240, w * 0.75));
    const dpr = window.devicePixelRatio || 1;
    canvas.width = w * dpr;
    canvas.height = hgt * dpr;
    canvas.style.height = `${hgt}px`;
    ctx = canvas.getContext('2d');
    ctx.scale(dpr, dpr);
    ctx.font = '11px system-ui';
    let last = null;
    canvas.addEventListener('pointerdown', (e) => {
      last = [e.clientX, e.clientY];
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!last) return;
      view.az += (e.clientX - last[0]) * 0.01;
      view.el = Math.max(-Math.PI / 2, Math.min(Math.PI / 2, view.el + (e.clientY - last[1]) * 0.01));
      last = [e.clientX, e.clientY];
      draw();
    });
    canvas.addEventListener('pointerup', () => (last = null));
    draw();
    const legend = (opts.traces || []).filter((t) => t.label);
    if (legend.length) {
      const lg = Object.assign(document.createElement('div'), { className: 'legend' });
      legend.forEach((t) => {
        const sw = document.createElement('i');
        sw.style.background = t.color || PALETTE[(opts.traces || []).indexOf(t) % PALETTE.length];
        const item = document.createElement('span');
        item.append(sw, t.label);
        lg.append(item);
      });
      el.append(lg);
    }
  };
  paint();
  return {
    el,
    update(o) {
      Object.assign(opts, o);
      paint();
    },
  };
}
