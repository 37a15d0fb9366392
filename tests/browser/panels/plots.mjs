// Plots: every chart shows its zoom hint; no title, legend, hint or axis
// label box lies outside its chart's box; the tool-path 3D view zooms with
// the wheel and a double-click restores it exactly; the Bode plots switch to Hz.
async function labelsOutside(page) {
  return page.evaluate(() => {
    const bad = [];
    for (const c of document.querySelectorAll('.chart')) {
      if (!c.offsetParent) continue;
      const box = c.getBoundingClientRect();
      for (const t of c.querySelectorAll('.chart-title, .legend span, .chart-hint, .u-label, .u-title')) {
        const r = t.getBoundingClientRect();
        if (!r.width) continue;
        if (r.left < box.left - 1 || r.right > box.right + 1 || r.top < box.top - 1 || r.bottom > box.bottom + 1) bad.push(`${t.className} "${t.textContent.slice(0, 40)}"`);
      }
    }
    return bad;
  });
}

export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  await page.click('#toolpath-run');
  // The path is a 3D view (lib/path3d.js): the wheel zooms the camera,
  // a double-click restores the view exactly.
  await page.waitForSelector('#toolpath-path3d canvas');
  const canvas = await page.$('#toolpath-path3d canvas');
  const cam = () => page.evaluate(() => {
    const v = /** @type {any} */ (document.querySelector('#toolpath-path3d')).pathView;
    return [v.camera.zoom, ...v.camera.position.toArray()].map((x) => x.toFixed(9)).join(' ');
  });
  const before = await cam();
  await canvas.scrollIntoViewIfNeeded();
  const b = await canvas.boundingBox();
  await page.mouse.move(b.x + b.width / 2, b.y + b.height / 2);
  await page.mouse.wheel(0, -300);
  await page.waitForTimeout(100);
  const zoomed = await cam();
  check(zoomed !== before, `the wheel should zoom the tool-path view (${before} → ${zoomed})`);
  await page.dblclick('#toolpath-path3d canvas');
  await page.waitForTimeout(100);
  check((await cam()) === before, 'a double-click should restore the unzoomed view');
  check(/wheel or pinch to zoom, double-click to reset/.test(await page.textContent('#toolpath-path')), 'the path view should say how to zoom');
  check(/drag to zoom, double-click to reset/.test(await page.textContent('#toolpath-velocity')), 'the velocity plot should say how to zoom');
  let out = await labelsOutside(page);
  check(out.length === 0, `tool path: labels outside their chart: ${out.join('; ')}`);

  await page.click('[data-tab="servo"]');
  await page.click('#servo-run');
  await page.waitForFunction(() => document.querySelectorAll('#servo-charts .uplot').length >= 6);
  // The torque chart shows its limit: ±torqueMax of the C axis is inside the visible range.
  const limit = Number(await page.inputValue('#servo-p-c-torqueMax'));
  const [yMin, yMax] = await page.$eval('#servo-torque-chart', (e) => [Number(e.dataset.yMin), Number(e.dataset.yMax)]);
  check(limit > 0 && yMin < -limit && yMax > limit, `servo: the torque chart's range ${yMin}…${yMax} N·m should include ±${limit} N·m`);
  await page.selectOption('#servo-bode-unit', 'hz');
  await page.waitForFunction(() => /f \[Hz\]/.test(document.querySelector('#servo-charts').textContent));
  out = await labelsOutside(page);
  check(out.length === 0, `servo: labels outside their chart: ${out.join('; ')}`);

  for (const tab of ['ballbar', 'kinematics']) {
    await page.click(`[data-tab="${tab}"]`);
    await page.waitForTimeout(200);
    out = await labelsOutside(page);
    check(out.length === 0, `${tab}: labels outside their chart: ${out.join('; ')}`);
  }
}
