// A generated path of 1,000,000 segments (a zig-zag raster of 1000 rows of
// 1000 pieces over a 100 × 100 mm bumped surface, like a finishing pass)
// and a simulated path of 1,000,000 samples are shown in the panel's 3D
// view, then rotated frame by frame: the median frame time (between
// animation frames, each rotating the camera 2° and drawing) must be at
// most 50 ms. Printed: that median, the median time of a draw forced to
// finish (render + a one-pixel read), and how many vertices the per-pixel
// thinning kept at rest and the size of the point cloud drawn while the
// camera moves. Headless Chromium draws WebGL with SwiftShader (software).
const LIMIT_MS = 50;

export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-path3d .path3d-mark', { timeout: 60_000 });
  const canvas = await page.$('#toolpath-path3d canvas');
  await canvas.scrollIntoViewIfNeeded();
  const shown = await page.evaluate(async () => {
    const v = /** @type {any} */ (document.querySelector('#toolpath-path3d')).pathView;
    const rows = 1000, cols = 1000, n = rows * cols;
    const surf = (x, y) => 5 * Math.sin(x / 10) * Math.cos(y / 12);
    // Program: piece i of row r goes along X (alternately), the last piece
    // of a row steps to the next row.
    const pos = new Float64Array(n * 6);
    const seg = new Int32Array(n);
    const pts = new Float64Array((n + 1) * 3);
    let k = 0;
    for (let r = 0; r < rows; r++) {
      for (let c = 0; c < cols; c++) {
        const x = r % 2 ? 100 - c * 0.1 : c * 0.1;
        const y = r * 0.1;
        pts.set([x, y, surf(x, y)], k++ * 3);
      }
    }
    pts.set(pts.subarray((n - 1) * 3, n * 3), n * 3);
    for (let i = 0; i < n; i++) {
      pos.set(pts.subarray(i * 3, i * 3 + 6), i * 6);
      seg[i] = i;
    }
    const first = new Int32Array(n + 1).map((_, i) => i);
    const program = { pos, seg, first, line: new Int32Array(n).map((_, i) => i + 1), rapid: new Uint8Array(n), feed: new Float64Array(n).fill(3000) };
    // Simulation: one sample per vertex (on its piece's segment), off the path by up to 20 µm.
    const sim = { t: new Float64Array(n), nearX: new Float64Array(n), nearY: new Float64Array(n), nearZ: new Float64Array(n), simX: new Float64Array(n), simY: new Float64Array(n), simZ: new Float64Array(n), errorUm: new Float64Array(n), sampleSegment: new Uint32Array(n).map((_, i) => i) };
    for (let i = 0; i < n; i++) {
      const [x, y, z] = pts.subarray(i * 3, i * 3 + 3);
      const e = 0.02 * Math.abs(Math.sin(i / 5000));
      sim.t[i] = i * 1e-3;
      sim.nearX[i] = x; sim.nearY[i] = y; sim.nearZ[i] = z;
      sim.simX[i] = x; sim.simY[i] = y + e; sim.simZ[i] = z;
      sim.errorUm[i] = e * 1e3;
    }
    const t0 = performance.now();
    await v.show({ program, sim, scaleUm: 20, marks: [] });
    const showMs = performance.now() - t0;
    // The coarser level for motion is made after the full one.
    while (!v.state().moveReady && performance.now() - t0 < 60_000) await new Promise((r) => setTimeout(r, 50));
    // A full-detail draw at rest, forced to finish.
    const gl = v.el.querySelector('canvas').getContext('webgl2');
    const t1 = performance.now();
    v.render();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    return { showMs, readyMs: performance.now() - t0, stillMs: performance.now() - t1, ...v.state() };
  });
  const measured = await page.evaluate(async () => {
    const v = /** @type {any} */ (document.querySelector('#toolpath-path3d')).pathView;
    const gl = v.el.querySelector('canvas').getContext('webgl2');
    const px = new Uint8Array(4);
    const step = (2 * Math.PI) / 180;
    const rotate = () => {
      const p = v.camera.position.clone().sub(v.controls.target);
      p.applyAxisAngle(v.camera.up, step);
      v.camera.position.copy(v.controls.target).add(p);
      v.controls.update();
    };
    // Forced draws: render, then a one-pixel read waits for the GPU (SwiftShader) to finish.
    const forced = [];
    for (let i = 0; i < 15; i++) {
      rotate();
      const t = performance.now();
      v.render();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      forced.push(performance.now() - t);
    }
    // Frames: each animation frame rotates 2° and draws.
    const stamps = [];
    await new Promise((done) => {
      const frame = (ts) => {
        stamps.push(ts);
        if (stamps.length > 61) return done();
        rotate();
        v.render();
        requestAnimationFrame(frame);
      };
      requestAnimationFrame(frame);
    });
    const med = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
    const gaps = stamps.slice(1).map((s, i) => s - stamps[i]);
    return { median: med(gaps), max: Math.max(...gaps), forced: med(forced), state: v.state() };
  });
  console.log(`  1 M segments: shown in ${shown.showMs.toFixed(0)} ms (motion level ready at ${shown.readyMs.toFixed(0)} ms); at rest, per-pixel thinning draws ${shown.drawnProgram} program pieces and ${shown.drawnSimulated} simulated vertices (of 1,000,000 each), a forced full draw took ${shown.stillMs.toFixed(0)} ms; while rotating, a point cloud of ${shown.movingPoints} points: median frame ${measured.median.toFixed(1)} ms (max ${measured.max.toFixed(1)} ms), median forced draw ${measured.forced.toFixed(1)} ms`);
  check(shown.moveReady, 'the motion level of the 1 M-segment path was made');
  check(measured.state.drawnProgram > 10_000 && measured.state.drawnSimulated > 10_000, `the generated path is drawn: ${JSON.stringify(measured.state)}`);
  check(measured.median <= LIMIT_MS, `a 1 M-segment path should rotate at a median frame time ≤ ${LIMIT_MS} ms; measured ${measured.median.toFixed(1)} ms`);
}
