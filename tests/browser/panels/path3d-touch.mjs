// Touch in the 3D path view, on a phone-sized page with a touch screen:
// real touch input through CDP (Input.dispatchTouchEvent, which Chromium
// turns into touch and pointer events as a finger would). One finger
// dragged across the view orbits the camera: it turns (its orientation,
// which for the flat example seen from above is mostly a turn about the
// vertical); its distance from the target, the target and the zoom stay.
// Two fingers spread apart about a point of the path zoom in about it:
// the orthographic camera's zoom grows by about the ratio of the fingers'
// distances (OrbitControls' dolly) and that point stays under the
// fingers (zoom to cursor; three.js r187 took the fingers' page
// coordinates for client ones and zoomed towards a point as far below
// them as the page was scrolled: path3d.js corrects it). Pinched together
// they zoom out again; the page does not scroll under the gestures and
// no gesture selects a line.
export default async function (page, check) {
  const ctx = await page.context().browser().newContext({ viewport: { width: 390, height: 844 }, deviceScaleFactor: 2, isMobile: true, hasTouch: true });
  try {
    const p = await ctx.newPage();
    const problems = [];
    p.on('pageerror', (e) => problems.push(e.message));
    await p.goto(page.url());
    await p.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 90_000 });
    await p.click('[data-tab="toolpath"]');
    await p.click('#toolpath-run');
    await p.waitForSelector('#toolpath-path3d .path3d-mark[data-rank="1"]', { timeout: 60_000 });
    await p.waitForFunction(() => document.querySelector('#toolpath-path3d').pathView.state().frames > 0);
    const canvas = await p.$('#toolpath-path3d canvas');
    await canvas.scrollIntoViewIfNeeded();
    const b = await canvas.boundingBox();
    const cx = b.x + b.width / 2;
    const cy = b.y + b.height / 2;
    const camera = () => p.evaluate(() => {
      const v = /** @type {any} */ (document.querySelector('#toolpath-path3d')).pathView;
      const pos = v.camera.position.clone().sub(v.controls.target);
      return { dir: pos.clone().normalize().toArray(), quat: v.camera.quaternion.toArray(), dist: pos.length(), target: v.controls.target.toArray(), zoom: v.camera.zoom, scrollY: window.scrollY, picked: v.el.dataset.pickedLine ?? null };
    });
    const cdp = await ctx.newCDPSession(p);
    /** One touch event with the fingers at `points` ([x, y] each; none for the end). */
    const touch = (type, points) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: points.map(([x, y], i) => ({ x, y, id: i + 1 })) });
    const settle = () => p.waitForTimeout(250);

    // One finger: orbit.
    const before = await camera();
    await touch('touchStart', [[cx, cy]]);
    for (let s = 1; s <= 8; s++) await touch('touchMove', [[cx + 10 * s, cy - 4 * s]]);
    await touch('touchEnd', []);
    await settle();
    const orbited = await camera();
    // The angle between the two orientations (unit quaternions).
    const turned = 2 * Math.acos(Math.min(1, Math.abs(before.quat.reduce((a, x, i) => a + x * orbited.quat[i], 0)))) * 180 / Math.PI;
    const same = (a, c, tol) => a.every((x, i) => Math.abs(x - c[i]) <= tol);
    check(turned > 5 && Math.abs(orbited.dist - before.dist) < 1e-6 * before.dist && same(orbited.target, before.target, 1e-9) && orbited.zoom === before.zoom,
      `a one-finger drag should orbit: turned ${turned.toFixed(1)}°, distance ${before.dist} → ${orbited.dist}, target ${before.target} → ${orbited.target}, zoom ${before.zoom} → ${orbited.zoom}`);

    // The point of the pinch: the middle of a worst spot's line that is
    // away from the centre and the edges of the view.
    const lines = await p.$$eval('.path3d-mark', (bs) => bs.map((m) => Number(/** @type {HTMLElement} */ (m).dataset.line)));
    const screenOfLine = (n) => p.evaluate((l) => /** @type {any} */ (document.querySelector('#toolpath-path3d')).pathView.screenOfLine(l), n);
    let line = 0;
    let at = [cx, cy];
    for (const n of lines) {
      const q = await screenOfLine(n);
      if (q && Math.abs(q[0] - cx) < b.width / 4 && Math.abs(q[1] - cy) < b.height / 4 && Math.hypot(q[0] - cx, q[1] - cy) > 20) {
        line = n;
        at = q;
        break;
      }
    }
    check(line > 0, `a worst spot's line should lie off the centre of the view, in its middle half (lines ${lines})`);
    // Two fingers spread from 40 px apart to 200 px: zoom in about ×5.
    const pinch = async (from, to) => {
      await touch('touchStart', [[at[0] - from / 2, at[1]], [at[0] + from / 2, at[1]]]);
      for (let s = 1; s <= 8; s++) {
        const d = from + ((to - from) * s) / 8;
        await touch('touchMove', [[at[0] - d / 2, at[1]], [at[0] + d / 2, at[1]]]);
      }
      await touch('touchEnd', []);
      await settle();
      return camera();
    };
    const spread = await pinch(40, 200);
    const ratio = spread.zoom / orbited.zoom;
    check(ratio > 3 && ratio < 7 && same(spread.dir, orbited.dir, 1e-6), `spreading two fingers ×5 should zoom in about ×5 without turning: zoom ×${ratio.toFixed(2)}, direction ${orbited.dir} → ${spread.dir}`);
    const after = line ? await screenOfLine(line) : at;
    const moved = Math.hypot(after[0] - at[0], after[1] - at[1]);
    check(moved < 3, `the pinched point (line ${line}) should stay under the fingers: it moved ${moved.toFixed(1)} px, from ${at.map((v) => v.toFixed(0))} to ${after.map((v) => v.toFixed(0))}`);
    const pinched = await pinch(200, 40);
    check(pinched.zoom < spread.zoom / 3, `pinching two fingers together should zoom out again: ${spread.zoom} → ${pinched.zoom}`);
    check(pinched.scrollY === before.scrollY, `the page should not scroll under the gestures: scrollY ${before.scrollY} → ${pinched.scrollY}`);
    check(pinched.picked === null, `no gesture should select a line (picked ${pinched.picked})`);
    check(problems.length === 0, `page errors: ${problems.join('; ')}`);
  } finally {
    await ctx.close();
  }
}
