// The 3D tool-path view (WebGL through three.js): the programmed path and
// the simulated path, coloured by contour error on cutting moves (samples
// on rapids dimmed, hidden with the rapids), with orbit, pan and zoom
// (OrbitControls: mouse, touch, keys), the worst spots marked, picking and
// hover. Drawing only: every number (errors, their maximum, the worst
// segments, the segment each sample belongs to: sampleSegment) comes from
// the core's result; this file places, thins and colours what it draws.
//
// Thinning: the camera is orthographic, so one screen pixel is the same
// length everywhere in the scene (at a given zoom). A vertex closer than
// one pixel (in 3D, which bounds its on-screen distance under any
// rotation) to the last drawn vertex of its polyline is merged into it;
// a merged vertex keeps the largest error of the vertices it stands for,
// so no peak disappears; a sample on a rapid never merges with one on a
// cutting move. The drawn level is rebuilt when the zoom changes
// the pixel size by a factor of two.
import {
  WebGLRenderer, Scene, OrthographicCamera, BufferGeometry, BufferAttribute, LineSegments, LineBasicMaterial,
  Points, PointsMaterial, Vector3, OrbitControls, ColorManagement, LinearSRGBColorSpace,
} from '../vendor/three.js';

// Colours are drawn as given (the legend's CSS gradient uses the same
// numbers): no conversion to linear light and back.
ColorManagement.enabled = false;

/** @typedef {import('./pieces.js').ProgramPieces} ProgramPieces */

/** Colour ramp of the contour error, 0 … the scale's maximum. */
/** @type {[number, number[]][]} */
const RAMP = [[0, [0.12, 0.31, 0.82]], [0.35, [0.06, 0.63, 0.56]], [0.7, [0.94, 0.55, 0.0]], [1, [0.78, 0.06, 0.18]]];
const CSS_RAMP = `linear-gradient(to right, ${RAMP.map(([f, c]) => `rgb(${c.map((v) => Math.round(v * 255)).join(',')}) ${f * 100}%`).join(', ')})`;
const PROGRAM_RGB = [0.35, 0.38, 0.42];
const RAPID_RGB = [0.8, 0.82, 0.85];
/** The simulated path on rapids: dimmed, off the error scale. */
const SIM_RAPID_RGB = [0.66, 0.72, 0.86];
const HIGHLIGHT = 0xd6336c;
/** Screen distance (px) within which the cursor picks. */
const PICK_PX = 8;

function ramp(f, out, o) {
  const x = f <= 0 ? 0 : f >= 1 ? 1 : f;
  let i = 1;
  while (i < RAMP.length - 1 && RAMP[i][0] < x) i++;
  const [f0, c0] = RAMP[i - 1];
  const [f1, c1] = RAMP[i];
  const u = (x - f0) / (f1 - f0);
  out[o] = c0[0] + u * (c1[0] - c0[0]);
  out[o + 1] = c0[1] + u * (c1[1] - c0[1]);
  out[o + 2] = c0[2] + u * (c1[2] - c0[2]);
}

/**
 * @typedef {object} SimulatedPath the core's simulated series (ToolPathSimulation)
 * @property {Float64Array} t
 * @property {Float64Array} nearX @property {Float64Array} nearY @property {Float64Array} nearZ
 * @property {Float64Array} simX @property {Float64Array} simY @property {Float64Array} simZ
 * @property {Float64Array} [velSimX] @property {Float64Array} [velSimY] @property {Float64Array} [velSimZ]
 * @property {Float64Array} errorUm
 * @property {Uint32Array} sampleSegment per sample, its segment (index into the program's segments)
 * @property {import('../pkg/mtmotion.js').SegmentStats[]} [segments]
 */
/**
 * @typedef {object} Mark one worst spot: rank, its line, error µm and where it is drawn (mm)
 * @property {number} rank @property {number} line @property {number} errorUm @property {number[]} at
 */

/**
 * A 3D path view in `parent`. `onPick(line)`: the user clicked the path
 * or a mark (its source line). `prefix` starts the ids of the view and its
 * controls (`${prefix}-path3d`, `${prefix}-show-rapids`, …).
 * @param {{ onPick?: (line: number) => void, onMagnification?: (k: number) => void, height?: number, prefix?: string }} [options]
 */
export function pathView({ onPick, onMagnification, height = 460, prefix = 'toolpath' } = {}) {
  const el = document.createElement('div');
  el.className = 'path3d';
  el.id = `${prefix}-path3d`;
  el.dataset.display = '';
  const bar = document.createElement('div');
  bar.className = 'path3d-bar';
  const toggle = (label, id, on) => {
    const box = Object.assign(document.createElement('input'), { type: 'checkbox', checked: on, id });
    const l = document.createElement('label');
    l.append(box, ` ${label}`);
    bar.append(l);
    return box;
  };
  const showProgram = toggle('programmed path', `${prefix}-show-program`, true);
  const showRapids = toggle('rapids', `${prefix}-show-rapids`, true);
  const showSim = toggle('simulated path', `${prefix}-show-sim`, true);
  const reset = Object.assign(document.createElement('button'), { type: 'button', textContent: 'Reset view', id: `${prefix}-view-reset` });
  bar.append(reset);
  const legend = document.createElement('div');
  legend.className = 'path3d-legend';
  const stage = document.createElement('div');
  stage.className = 'path3d-stage';
  stage.style.height = `${height}px`;
  const canvas = document.createElement('canvas');
  canvas.tabIndex = 0;
  canvas.setAttribute('aria-label', 'Tool path in 3D: drag to orbit, right-drag or shift-drag to pan, wheel or pinch to zoom; arrow keys pan, shift+arrows orbit, + and − zoom, 0 resets');
  const tip = document.createElement('div');
  tip.className = 'path3d-tip';
  tip.hidden = true;
  const labels = document.createElement('div');
  labels.className = 'path3d-labels';
  stage.append(canvas, labels, tip);
  const hint = document.createElement('p');
  hint.className = 'chart-hint';
  hint.textContent = 'Drag to orbit, right-drag or shift-drag to pan, wheel or pinch to zoom, double-click to reset; keys: arrows pan, shift+arrows orbit, + − zoom, 0 resets. Click the path to select its line.';
  el.append(bar, legend, stage, hint);

  let renderer;
  try {
    renderer = new WebGLRenderer({ canvas, antialias: false, powerPreference: 'high-performance' });
  } catch (e) {
    stage.replaceChildren(Object.assign(document.createElement('p'), { className: 'error-box', textContent: `This browser cannot draw the 3D path (WebGL is not available: ${e.message}).` }));
    return { el, show() {}, highlightLine() {}, setMagnification() {}, autoMagnification: () => 1, render() {}, state: () => ({}) };
  }
  renderer.setPixelRatio(1);
  renderer.outputColorSpace = LinearSRGBColorSpace;
  renderer.setClearColor(0xfbfbfd);
  const scene = new Scene();
  const camera = new OrthographicCamera(-1, 1, 1, -1, -1000, 1000);
  camera.up.set(0, 0, 1);
  const controls = new OrbitControls(camera, canvas);
  controls.enableDamping = false;
  controls.zoomToCursor = true;
  controls.listenToKeyEvents(canvas);
  controls.keyPanSpeed = 20;
  // three.js r187's OrbitControls gives its zoom-to-cursor step a pinch's
  // centre in page coordinates (pageX/pageY) and measures it against the
  // canvas's client rectangle (the wheel gives clientX/clientY): on a
  // scrolled page (a phone, the view below the fold) a pinch zoomed
  // towards a point as far below the fingers as the page was scrolled, and
  // the path flew out of view. While fingers are down, the point is moved
  // to client coordinates. (Test: path3d-touch.mjs.)
  const touching = new Set();
  canvas.addEventListener('pointerdown', (e) => e.pointerType === 'touch' && touching.add(e.pointerId), true);
  /** @param {PointerEvent} e */
  const lift = (e) => touching.delete(e.pointerId);
  window.addEventListener('pointerup', lift, true);
  window.addEventListener('pointercancel', lift, true);
  const zoomAt = /** @type {any} */ (controls)._updateZoomParameters;
  if (typeof zoomAt === 'function') {
    /** @type {any} */ (controls)._updateZoomParameters = (x, y) => (touching.size ? zoomAt.call(controls, x - window.scrollX, y - window.scrollY) : zoomAt.call(controls, x, y));
  }

  const progMat = new LineBasicMaterial({ vertexColors: true });
  const simMat = new LineBasicMaterial({ vertexColors: true });
  const hiMat = new LineBasicMaterial({ color: HIGHLIGHT });
  const hiDots = new PointsMaterial({ color: HIGHLIGHT, size: 9, sizeAttenuation: false });
  const markMat = new PointsMaterial({ color: 0xc8102e, size: 8, sizeAttenuation: false });
  const progObj = new LineSegments(new BufferGeometry(), progMat);
  // Pairs of drawn samples (an index buffer): the path breaks where the
  // samples of hidden rapids are left out.
  const simObj = new LineSegments(new BufferGeometry(), simMat);
  // The point clouds drawn while the camera moves (see MOVING_POINTS).
  const cloudMat = new PointsMaterial({ vertexColors: true, size: 2, sizeAttenuation: false });
  const progMove = new Points(new BufferGeometry(), cloudMat);
  const simMove = new Points(new BufferGeometry(), cloudMat);
  progMove.visible = false;
  simMove.visible = false;
  const hiObj = new LineSegments(new BufferGeometry(), hiMat);
  const hiPts = new Points(new BufferGeometry(), hiDots);
  const markObj = new Points(new BufferGeometry(), markMat);
  for (const o of [progObj, simObj, progMove, simMove, hiObj, hiPts, markObj]) {
    o.frustumCulled = false;
    scene.add(o);
  }
  hiObj.renderOrder = 4;
  hiPts.renderOrder = 4;
  markObj.renderOrder = 3;
  // The shaders are compiled once, while the page is idle: the first draw
  // of a large result (cameo) otherwise spent ~0.1 s compiling them.
  (window.requestIdleCallback ?? setTimeout)(() => renderer.compile(scene, camera));
  hiMat.depthTest = false;
  hiDots.depthTest = false;
  markMat.depthTest = false;

  /** @type {ProgramPieces | null} */
  let prog = null;
  /** @type {SimulatedPath | null} */
  let sim = null;
  /** @type {Mark[]} */
  let marks = [];
  // Per segment of the program (the index sampleSegment gives): its line,
  // rapid or not, programmed feed (mm/min; NaN unknown).
  /** @type {Int32Array} */
  let segLine = new Int32Array(0);
  /** @type {Uint8Array} */
  let segRapid = new Uint8Array(0);
  /** @type {Float64Array} */
  let segFeed = new Float64Array(0);
  /** Whether sample i of the simulation is on a rapid (the core's mapping). */
  const rapidAt = (i) => segRapid[sim.sampleSegment[i]] === 1;
  let scaleUm = 1;
  let k = 1;
  let autoK = 1;
  const centre = [0, 0, 0];
  let radius = 1;
  let level = NaN;
  // The drawn (thinned) vertices, for picking: positions relative to the centre.
  let drawnProg = { pos: new Float32Array(0), seg: new Int32Array(0) };
  let drawnSim = { pos: new Float32Array(0), idx: new Int32Array(0) };
  let drawnSimRapids = 0;
  let drawnSimPieces = 0;
  let highlighted = 0;
  let picked = 0;
  let frames = 0;

  /** The simulated point i as drawn: near + k·(sim − near), its deviation at most the scale's maximum. */
  const dmax = () => scaleUm / 1e3;
  function simPoint(i, out, o) {
    const s = sim;
    let dx = s.simX[i] - s.nearX[i];
    let dy = s.simY[i] - s.nearY[i];
    let dz = s.simZ[i] - s.nearZ[i];
    const d = Math.sqrt(dx * dx + dy * dy + dz * dz);
    const lim = dmax();
    if (d > lim && d > 0) {
      const f = lim / d;
      dx *= f;
      dy *= f;
      dz *= f;
    }
    out[o] = s.nearX[i] + k * dx - centre[0];
    out[o + 1] = s.nearY[i] + k * dy - centre[1];
    out[o + 2] = s.nearZ[i] + k * dz - centre[2];
  }

  const sizeOf = () => [canvas.clientWidth || 1, canvas.clientHeight || 1];
  /** World length of one (CSS) pixel at the current zoom. */
  const pixel = () => (camera.top - camera.bottom) / camera.zoom / sizeOf()[1];

  /** A new task (the page answers input between chunks of a build). */
  const tick = () => new Promise((r) => setTimeout(r, 0));
  /** Longest stretch of building between two ticks, ms. */
  const SLICE_MS = 25;
  /** While the camera moves, a path drawn with more vertices than this is
   * drawn as a point cloud of at most about this many points each for the
   * program and the simulation: one per occupied cube of a 3D grid (the
   * vertex of largest error in it), made after each full level. A
   * sequential thinning cannot go below two vertices per raster row, and
   * in headless Chromium's software WebGL (SwiftShader) on a busy 2-core
   * machine a line cost ~2 µs whatever its length (1 M lines 0.4–0.9 s,
   * 15k 18–33 ms). At rest the full level (one pixel) is drawn again. */
  const MOVING_POINTS = 10_000;
  let gen = 0;
  let genMove = 0;
  let moveReady = false;
  let moving = false;

  /** Rebuilds the drawn (thinned) geometry for a pixel of `px` mm, in
   * slices of SLICE_MS; a newer build or new data stops it. `coarse`: the
   * level drawn while the camera moves (after a full one, which cancels it). */
  async function build(px) {
    const my = ++gen;
    genMove++;
    moveReady = false;
    const stale = () => my !== gen;
    const [progTo, simTo] = [progObj, simObj];
    let t0 = performance.now();
    const px2 = px * px;
    // Programmed path: chains of touching pieces, merged below a pixel
    // (a rapid never merges with a cutting move).
    if (prog) {
      const src = prog.pos;
      const n = prog.seg.length;
      const pos = new Float32Array(n * 6);
      const col = new Float32Array(n * 6);
      const seg = new Int32Array(n);
      let m = 0;
      let sx = 0, sy = 0, sz = 0, ex = 0, ey = 0, ez = 0, open = false, fresh = true, oseg = 0;
      const emit = () => {
        const r = prog.rapid[oseg];
        if (r && !showRapids.checked) return;
        const c = r ? RAPID_RGB : PROGRAM_RGB;
        pos[m * 6] = sx - centre[0]; pos[m * 6 + 1] = sy - centre[1]; pos[m * 6 + 2] = sz - centre[2];
        pos[m * 6 + 3] = ex - centre[0]; pos[m * 6 + 4] = ey - centre[1]; pos[m * 6 + 5] = ez - centre[2];
        col.set(c, m * 6);
        col.set(c, m * 6 + 3);
        seg[m++] = oseg;
      };
      for (let i = 0; i < n; i++) {
        if (!(i & 4095) && performance.now() - t0 > SLICE_MS) {
          await tick();
          if (stale()) return;
          t0 = performance.now();
        }
        const o = i * 6;
        const g = prog.seg[i];
        const joins = open && prog.rapid[g] === prog.rapid[oseg] && src[o] === ex && src[o + 1] === ey && src[o + 2] === ez;
        if (!joins) {
          if (open && !fresh) emit();
          sx = src[o]; sy = src[o + 1]; sz = src[o + 2];
          open = true;
          fresh = true;
        }
        if (fresh) {
          oseg = g;
          fresh = false;
        }
        ex = src[o + 3]; ey = src[o + 4]; ez = src[o + 5];
        if ((ex - sx) ** 2 + (ey - sy) ** 2 + (ez - sz) ** 2 >= px2) {
          emit();
          sx = ex; sy = ey; sz = ez;
          fresh = true;
        }
      }
      if (open && !fresh) emit();
      drawnProg = { pos: pos.subarray(0, m * 6), seg: seg.subarray(0, m) };
      const g = new BufferGeometry();
      g.setAttribute('position', new BufferAttribute(pos.subarray(0, m * 6), 3));
      g.setAttribute('color', new BufferAttribute(col.subarray(0, m * 6), 3));
      progTo.geometry.dispose();
      progTo.geometry = g;
    }
    if (sim) {
      const n = sim.errorUm.length;
      const pos = new Float32Array(n * 3);
      const col = new Float32Array(n * 3);
      const idx = new Int32Array(n);
      const pairs = new Uint32Array(2 * n);
      const p = [0, 0, 0];
      let m = 0;
      let q = 0;
      let worst = -1;
      // A break before the next drawn vertex (start, or hidden samples).
      let gap = true;
      let lastRapid = false;
      let rapids = 0;
      const hide = !showRapids.checked;
      for (let i = 0; i < n; i++) {
        if (!(i & 4095) && performance.now() - t0 > SLICE_MS) {
          await tick();
          if (stale()) return;
          t0 = performance.now();
        }
        const r = rapidAt(i);
        if (r && hide) {
          gap = true;
          continue;
        }
        simPoint(i, p, 0);
        if (!gap && r === lastRapid && i < n - 1) {
          const o = (m - 1) * 3;
          const d2 = (p[0] - pos[o]) ** 2 + (p[1] - pos[o + 1]) ** 2 + (p[2] - pos[o + 2]) ** 2;
          if (d2 < px2) {
            if (worst < 0 || sim.errorUm[i] > sim.errorUm[worst]) worst = i;
            continue;
          }
        }
        if (worst >= 0 && sim.errorUm[worst] > sim.errorUm[idx[m - 1]]) {
          // The merged run's peak stands for the last drawn vertex (and
          // colours it, on a cutting move).
          idx[m - 1] = worst;
          if (!lastRapid) ramp(sim.errorUm[worst] / scaleUm, col, (m - 1) * 3);
        }
        worst = -1;
        pos[m * 3] = p[0]; pos[m * 3 + 1] = p[1]; pos[m * 3 + 2] = p[2];
        if (r) {
          col.set(SIM_RAPID_RGB, m * 3);
          rapids++;
        } else ramp(sim.errorUm[i] / scaleUm, col, m * 3);
        if (!gap) {
          pairs[q++] = m - 1;
          pairs[q++] = m;
        }
        idx[m++] = i;
        gap = false;
        lastRapid = r;
      }
      drawnSim = { pos: pos.subarray(0, m * 3), idx: idx.subarray(0, m) };
      drawnSimRapids = rapids;
      drawnSimPieces = q / 2;
      const g = new BufferGeometry();
      g.setAttribute('position', new BufferAttribute(pos.subarray(0, m * 3), 3));
      g.setAttribute('color', new BufferAttribute(col.subarray(0, m * 3), 3));
      g.setIndex(new BufferAttribute(pairs.subarray(0, q), 1));
      simTo.geometry.dispose();
      simTo.geometry = g;
    }
    el.dataset.drawnProgram = String(drawnProg.seg.length);
    el.dataset.drawnSimulated = String(drawnSim.idx.length);
    requestRender();
    if (drawnProg.seg.length > MOVING_POINTS || drawnSim.idx.length > MOVING_POINTS) buildClouds();
  }
  let movingCounts = [0, 0];

  /** One point per occupied grid cube of the drawn vertices `pos` (stride
   * `step` floats, the first three a position), the cube's edge grown until
   * at most MOVING_POINTS are left; `weight(i)` picks the cube's vertex
   * (the largest), `colour(i, out, o)` colours it. Null when stale. */
  async function cloud(pos, step, weight, colour, my) {
    const n = Math.floor(pos.length / step);
    let edge = (2 * radius) / Math.sqrt(MOVING_POINTS);
    let t0 = performance.now();
    for (;;) {
      const cells = new Map();
      for (let i = 0; i < n; i++) {
        if (!(i & 4095) && performance.now() - t0 > SLICE_MS) {
          await tick();
          if (my !== genMove) return null;
          t0 = performance.now();
        }
        const o = i * step;
        const key = Math.floor(pos[o] / edge + 65536) + 131072 * (Math.floor(pos[o + 1] / edge + 65536) + 131072 * Math.floor(pos[o + 2] / edge + 65536));
        const j = cells.get(key);
        if (j === undefined || weight(i) > weight(j)) cells.set(key, i);
      }
      if (cells.size > MOVING_POINTS * 1.5) {
        edge *= Math.sqrt(cells.size / MOVING_POINTS);
        continue;
      }
      const out = new Float32Array(cells.size * 3);
      const col = new Float32Array(cells.size * 3);
      let m = 0;
      for (const i of cells.values()) {
        out[m * 3] = pos[i * step]; out[m * 3 + 1] = pos[i * step + 1]; out[m * 3 + 2] = pos[i * step + 2];
        colour(i, col, m * 3);
        m++;
      }
      const g = new BufferGeometry();
      g.setAttribute('position', new BufferAttribute(out, 3));
      g.setAttribute('color', new BufferAttribute(col, 3));
      return g;
    }
  }

  /** The clouds drawn while the camera moves. */
  async function buildClouds() {
    const my = ++genMove;
    const grey = (_i, out, o) => out.set(PROGRAM_RGB, o);
    const pg = await cloud(drawnProg.pos, 6, () => 0, grey, my);
    if (!pg) return;
    const ds = drawnSim;
    // A rapid's sample gives way to a cutting move's in its cube.
    const weight = (i) => (rapidAt(ds.idx[i]) ? -1 : sim.errorUm[ds.idx[i]]);
    const colour = (i, out, o) => (rapidAt(ds.idx[i]) ? out.set(SIM_RAPID_RGB, o) : ramp(sim.errorUm[ds.idx[i]] / scaleUm, out, o));
    const sg = await cloud(ds.pos, 3, weight, colour, my);
    if (!sg) return;
    progMove.geometry.dispose();
    progMove.geometry = pg;
    simMove.geometry.dispose();
    simMove.geometry = sg;
    movingCounts = [pg.getAttribute('position').count, sg.getAttribute('position').count];
    moveReady = true;
  }

  /** Rebuilds when the pixel size left its power-of-two level. */
  let building = Promise.resolve();
  function rebuildIfNeeded(force = false) {
    const px = pixel();
    const l = Math.floor(Math.log2(px));
    if (!force && l === level) return building;
    level = l;
    building = build(2 ** l);
    return building;
  }

  function setPoints(obj, coords) {
    const g = new BufferGeometry();
    g.setAttribute('position', new BufferAttribute(new Float32Array(coords), 3));
    obj.geometry.dispose();
    obj.geometry = g;
  }

  const project = new Vector3();

  function placeLabels() {
    const [w, hgt] = sizeOf();
    // Labels of marks that fall together are set side by side.
    const placed = [];
    for (const b of labels.children) {
      const m = marks[Number(/** @type {HTMLElement} */ (b).dataset.index)];
      project.set(m.at[0] - centre[0], m.at[1] - centre[1], m.at[2] - centre[2]).project(camera);
      const x = ((project.x + 1) / 2) * w + 6;
      const y = ((1 - project.y) / 2) * hgt - 18;
      let y2 = y;
      while (placed.some(([px, py]) => Math.abs(px - x) < 22 && Math.abs(py - y2) < 15)) y2 -= 16;
      placed.push([x, y2]);
      /** @type {HTMLElement} */ (b).style.transform = `translate(${x}px, ${y2}px)`;
    }
  }

  let pending = 0;
  function render() {
    pending = 0;
    const coarse = moving && moveReady;

    progObj.visible = showProgram.checked && !coarse;
    simObj.visible = showSim.checked && !coarse;
    progMove.visible = showProgram.checked && coarse;
    simMove.visible = showSim.checked && coarse;
    renderer.render(scene, camera);
    placeLabels();
    frames++;
  }
  const requestRender = () => {
    if (!pending) pending = requestAnimationFrame(render);
  };
  let settle = 0;
  controls.addEventListener('change', () => {
    tip.hidden = true;
    moving = true;
    requestRender();
    clearTimeout(settle);
    settle = setTimeout(() => {
      moving = false;
      rebuildIfNeeded();
      requestRender();
    }, 150);
  });

  // Half extents of the path's box as seen from the reset view (mm).
  let seen = [1, 1];
  function resize() {
    const [w, hgt] = sizeOf();
    renderer.setSize(w, hgt, false);
    const aspect = w / hgt;
    const r = Math.max(seen[0] / aspect, seen[1]) * 1.08;
    camera.left = -r * aspect;
    camera.right = r * aspect;
    camera.top = r;
    camera.bottom = -r;
    camera.near = -radius * 20;
    camera.far = radius * 20;
    camera.updateProjectionMatrix();
    rebuildIfNeeded();
    requestRender();
  }
  new ResizeObserver(resize).observe(stage);

  // A flat path (Z range under 1 % of its size) is first seen from above,
  // any other from the front right, above.
  let half = [1, 1, 1];
  function resetView() {
    controls.target.set(0, 0, 0);
    const flat = half[2] < 0.01 * Math.max(half[0], half[1]);
    if (flat) camera.position.set(0, -1e-3, 1);
    else camera.position.set(0.55, -0.9, 0.75);
    camera.position.normalize().multiplyScalar(radius * 4);
    camera.zoom = 1;
    camera.lookAt(0, 0, 0);
    controls.update();
    camera.updateMatrixWorld();
    const inv = camera.matrixWorldInverse;
    seen = [1e-6, 1e-6];
    for (const sx of [-1, 1]) for (const sy of [-1, 1]) for (const sz of [-1, 1]) {
      project.set(sx * half[0], sy * half[1], sz * half[2]).applyMatrix4(inv);
      seen = [Math.max(seen[0], Math.abs(project.x)), Math.max(seen[1], Math.abs(project.y))];
    }
    resize();
  }
  reset.addEventListener('click', resetView);
  canvas.addEventListener('dblclick', resetView);
  canvas.addEventListener('keydown', (e) => {
    if (e.key === '+' || e.key === '=' || e.key === '-' || e.key === '_') {
      camera.zoom *= e.key === '+' || e.key === '=' ? 1.25 : 0.8;
      camera.updateProjectionMatrix();
      controls.dispatchEvent({ type: 'change' });
      e.preventDefault();
    } else if (e.key === '0') {
      resetView();
      e.preventDefault();
    }
  });
  for (const box of [showRapids]) box.addEventListener('change', () => rebuildIfNeeded(true));
  for (const box of [showProgram, showSim, showRapids]) box.addEventListener('change', requestRender);

  /** Screen coordinates (CSS px in the canvas) of the drawn point (x, y, z) relative to the centre. */
  function screenMatrix() {
    camera.updateMatrixWorld();
    const m = camera.projectionMatrix.clone().multiply(camera.matrixWorldInverse).elements;
    const [w, hgt] = sizeOf();
    return { m, w, hgt };
  }

  /**
   * What is under the cursor: the nearest, within PICK_PX, of the drawn
   * programmed pieces and simulated samples. A sample gives its segment
   * (the core's sampleSegment); a piece gives its segment and, for the
   * read-out, the nearest drawn sample of that same segment (none: -1).
   */
  function pickAt(cx, cy) {
    const { m, w, hgt } = screenMatrix();
    const sx = (x, y, z) => ((m[0] * x + m[4] * y + m[8] * z + m[12]) + 1) / 2 * w;
    const sy = (x, y, z) => (1 - (m[1] * x + m[5] * y + m[9] * z + m[13])) / 2 * hgt;
    let bestSeg = -1;
    let segD = PICK_PX * PICK_PX;
    if (prog && showProgram.checked) {
      const p = drawnProg.pos;
      for (let i = 0, n = drawnProg.seg.length; i < n; i++) {
        const o = i * 6;
        const ax = sx(p[o], p[o + 1], p[o + 2]), ay = sy(p[o], p[o + 1], p[o + 2]);
        const bx = sx(p[o + 3], p[o + 4], p[o + 5]), by = sy(p[o + 3], p[o + 4], p[o + 5]);
        const vx = bx - ax, vy = by - ay;
        const l2 = vx * vx + vy * vy;
        const u = l2 > 0 ? Math.max(0, Math.min(1, ((cx - ax) * vx + (cy - ay) * vy) / l2)) : 0;
        const d = (ax + u * vx - cx) ** 2 + (ay + u * vy - cy) ** 2;
        if (d < segD) {
          segD = d;
          bestSeg = drawnProg.seg[i];
        }
      }
    }
    /** The nearest drawn sample (of segment `only`, when given) within `limit²` px². */
    const nearestSample = (limit, only = -1) => {
      let best = -1;
      let bestD = limit;
      if (!sim || !showSim.checked) return [best, bestD];
      const p = drawnSim.pos;
      for (let i = 0, n = drawnSim.idx.length; i < n; i++) {
        if (only >= 0 && sim.sampleSegment[drawnSim.idx[i]] !== only) continue;
        const o = i * 3;
        const d = (sx(p[o], p[o + 1], p[o + 2]) - cx) ** 2 + (sy(p[o], p[o + 1], p[o + 2]) - cy) ** 2;
        if (d < bestD) {
          bestD = d;
          best = drawnSim.idx[i];
        }
      }
      return [best, bestD];
    };
    const [sample, sampleD] = nearestSample(PICK_PX * PICK_PX);
    if (sample >= 0 && (bestSeg < 0 || sampleD < segD)) return { segment: sim.sampleSegment[sample], sample };
    if (bestSeg < 0) return { segment: -1, sample: -1 };
    return { segment: bestSeg, sample: nearestSample(Infinity, bestSeg)[0] };
  }

  const fmtN = (x, d) => (Number.isFinite(x) ? x.toFixed(d) : '—');
  /** The read-out of a pick: the segment's line and programmed feed, and the sample's time, error and simulated speed. */
  function describe({ segment, sample }) {
    const parts = [];
    if (segment >= 0 && segment < segLine.length) {
      parts.push(`line ${segLine[segment]} (${segRapid[segment] ? 'rapid' : `F ${fmtN(segFeed[segment], 0)} mm/min`})`);
    }
    if (sample >= 0 && sim) {
      const s = sim;
      parts.push(`t ${fmtN(s.t[sample], 3)} s`, `error ${fmtN(s.errorUm[sample], 2)} µm${segRapid[segment] ? ' (rapid)' : ''}`);
      if (s.velSimX) parts.push(`speed ${fmtN(Math.hypot(s.velSimX[sample], s.velSimY[sample], s.velSimZ[sample]) * 60, 0)} mm/min (simulated)`);
    }
    return parts.join(' · ');
  }

  let down = null;
  canvas.addEventListener('pointerdown', (e) => {
    down = [e.clientX, e.clientY];
  });
  canvas.addEventListener('pointerup', (e) => {
    if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
    down = null;
    const r = canvas.getBoundingClientRect();
    const hit = pickAt(e.clientX - r.left, e.clientY - r.top);
    if (hit.segment >= 0 && hit.segment < segLine.length) {
      const line = segLine[hit.segment];
      picked = line;
      el.dataset.pickedLine = String(line);
      highlightLine(line);
      onPick?.(line);
    }
  });
  let hoverPending = 0;
  canvas.addEventListener('pointermove', (e) => {
    if (e.buttons || hoverPending) return;
    hoverPending = requestAnimationFrame(() => {
      hoverPending = 0;
      const r = canvas.getBoundingClientRect();
      const x = e.clientX - r.left, y = e.clientY - r.top;
      const text = describe(pickAt(x, y));
      tip.hidden = !text;
      if (text) {
        tip.textContent = text;
        tip.style.transform = `translate(${Math.min(x + 12, r.width - 260)}px, ${y + 14}px)`;
      }
    });
  });
  canvas.addEventListener('pointerleave', () => {
    tip.hidden = true;
  });

  /** Highlights the segment(s) of source line `n` (0: none). */
  function highlightLine(n) {
    highlighted = 0;
    const coords = [];
    if (prog && n > 0) {
      for (let g = 0; g < prog.line.length; g++) {
        if (prog.line[g] !== n) continue;
        highlighted = n;
        for (let i = prog.first[g]; i < prog.first[g + 1]; i++) {
          for (let j = 0; j < 6; j++) coords.push(prog.pos[i * 6 + j] - centre[j % 3]);
        }
      }
    }
    setPoints(hiObj, coords);
    setPoints(hiPts, coords);
    el.dataset.highlightLine = String(highlighted);
    requestRender();
    return highlighted > 0;
  }

  function legendText() {
    legend.replaceChildren();
    if (!sim) return;
    const bar2 = document.createElement('span');
    bar2.className = 'path3d-ramp';
    bar2.style.background = CSS_RAMP;
    const rapidKey = document.createElement('span');
    rapidKey.className = 'path3d-ramp path3d-rapid-key';
    rapidKey.title = 'the simulated path on rapids: one colour, off the error scale, its deviation drawn at most at the scale\'s maximum; hidden with the rapids';
    rapidKey.style.background = `rgb(${SIM_RAPID_RGB.map((v) => Math.round(v * 255)).join(',')})`;
    legend.append('contour error 0 ', bar2, ` ${fmtN(scaleUm, 2)} µm (scale: the largest error on cutting moves) · on rapids `, rapidKey, ` off the scale · simulated path: error ×${k}${k === autoK ? ' (automatic)' : ''}`);
  }

  /** The automatic magnification: the largest cutting-move error drawn as 2 % of the path's size, on a 1-2-5 step. */
  function autoMagnification() {
    const want = (0.02 * 2 * radius) / Math.max(dmax(), 1e-9);
    const e = 10 ** Math.floor(Math.log10(want));
    const step = [1, 2, 5, 10].filter((s) => s * e <= want).pop() * e;
    return Math.max(1, Math.min(1e6, Math.round(step)));
  }

  /**
   * Shows a program and its simulation.
   * @param {{ program?: ProgramPieces | null, sim?: SimulatedPath | null, scaleUm: number, marks?: Mark[] }} data
   *   scaleUm: the colour scale's maximum (the core's maximum over cutting moves)
   * @param {{ keepView?: boolean }} [options] keepView: another simulation
   *   of the same program (before/after a compensation): the camera and the
   *   magnification stay as they are
   */
  function show(data, { keepView = false } = {}) {
    prog = data.program ?? null;
    sim = data.sim ?? null;
    scaleUm = data.scaleUm > 0 ? data.scaleUm : 1;
    marks = data.marks ?? [];
    // The segments' lines, rapids and feeds: the programmed pieces' (the
    // core's parseNc segments), else the simulation's own statistics.
    if (prog) {
      segLine = prog.line;
      segRapid = prog.rapid;
      segFeed = prog.feed;
    } else {
      const stats = sim?.segments ?? [];
      const n = stats.reduce((a, g) => Math.max(a, g.segment + 1), 0);
      segLine = new Int32Array(n);
      segRapid = new Uint8Array(n);
      segFeed = new Float64Array(n).fill(NaN);
      for (const g of stats) {
        segLine[g.segment] = g.line;
        segRapid[g.segment] = g.kind === 'rapid' ? 1 : 0;
      }
    }
    // Bounds of the programmed path (else of the simulated one).
    const lo = [Infinity, Infinity, Infinity];
    const hi = [-Infinity, -Infinity, -Infinity];
    const grow = (x, y, z) => {
      if (x < lo[0]) lo[0] = x;
      if (x > hi[0]) hi[0] = x;
      if (y < lo[1]) lo[1] = y;
      if (y > hi[1]) hi[1] = y;
      if (z < lo[2]) lo[2] = z;
      if (z > hi[2]) hi[2] = z;
    };
    if (prog) for (let i = 0; i < prog.pos.length; i += 3) grow(prog.pos[i], prog.pos[i + 1], prog.pos[i + 2]);
    else if (sim) for (let i = 0; i < sim.nearX.length; i++) grow(sim.nearX[i], sim.nearY[i], sim.nearZ[i]);
    if (!(hi[0] >= lo[0])) lo.fill(0), hi.fill(1);
    for (let a = 0; a < 3; a++) centre[a] = (lo[a] + hi[a]) / 2;
    radius = Math.max(1e-3, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2);
    half = [0, 1, 2].map((a) => Math.max((hi[a] - lo[a]) / 2, radius * 1e-3));
    if (!keepView) {
      autoK = autoMagnification();
      k = autoK;
    }
    setPoints(markObj, marks.flatMap((m) => m.at.map((v, a) => v - centre[a])));
    labels.replaceChildren(...marks.map((m, i) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.className = 'path3d-mark';
      b.dataset.index = String(i);
      b.dataset.rank = String(m.rank);
      b.dataset.line = String(m.line);
      b.textContent = String(m.rank);
      b.title = `#${m.rank}: line ${m.line}, ${fmtN(m.errorUm, 2)} µm`;
      b.addEventListener('click', () => {
        highlightLine(m.line);
        onPick?.(m.line);
      });
      return b;
    }));
    highlightLine(0);
    level = NaN; // new data: rebuilt at the view's pixel size
    if (keepView) rebuildIfNeeded();
    else resetView();
    legendText();
    if (!keepView) onMagnification?.(k);
    return building;
  }

  /** Sets the simulated path's error magnification. */
  function setMagnification(v) {
    if (!(v > 0) || v === k) return;
    k = v;
    legendText();
    rebuildIfNeeded(true);
    requestRender();
  }

  const api = {
    el, show, highlightLine, setMagnification, render, controls, camera, scene, renderer,
    autoMagnification: () => autoK,
    /** Screen position (CSS px in the page) of model point (x, y, z) mm. */
    screenOf(x, y, z) {
      const r = canvas.getBoundingClientRect();
      project.set(x - centre[0], y - centre[1], z - centre[2]).project(camera);
      return [r.left + ((project.x + 1) / 2) * r.width, r.top + ((1 - project.y) / 2) * r.height];
    },
    /** Screen position (CSS px in the page) of the middle of line `n`'s first segment, or null. */
    screenOfLine(n) {
      if (!prog) return null;
      const g = prog.line.indexOf(n);
      if (g < 0 || prog.first[g + 1] === prog.first[g]) return null;
      const mid = (prog.first[g] + prog.first[g + 1] - 1) >> 1;
      const p = prog.pos;
      return api.screenOf((p[mid * 6] + p[mid * 6 + 3]) / 2, (p[mid * 6 + 1] + p[mid * 6 + 4]) / 2, (p[mid * 6 + 2] + p[mid * 6 + 5]) / 2);
    },
    /** Draws now and counts the pixels within 24 (of 255) of colour 0xRRGGBB (a check that something is drawn). */
    countPixels(rgb) {
      render();
      const gl = renderer.getContext();
      const w = gl.drawingBufferWidth, hgt = gl.drawingBufferHeight;
      const px = new Uint8Array(w * hgt * 4);
      gl.readPixels(0, 0, w, hgt, gl.RGBA, gl.UNSIGNED_BYTE, px);
      const c = [(rgb >> 16) & 255, (rgb >> 8) & 255, rgb & 255];
      let n = 0;
      for (let i = 0; i < px.length; i += 4) if (Math.abs(px[i] - c[0]) <= 24 && Math.abs(px[i + 1] - c[1]) <= 24 && Math.abs(px[i + 2] - c[2]) <= 24) n++;
      return n;
    },
    /** Screen position (CSS px in the page) of simulated sample `i` as drawn, or null when it is not a drawn vertex. */
    screenOfSample(i) {
      const j = drawnSim.idx.indexOf(i);
      if (j < 0) return null;
      const p = drawnSim.pos;
      return api.screenOf(p[j * 3] + centre[0], p[j * 3 + 1] + centre[1], p[j * 3 + 2] + centre[2]);
    },
    state: () => ({ highlighted, picked, k, autoK, frames, drawnProgram: drawnProg.seg.length, drawnSimulated: drawnSim.idx.length, drawnSimulatedRapids: drawnSimRapids, drawnSimulatedPieces: drawnSimPieces, level, moving, moveReady, movingPoints: moveReady ? movingCounts[0] + movingCounts[1] : null }),
  };
  // The view's handle on its element (the report draws it to an image; tests).
  /** @type {any} */ (el).pathView = api;
  return api;
}
