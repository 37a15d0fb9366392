// The documentation example: each calculator shows the value the JS API gives
// for its attributes, the host page's styles are untouched (shadow DOM), and
// all elements share one wasm instance.
export default async function (page, check, base) {
  await page.goto(`${base}embed-example.html`);
  const ids = ['calc-radius', 'calc-torque', 'calc-circularity', 'calc-bias'];
  await page.waitForFunction((ids) => ids.every((id) => document.getElementById(id)?.dataset.value), ids, { timeout: 30_000 });
  const shown = await page.evaluate((ids) => Object.fromEntries(ids.map((id) => [id, Number(document.getElementById(id).dataset.value)])), ids);
  const wasmLoads = await page.evaluate(() => performance.getEntriesByType('resource').filter((e) => e.name.endsWith('.wasm')).length);
  check(wasmLoads === 1, `all calculators share one wasm instance (wasm fetched ${wasmLoads} times)`);
  // Independent: the JS API in a fresh instance, with the attributes' values.
  const expected = await page.evaluate(async () => {
    const mt = await import('./pkg/mtmotion.js');
    await mt.default({ module_or_path: new URL('./pkg/mtmotion_bg.wasm', location.href) });
    const attr = (id, a) => Number(document.getElementById(id).getAttribute(a));
    const m = mt.machinePreset('nmv5000');
    const [sat] = mt.torqueSaturation(m, { j1: [attr('calc-torque', 'inertia') - m.axes.c.j], torqueMax: attr('calc-torque', 'torque-max'), accelTime: attr('calc-torque', 'accel-time'), feedAtCuttingPoint: attr('calc-torque', 'feed') });
    const ct = mt.circularTest(mt.parseBallbarTrace(document.getElementById('calc-circularity').textContent));
    const [sw] = mt.travelRangeSweep({ offset: { z: 0, x: 0 }, harmonics: [{ order: attr('calc-bias', 'order'), amplitude: attr('calc-bias', 'amplitude') / 1000, phase: 0 }], ranges: [attr('calc-bias', 'range')], radius: attr('calc-bias', 'radius'), samples: 1000 });
    return {
      'calc-radius': 1000 * mt.radiusReduction({ feed: attr('calc-radius', 'feed'), radius: attr('calc-radius', 'radius'), tA: attr('calc-radius', 'ta'), T: attr('calc-radius', 't') }),
      'calc-torque': sat.rcMin,
      'calc-circularity': Math.max(...ct.runs.map((r) => r.gUm)),
      'calc-bias': 1000 * Math.hypot(sw.errorZ, sw.errorX),
    };
  });
  for (const id of ids) check(Math.abs(shown[id] - expected[id]) <= 1e-9 * Math.max(1, Math.abs(expected[id])) && Number.isFinite(shown[id]), `${id} shows ${shown[id]}, the JS API gives ${expected[id]}`);
  // Eq. 3 by hand for the radius element: F = 2000 mm/min, R = 10 mm, tA = 0.064 s, T = 0.03 s.
  const w = 2000 / 60 / 10;
  const x = (0.064 * w) / 2;
  const eq3 = (1 - (Math.sin(x) / x) / Math.sqrt(0.03 ** 2 * w ** 2 + 1)) * 10 * 1000;
  check(Math.abs(shown['calc-radius'] - eq3) < 1e-9, `radius loss ${shown['calc-radius']} µm should equal Eq. 3 by hand, ${eq3} µm`);
  // Host styles untouched: the page's own inputs rule does not reach the shadow inputs, and vice versa.
  const styles = await page.evaluate(() => {
    const inner = document.getElementById('calc-radius').shadowRoot.querySelector('input');
    return { inner: getComputedStyle(inner).backgroundColor, body: getComputedStyle(document.body).fontFamily };
  });
  check(styles.inner !== 'rgb(255, 255, 221)', 'the host page style does not leak into the calculator');
  check(/Georgia/.test(styles.body), 'the calculators leave the host page font alone');
  // Editing an input updates the result live.
  await page.evaluate(() => {
    const input = document.getElementById('calc-radius').shadowRoot.querySelector('input[name="feed"]');
    input.value = '4000';
    input.dispatchEvent(new Event('input'));
  });
  await page.waitForFunction((old) => Number(document.getElementById('calc-radius').dataset.value) > old * 3, shown['calc-radius']);
}
