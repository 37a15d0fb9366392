// Tool-path panel, cutter compensation: a G41 D1 circle of radius 20 mm.
// Without a tool radius the summary says the simulated path is the
// programmed one and the warning is grouped under "cutter compensation";
// with "D1=2" in the tool-radii field it says the offset path uses 2 mm,
// and the cutting length is that of the offset path, computed here: the
// start-up and cancel lines of 18 mm and the circle of radius 18 mm.
export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  await page.waitForSelector('#toolpath-nc');
  await page.fill('#toolpath-radii', '');
  await page.fill('#toolpath-nc', 'G0 X0 Y0\nG41 D1 G1 X20 F400\nG3 X20 Y0 I-20 J0\nG40 G1 X0 Y0\nM30');
  await page.waitForSelector('#toolpath-cutter', { timeout: 30_000 });
  const before = await page.textContent('#toolpath-cutter');
  check(before.includes('G41 D1 (line 2)') && before.includes('programmed (un-offset) path'), `without a radius: '${before}'`);
  check((await page.textContent('#toolpath-check')).includes('cutter compensation (1)'), 'the warning is grouped as cutter compensation');
  await page.fill('#toolpath-radii', 'D1=2');
  await page.dispatchEvent('#toolpath-radii', 'change');
  await page.waitForFunction(() => document.querySelector('#toolpath-cutter')?.textContent.includes('tool radius 2'), null, { timeout: 30_000 });
  const row = await page.$$eval('#toolpath-check tr', (rows) => rows.map((r) => r.textContent).find((t) => t.startsWith('path length')) ?? '');
  const cutting = parseFloat(/\(([\d.]+) mm\)/.exec(row)?.[1] ?? 'NaN');
  const want = 18 + 2 * Math.PI * 18 + 18;
  check(Math.abs(cutting - want) < 1e-4, `cutting length of the offset path ${cutting} mm, expected ${want}`);
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-max-error', { timeout: 60_000 });
  await page.fill('#toolpath-radii', '');
  await page.dispatchEvent('#toolpath-radii', 'change');
}
